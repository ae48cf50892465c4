"""Malformed results files give errors that name the file, the line and the column."""

import contextlib
import io
import json
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder, write_parent_weights
from phdslam_reports.csv_table import ResultsFormatError, read_csv
from phdslam_reports.report import build_report

import make_report
import tables


def replace_line(path: Path, index: int, old: str, new: str) -> None:
    lines = path.read_text().splitlines()
    lines[index] = lines[index].replace(old, new, 1)
    path.write_text("\n".join(lines) + "\n")


class MalformedInputTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.results = make_results_folder(Path(self.tmp.name) / "r", FixtureSpec(
            groups=(("phd3", 10),), steps=10, seeds=(1, 2)))
        self.out = Path(self.tmp.name) / "out"

    def tearDown(self):
        self.tmp.cleanup()

    def assert_report_error(self, *fragments: str) -> str:
        with self.assertRaises(ResultsFormatError) as caught:
            build_report([self.results], self.out)
        message = str(caught.exception)
        for fragment in fragments:
            self.assertIn(fragment, message)
        return message

    def test_summary_duplicated_row_is_refused_naming_both_lines(self):
        path = self.results / "summary.csv"
        lines = path.read_text().splitlines()
        path.write_text("\n".join(lines + [lines[1]]) + "\n")
        self.assert_report_error(str(path), f"line {len(lines) + 1}", "phd3 N=10",
                                 "appears twice", "first on line 2")

    def test_byte_order_mark_is_accepted(self):
        path = self.results / "summary.csv"
        path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
        build_report([self.results], self.out)
        html = (self.out / "index.html").read_text()
        self.assertNotIn("required column 'estimator' is missing", html)
        self.assertIn("phd3", html)

    def test_a_run_without_map_csv_is_noted(self):
        for seed in (1, 2):
            (self.results / "runs" / "phd3-N10" / f"seed-{seed}" / "map.csv").unlink()
        build_report([self.results], self.out)
        html = (self.out / "index.html").read_text()
        self.assertIn("map.csv: no estimated map is drawn", html)

    def test_summary_missing_column(self):
        path = self.results / "summary.csv"
        replace_line(path, 0, "gospa_std_m", "gospa_sd")
        self.assert_report_error(str(path), "'gospa_std_m'", "missing")

    def test_summary_non_number(self):
        path = self.results / "summary.csv"
        lines = path.read_text().splitlines()
        cells = lines[1].split(",")
        cells[4] = "fast"  # pos_rmse_m
        lines[1] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
        self.assert_report_error(str(path), "line 2", "column 'pos_rmse_m'", "'fast'")

    def test_steps_non_number_names_line_and_column(self):
        path = self.results / "runs" / "phd3-N10" / "seed-2" / "steps.csv"
        lines = path.read_text().splitlines()
        cells = lines[4].split(",")
        cells[8] = "abc"  # pos_err_m of step 3, file line 5
        lines[4] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
        self.assert_report_error(str(path), "line 5", "column 'pos_err_m'", "'abc'")

    def test_steps_missing_column(self):
        path = self.results / "runs" / "phd3-N10" / "seed-1" / "steps.csv"
        replace_line(path, 0, "heading_err_deg", "heading_error")
        self.assert_report_error(str(path), "'heading_err_deg'")

    def test_runs_short_row(self):
        path = self.results / "runs.csv"
        lines = path.read_text().splitlines()
        lines[2] = lines[2].rsplit(",", 2)[0]
        path.write_text("\n".join(lines) + "\n")
        self.assert_report_error(str(path), "line 3", "cells")

    def test_runs_nan_cell_is_refused(self):
        path = self.results / "runs.csv"
        lines = path.read_text().splitlines()
        header = lines[0].split(",")
        cells = lines[2].split(",")
        cells[header.index("pos_rmse_m")] = "nan"
        lines[2] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
        self.assert_report_error(str(path), "line 3", "column 'pos_rmse_m'", "not a finite")

    def test_summary_header_only_is_refused(self):
        path = self.results / "summary.csv"
        path.write_text(path.read_text().splitlines()[0] + "\n")
        self.assert_report_error(str(path), "header only")

    def test_summary_cut_before_a_group_is_refused(self):
        self.results = make_results_folder(Path(self.tmp.name) / "two", FixtureSpec(
            groups=(("phd3", 10), ("phd3", 100)), steps=10, seeds=(1, 2)))
        path = self.results / "summary.csv"
        path.write_text("\n".join(path.read_text().splitlines()[:2]) + "\n")
        self.assert_report_error(str(path), "no row for phd3 N=100")

    def test_missing_results_folder_is_refused_and_not_created(self):
        missing = Path(self.tmp.name) / "no-such-folder"
        stderr = io.StringIO()
        with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            self.assertEqual(make_report.main([str(missing)]), 1)
        self.assertIn(f"{missing}: not a folder", stderr.getvalue())
        self.assertFalse(missing.exists())

    def test_map_missing_y(self):
        path = self.results / "runs" / "phd3-N10" / "seed-1" / "map.csv"
        replace_line(path, 0, "x,y,", "x,yy,")
        self.assert_report_error(str(path), "'y'")

    def test_config_not_json(self):
        (self.results / "config.json").write_text("{ not json")
        self.assert_report_error(str(self.results / "config.json"), "JSON")

    def test_cli_exit_code_and_message(self):
        path = self.results / "summary.csv"
        replace_line(path, 0, "ms_per_step_mean", "ms")
        for main, argv in ((make_report.main, [str(self.results), "--out", str(self.out)]),
                           (tables.main, [str(self.results)])):
            stderr = io.StringIO()
            with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
                self.assertEqual(main(argv), 1)
            self.assertIn(f"{path}: required column 'ms_per_step_mean' is missing",
                          stderr.getvalue())

    def assert_cli_error(self, *fragments: str) -> str:
        stderr = io.StringIO()
        with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            self.assertEqual(make_report.main([str(self.results), "--out", str(self.out)]), 1)
        message = stderr.getvalue()
        for fragment in fragments:
            self.assertIn(fragment, message)
        return message

    def test_parent_weights_missing_column(self):
        write_parent_weights(self.results)
        path = self.results / "parent_weights.csv"
        replace_line(path, 0, "rb_weight", "rb")
        self.assert_cli_error(f"{path}: required column 'rb_weight' is missing")

    def test_parent_weights_non_numeric_weight(self):
        write_parent_weights(self.results)
        path = self.results / "parent_weights.csv"
        lines = path.read_text().splitlines()
        cells = lines[3].split(",")
        cells[4] = "heavy"  # sc_weight of parent 2, file line 4
        lines[3] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
        self.assert_cli_error(f"{path}, line 4, column 'sc_weight': 'heavy' is not a number")

    def test_parent_weights_empty_weight(self):
        write_parent_weights(self.results)
        path = self.results / "parent_weights.csv"
        lines = path.read_text().splitlines()
        cells = lines[6].split(",")
        cells[5] = ""  # rb_weight of parent 5, file line 7
        lines[6] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
        self.assert_cli_error(f"{path}, line 7, column 'rb_weight': empty cell")

    def test_parent_weights_not_summing_to_one(self):
        write_parent_weights(self.results, parents=10)
        path = self.results / "parent_weights.csv"
        lines = path.read_text().splitlines()
        cells = lines[1].split(",")
        cells[5] = repr(float(cells[5]) + 1e-4)  # rb_weight of the first parent
        lines[1] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
        message = self.assert_cli_error(f"{path}, lines 2-11, column 'rb_weight': the weights "
                                        "sum to 1.0001")
        self.assertIn("expected 1 within 1e-06", message)

    def test_parent_weights_negative_weight(self):
        write_parent_weights(self.results)
        path = self.results / "parent_weights.csv"
        lines = path.read_text().splitlines()
        cells = lines[2].split(",")
        cells[4] = "-" + cells[4]
        lines[2] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
        self.assert_cli_error(f"{path}, line 3, column 'sc_weight': negative weight")

    def set_parent_cell(self, line: int, column: str, value: str) -> Path:
        """Writes the fixture's parent_weights.csv with one cell replaced (1-based file line)."""
        write_parent_weights(self.results)
        path = self.results / "parent_weights.csv"
        lines = path.read_text().splitlines()
        cells = lines[line - 1].split(",")
        cells[lines[0].split(",").index(column)] = value
        lines[line - 1] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
        return path

    def test_parent_weights_non_numeric_log_weight_and_missed_mass(self):
        path = self.set_parent_cell(5, "sc_log_weight", "tiny")
        self.assert_cli_error(f"{path}, line 5, column 'sc_log_weight': 'tiny' is not a number")
        path = self.set_parent_cell(9, "missed_mass", "n/a")
        self.assert_cli_error(f"{path}, line 9, column 'missed_mass': 'n/a' is not a number")

    def test_parent_weights_empty_or_infinite_optional_cells(self):
        path = self.set_parent_cell(3, "rb_log_weight", "")
        self.assert_cli_error(f"{path}, line 3, column 'rb_log_weight': empty cell")
        path = self.set_parent_cell(4, "sc_log_weight", "-inf")
        self.assert_cli_error(f"{path}, line 4, column 'sc_log_weight': '-inf' is not a finite "
                              "number")

    def test_parent_weights_negative_missed_mass(self):
        path = self.set_parent_cell(6, "missed_mass", "-0.5")
        self.assert_cli_error(f"{path}, line 6, column 'missed_mass': negative missed-detection "
                              "mass -0.5")

    def test_parent_weights_log_weights_not_normalised(self):
        write_parent_weights(self.results, parents=10)
        path = self.results / "parent_weights.csv"
        lines = path.read_text().splitlines()
        column = lines[0].split(",").index("rb_log_weight")
        for i in range(1, len(lines)):
            cells = lines[i].split(",")
            cells[column] = repr(float(cells[column]) - 0.5)  # log-sum-exp -0.5
            lines[i] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
        message = self.assert_cli_error(f"{path}, lines 2-11, column 'rb_log_weight': the "
                                        "log-sum-exp of the log-weights is -0.5")
        self.assertIn("expected 0 within 1e-06", message)

    def test_parent_weights_one_log_weight_column_without_the_other(self):
        write_parent_weights(self.results)
        path = self.results / "parent_weights.csv"
        replace_line(path, 0, "rb_log_weight", "rb_log")
        self.assert_cli_error(f"{path}: column 'sc_log_weight' without 'rb_log_weight'")

    def test_parent_weights_json_spread(self):
        write_parent_weights(self.results)
        path = self.results / "parent_weights.json"
        data = json.loads(path.read_text())
        data["spread"] = "wide"
        path.write_text(json.dumps(data))
        self.assert_cli_error(f"{path}: key 'spread': expected a positive number, got \"wide\"")

    def test_parent_weights_json_missing_key_and_wrong_count(self):
        write_parent_weights(self.results)
        path = self.results / "parent_weights.json"
        data = json.loads(path.read_text())
        del data["predicted_mean"]
        path.write_text(json.dumps(data))
        self.assert_cli_error(f"{path}: key 'predicted_mean': expected [x, y, theta], got "
                              "missing")
        data["predicted_mean"] = [1, 2, 3]
        data["parents"] = 41
        path.write_text(json.dumps(data))
        self.assert_cli_error(f"{path}: key 'parents' is 41, but parent_weights.csv has 40")

    def test_gps_missing_column(self):
        results = make_results_folder(Path(self.tmp.name) / "vp", FixtureSpec(
            groups=(("phd3", 10),), steps=10, seeds=(1,), gps_only=True))
        path = results / "truth" / "seed-1" / "gps.csv"
        replace_line(path, 0, "t,x,y", "t,x,north")
        self.results = results
        self.assert_cli_error(f"{path}: required column 'y' is missing")

    def test_not_a_results_folder(self):
        empty = Path(self.tmp.name) / "empty"
        empty.mkdir()
        with self.assertRaises(ResultsFormatError) as caught:
            build_report([empty], self.out)
        self.assertIn("not a results folder", str(caught.exception))


