"""What a reader sees: the step count in words, time flags only for slower times, Fig. 3 drawn
from the traces `phdslam run --particles-trace` writes, and no wording from outside the report."""

import re
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder
from phdslam_reports.comparison import compare
from phdslam_reports.csv_table import ResultsFormatError
from phdslam_reports.figures.particle_paths import particle_weights
from phdslam_reports.paper import PaperValues
from phdslam_reports.report import build_report
from phdslam_reports.results import ResultsFolder
from phdslam_reports import stats


def section_status(html: str, section_id: str) -> str | None:
    """'shown', 'skipped' or None when the page has no such section."""
    match = re.search(rf'<section id="{re.escape(section_id)}" data-status="(\w+)">', html)
    return match.group(1) if match else None


def set_summary_cells(folder: Path, column: str, values: dict[tuple[str, int], float]) -> None:
    """Rewrites ``column`` of summary.csv for the given (estimator, N) rows."""
    path = folder / "summary.csv"
    lines = path.read_text(encoding="utf-8").splitlines()
    header = lines[0].split(",")
    index = header.index(column)
    for i, line in enumerate(lines[1:], start=1):
        cells = line.split(",")
        key = (cells[0], int(cells[1]))
        if key in values:
            cells[index] = repr(values[key])
            lines[i] = ",".join(cells)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def cell_class(html: str, text: str) -> str:
    """The class attribute of the summary cell whose content holds ``text`` ('' if none)."""
    match = re.search(r'<td(?: class="([^"]*)")?>[^<]*<br><span class="sub">' + re.escape(text),
                      html)
    if match is None:
        raise AssertionError(f"no cell with {text!r}")
    return match.group(1) or ""


class HeaderStepsTest(unittest.TestCase):
    def header(self, steps_option):
        with tempfile.TemporaryDirectory() as tmp:
            results = make_results_folder(Path(tmp) / "results", FixtureSpec(
                groups=(("phd3", 1),), steps=30, seeds=(1, 2), steps_option=steps_option))
            report = build_report([results], Path(tmp) / "report")
        return report.html.split("<nav>")[0]

    def test_a_full_length_run_says_all_steps_with_their_number(self):
        header = self.header(0)  # config.json: steps 0, the runner's "no limit"
        self.assertIn("all 30 steps", header)
        self.assertNotIn("steps = 0", header)

    def test_a_step_limit_is_stated_as_such(self):
        header = self.header(None)  # config.json: steps 30
        self.assertIn("first 30 steps", header)