def add_column(path: Path, name: str, value: str) -> None:
    """Appends column ``name`` with ``value`` in every row."""
    lines = path.read_text().splitlines()
    lines = [lines[0] + "," + name] + [line + "," + value for line in lines[1:]]
    path.write_text("\n".join(lines) + "\n")


def set_cell(path: Path, row: int, column: str, value: str) -> None:
    """Sets the cell of data row ``row`` (0-based) in ``column``."""
    lines = path.read_text().splitlines()
    header = lines[0].split(",")
    cells = lines[row + 1].split(",")
    cells[header.index(column)] = value
    lines[row + 1] = ",".join(cells)
    path.write_text("\n".join(lines) + "\n")


class MagnitudeBoundTest(unittest.TestCase):
    """Numbers beyond 1e100 are refused, but for the consistency statistics: a filter whose
    particles collapse without resampling writes a NEES of 1e300 and more, as it is."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.results = make_results_folder(Path(self.tmp.name) / "r", FixtureSpec(
            groups=(("phd3", 10),), steps=10, seeds=(1, 2), nees=True))
        self.out = Path(self.tmp.name) / "out"
        self.steps = self.results / "runs" / "phd3-N10" / "seed-2" / "steps.csv"

    def tearDown(self):
        self.tmp.cleanup()

    def test_nees_of_a_collapsed_filter_is_read_and_reported(self):
        set_cell(self.steps, 3, "nees", "1e+300")
        add_column(self.results / "runs.csv", "pose_nees_mean", "4.62967442e+304")
        add_column(self.results / "summary.csv", "pose_nees_mean", "2.972976172e+240")
        build_report([self.results], self.out)
        self.assertTrue((self.out / "index.html").is_file())
        with contextlib.redirect_stdout(io.StringIO()):
            self.assertEqual(tables.main([str(self.results)]), 0)
        runs = read_csv(self.results / "runs.csv", text_columns=("estimator",))
        self.assertEqual(runs.num("pose_nees_mean")[0], 4.62967442e+304)

    def test_nees_near_the_double_range_is_drawn(self):
        # Means of 1e267 (which a log axis of matplotlib cannot label) and of +inf (a sum over
        # the runs beyond the double range) at two steps.
        for seed in (1, 2):
            steps = self.results / "runs" / "phd3-N10" / f"seed-{seed}" / "steps.csv"
            set_cell(steps, 3, "nees", "1e+267")
            set_cell(steps, 5, "nees", "1.7e+308")
        build_report([self.results], self.out)
        self.assertTrue((self.out / "nees.png").is_file())

    def test_infinite_or_hugely_negative_nees_is_refused(self):
        for value in ("inf", "-1e+300"):
            set_cell(self.steps, 3, "nees", value)
            with self.assertRaises(ResultsFormatError) as caught:
                build_report([self.results], self.out)
            self.assertIn(f"{self.steps}, line 5, column 'nees': {value} is infinite or below "
                          "-1e+100", str(caught.exception))

    def test_huge_error_metric_is_refused(self):
        set_cell(self.steps, 3, "pos_err_m", "1e+300")
        with self.assertRaises(ResultsFormatError) as caught:
            build_report([self.results], self.out)
        self.assertIn(f"{self.steps}, line 5, column 'pos_err_m': 1e+300 is infinite or beyond "
                      "+-1e+100", str(caught.exception))


class CsvReaderTest(unittest.TestCase):
    def test_empty_cells_are_nan_and_comments_skipped(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "m.csv"
            path.write_text("# a comment\nx,y,weight\n1,2,\n\n3,,0.5\n")
            table = read_csv(path, ("x", "y"))
            self.assertEqual(table.rows, 2)
            self.assertEqual(list(table.num("x")), [1.0, 3.0])
            self.assertNotEqual(table.num("y")[1], table.num("y")[1])  # NaN
            path.write_text("# a comment\nx,y\n1,2\n\n3,oops\n")
            with self.assertRaises(ResultsFormatError) as caught:
                read_csv(path, ("x", "y"))
            self.assertIn(f"{path}, line 5, column 'y': 'oops' is not a number",
                          str(caught.exception))


if __name__ == "__main__":
    unittest.main()