class TimeFlagTest(unittest.TestCase):
    """Table II's times per step (PHD 3.0: 0.14 ms at N = 1, 1.17 ms at N = 10)."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.results = make_results_folder(Path(cls.tmp.name) / "results", FixtureSpec(
            groups=(("phd3", 1), ("phd3", 10)), steps=30, seeds=(1, 2, 3), steps_option=4000))
        # 14 times faster than the paper at N = 1; 1.7 times slower at N = 10
        set_summary_cells(cls.results, "ms_per_step_mean",
                          {("phd3", 1): 0.01, ("phd3", 10): 2.0})
        cls.report = build_report([cls.results], Path(cls.tmp.name) / "report")
        cls.summary = cls.report.section("summary").body
        cls.comparison = compare(ResultsFolder(cls.results), PaperValues.load())

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def time_cell(self, particles):
        row = next(r for r in self.comparison.rows if r.group.particles == particles)
        return row.cell("ms_per_step_mean")

    def test_a_faster_time_is_not_flagged_nor_painted(self):
        cell = self.time_cell(1)
        self.assertAlmostEqual(cell.relative, 0.01 / 0.14 - 1)
        self.assertFalse(cell.flagged)
        self.assertFalse(cell.agrees)
        self.assertEqual(cell_class(self.summary, "paper 0.14,"), "")

    def test_a_slower_time_beyond_the_tolerance_is_flagged(self):
        cell = self.time_cell(10)
        self.assertTrue(cell.flagged)
        self.assertEqual(cell_class(self.summary, "paper 1.17,"), "flag")

    def test_accuracy_below_the_paper_is_still_flagged_both_ways(self):
        self.assertTrue(stats.is_flagged(0.5, 1.0))
        self.assertTrue(stats.is_flagged(1.5, 1.0))
        self.assertFalse(stats.is_flagged(0.5, 1.0, only_above=True))
        self.assertTrue(stats.is_flagged(1.151, 1.0, only_above=True))
        self.assertFalse(stats.is_flagged(1.15, 1.0, only_above=True))
        self.assertFalse(stats.is_flagged(0.0, 0.0, only_above=True))

    def test_the_page_says_how_times_are_flagged(self):
        self.assertIn("A time per step is red only when it is more than 15 % slower",
                      self.summary)


class ParticleTraceTest(unittest.TestCase):
    """particles.csv as `phdslam run --particles-trace` writes it: step,particle,x,y,log_weight."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.results = make_results_folder(Path(cls.tmp.name) / "results", FixtureSpec(
            groups=(("phd1", 10), ("phd3", 10), ("odometry", 1)), particles_file=True,
            steps=30, seeds=(1, 2, 3)))
        cls.report = build_report([cls.results], Path(cls.tmp.name) / "report")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_fig3_is_drawn_with_one_run_per_estimator_and_particle_count(self):
        self.assertEqual(section_status(self.report.html, "fig3"), "shown")
        body = self.report.section("fig3").body
        self.assertIn("fig3-particle-paths.png", body)
        self.assertIn("one run per estimator and particle count", body)
        self.assertIn("(fig3-particle-paths.png)", body)
        self.assertTrue((Path(self.tmp.name) / "report" / "fig3-particle-paths.png").is_file())

    def test_resampling_runs_say_their_lines_can_jump(self):
        self.assertIn("These runs resample", self.report.section("fig3").body)

    def test_log_weights_are_read_as_weights(self):
        folder = ResultsFolder(self.results)
        (_, _, path), *_ = folder.particle_files()
        weights = particle_weights(folder.particles(path))
        first_step = weights[:10]
        self.assertAlmostEqual(float(first_step.sum()), 1.0, places=6)  # %.10g in the file
        self.assertAlmostEqual(float(first_step[0] / first_step[1]), 2.0, places=6)

    def test_linear_weights_are_still_read(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = make_results_folder(Path(tmp) / "results", FixtureSpec(
                groups=(("phd3", 10),), particles_file=True, particles_weight_column="weight",
                steps=12, seeds=(1,)))
            report = build_report([results], Path(tmp) / "report")
            self.assertEqual(section_status(report.html, "fig3"), "shown")

    def test_a_trace_without_weights_names_the_file(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = make_results_folder(Path(tmp) / "results", FixtureSpec(
                groups=(("phd3", 10),), particles_file=True, steps=12, seeds=(1,)))
            path = results / "runs" / "phd3-N10" / "seed-1" / "particles.csv"
            lines = path.read_text(encoding="utf-8").splitlines()
            path.write_text("\n".join([",".join(lines[0].split(",")[:4])]
                                      + [",".join(line.split(",")[:4]) for line in lines[1:]])
                            + "\n", encoding="utf-8")
            with self.assertRaises(ResultsFormatError) as error:
                build_report([results], Path(tmp) / "report")
            self.assertIn(str(path), str(error.exception))
            self.assertIn("'log_weight'", str(error.exception))

    def test_without_traces_the_note_says_how_to_get_them(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = make_results_folder(Path(tmp) / "results", FixtureSpec(
                groups=(("phd3", 10),), steps=12, seeds=(1,)))
            report = build_report([results], Path(tmp) / "report")
            self.assertEqual(section_status(report.html, "fig3"), "skipped")
            self.assertIn("--particles-trace", report.section("fig3").skipped_note)
            self.assertNotIn("not write particle paths yet", report.html)


class WordingTest(unittest.TestCase):
    def test_no_wording_from_outside_the_project(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = make_results_folder(Path(tmp) / "results", FixtureSpec(
                steps=12, seeds=(1, 2), steps_option=4000, da_rates=True))
            html = build_report([results], Path(tmp) / "report").html
        for phrase in ("brief", "reference notes", "notes section", "/work/", "session"):
            self.assertNotIn(phrase, html.lower(), phrase)


if __name__ == "__main__":
    unittest.main()
