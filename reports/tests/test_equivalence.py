"""ci/equivalence.py: paired TOST of two results folders on synthetic runs of a known verdict."""

import contextlib
import importlib.util
import io
import json
import math
import random
import sys
import tempfile
import unittest
from pathlib import Path

from fixture import REPORTS_DIR

CI_DIR = REPORTS_DIR.parent / "ci"
_spec = importlib.util.spec_from_file_location("equivalence", CI_DIR / "equivalence.py")
equivalence = importlib.util.module_from_spec(_spec)
sys.modules["equivalence"] = equivalence
_spec.loader.exec_module(equivalence)

COLUMNS = "estimator,particles,seed,steps,pos_rmse_m,gospa_m,ms_per_step_mean"


def runs_csv(rows: list[tuple[str, int, int, float, float]]) -> str:
    lines = [COLUMNS]
    for estimator, particles, seed, rmse, gospa in rows:
        gospa_text = "" if math.isnan(gospa) else f"{gospa:.10g}"
        lines.append(f"{estimator},{particles},{seed},100,{rmse:.10g},{gospa_text},0.1")
    return "\n".join(lines) + "\n"


def noisy_runs(seeds: int, rng: random.Random,
               name: str = "phd3") -> list[tuple[str, int, int, float, float]]:
    """Per-seed values that vary like independent filter runs (coefficient of variation 30 %)."""
    return [(name, 10, s, 3.0 * (1 + 0.3 * rng.gauss(0, 1)), 40.0 * (1 + 0.3 * rng.gauss(0, 1)))
            for s in range(1, seeds + 1)]


def rerun(rows, rng: random.Random, spread: float, factor: float = 1.0):
    """The same seeds run again: each value times factor and a relative noise of this spread."""
    return [(e, n, s, r * factor * (1 + spread * rng.gauss(0, 1)),
             g * factor * (1 + spread * rng.gauss(0, 1))) for e, n, s, r, g in rows]


def write_config(folder: Path) -> None:
    """A config.json naming the scenario (every results folder has one)."""
    (folder / "config.json").write_text(json.dumps({"scenario": {"name": "synthetic",
                                                                 "options": {}}}))


class Folders:
    """BEFORE and AFTER results folders in a temporary directory."""

    def __init__(self, before: str, after: str):
        self._tmp = tempfile.TemporaryDirectory()
        root = Path(self._tmp.name)
        self.before, self.after = root / "before", root / "after"
        for folder, text in ((self.before, before), (self.after, after)):
            folder.mkdir()
            (folder / "runs.csv").write_text(text)
            write_config(folder)

    def run(self, *extra: str) -> tuple[int, str, str]:
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = equivalence.main([str(self.before), str(self.after), *extra])
        return code, out.getvalue(), err.getvalue()

    def close(self) -> None:
        self._tmp.cleanup()


def run_pair(before: str, after: str, *extra: str) -> tuple[int, str, str]:
    folders = Folders(before, after)
    try:
        return folders.run(*extra)
    finally:
        folders.close()


def verdicts(output: str) -> list[str]:
    return [line for line in output.splitlines() if "phd3" in line]


def column_of(output: str, line: str, name: str) -> str:
    """A cell of a printed line by its header name (cells are separated by 2+ spaces)."""
    header = next(h for h in output.splitlines() if h.startswith("scenario"))
    names = header.split()
    cells = [c for c in line.split("  ") if c.strip()]
    offset = len(names) - len(cells)  # the scenario cell is empty without a config.json
    return cells[names.index(name) - offset].strip()


class StudentT(unittest.TestCase):
    def test_quantiles_match_tables(self):
        # One-sided 95 % critical values of Student's t (standard tables).
        for df, expected in ((1, 6.313752), (4, 2.131847), (9, 1.833113), (30, 1.697261),
                             (199, 1.652547)):
            self.assertAlmostEqual(equivalence.t_quantile(0.95, df), expected, places=5)
        self.assertAlmostEqual(equivalence.t_quantile(0.05, 9), -1.833113, places=5)
        self.assertAlmostEqual(equivalence.normal_quantile(0.95), 1.6448536270, places=9)

    def test_cdf_symmetry_and_known_value(self):
        self.assertAlmostEqual(equivalence.t_cdf(0.0, 7), 0.5, places=12)
        self.assertAlmostEqual(equivalence.t_cdf(2.0, 5) + equivalence.t_cdf(-2.0, 5), 1.0,
                               places=12)
        # df = 1 is the Cauchy distribution: P(T <= t) = 1/2 + atan(t) / pi.
        for t in (-3.0, 0.4, 10.0):
            self.assertAlmostEqual(equivalence.t_cdf(t, 1), 0.5 + math.atan(t) / math.pi,
                                   places=10)

    def test_against_scipy(self):
        try:
            from scipy import stats
        except ImportError:
            self.skipTest("SciPy is not installed")
        for df in (1, 2, 5, 19, 99, 199, 999):
            for p in (0.9, 0.95, 0.975, 0.999):
                self.assertAlmostEqual(equivalence.t_quantile(p, df), stats.t.ppf(p, df),
                                       places=7, msg=f"p={p} df={df}")
            for t in (-4.0, -1.0, 0.3, 2.5):
                self.assertAlmostEqual(equivalence.t_cdf(t, df), stats.t.cdf(t, df), places=10)


class PairedTost(unittest.TestCase):
    def test_identical_folders_are_equivalent(self):
        rows = noisy_runs(50, random.Random(1))
        code, out, _ = run_pair(runs_csv(rows), runs_csv(rows))
        self.assertEqual(code, 0, out)
        self.assertEqual(len(verdicts(out)), 2)
        for line in verdicts(out):
            self.assertTrue(line.endswith("EQUIVALENT"), line)
            self.assertEqual(column_of(out, line, "ci90_low_pct"), "0")
        self.assertIn("2 of 2 EQUIVALENT", out)

    def test_rounding_noise_on_200_seeds_is_equivalent(self):
        # AFTER differs from BEFORE like an independent run with 10 % spread: mean 0, so with
        # 200 seeds the 90 % interval (about +-0.012 x mean) lies well inside +-5 %.
        rng = random.Random(2)
        rows = noisy_runs(200, rng)
        code, out, _ = run_pair(runs_csv(rows), runs_csv(rerun(rows, rng, 0.1)))
        self.assertEqual(code, 0, out)

    def test_shifted_after_is_not_shown(self):
        rng = random.Random(3)
        rows = noisy_runs(200, rng)
        after = rerun(rows, rng, 0.02, factor=1.10)
        code, out, _ = run_pair(runs_csv(rows), runs_csv(after))
        self.assertEqual(code, 1, out)
        for line in verdicts(out):
            self.assertTrue(line.endswith("NOT SHOWN"), line)
            # The interval, in % of BEFORE's mean, sits around the 10 % shift.
            self.assertGreater(float(column_of(out, line, "ci90_low_pct")), 8.0)
            self.assertLess(float(column_of(out, line, "ci90_high_pct")), 12.0)
        self.assertIn("0 of 2 EQUIVALENT", out)
        # A margin of 15 % accepts the same 10 % shift.
        code, out, _ = run_pair(runs_csv(rows), runs_csv(after), "--margin", "0.15")
        self.assertEqual(code, 0, out)

    def test_noisy_after_with_too_few_seeds_is_not_shown(self):
        rng = random.Random(4)
        rows = noisy_runs(5, rng)
        code, out, _ = run_pair(runs_csv(rows), runs_csv(rerun(rows, rng, 0.1)))
        # Five seeds of 10 % noise: the interval is wider than +-5 % although nothing moved.
        self.assertEqual(code, 1, out)
        for line in verdicts(out):
            self.assertTrue(line.endswith("NOT SHOWN"), line)
            self.assertGreater(int(column_of(out, line, "seeds_needed")), 5)

    def test_too_few_pairs_is_an_error(self):
        rows = noisy_runs(5, random.Random(5))
        code, _, err = run_pair(runs_csv(rows[:1]), runs_csv(rows[:1]))
        self.assertEqual(code, 2)
        self.assertIn("1 paired seed(s), fewer than 2", err)
        code, _, err = run_pair(runs_csv(rows), runs_csv(rows), "--min-seeds", "200")
        self.assertEqual(code, 2)
        self.assertIn("5 paired seed(s), fewer than 200", err)

    def test_interval_and_p_value_by_hand(self):
        before = [1.0, 2.0, 3.0, 4.0]
        after = [1.1, 2.0, 3.2, 4.1]  # d = 0.1, 0, 0.2, 0.1: mean 0.1, sd sqrt(0.02/3)
        tost = equivalence.paired_tost(before, after, 0.2, 0.05)
        se = math.sqrt(0.02 / 3 / 4)
        half = 2.353363 * se  # t(0.95, 3)
        self.assertAlmostEqual(tost.mean_difference, 0.1, places=12)
        self.assertAlmostEqual(tost.ci_low, 0.1 - half, places=5)
        self.assertAlmostEqual(tost.ci_high, 0.1 + half, places=5)
        self.assertAlmostEqual(tost.margin, 0.5, places=12)
        self.assertTrue(tost.equivalent)
        # p = P(T_3 >= (0.5 - 0.1) / se) for the binding upper test.
        self.assertAlmostEqual(tost.p_value, 1 - equivalence.t_cdf(0.4 / se, 3), places=12)
        # The paired t-test of mean(d) = 0: t = 0.1 / se = 2.449 with 3 degrees of freedom.
        self.assertAlmostEqual(tost.p_difference, 2 * equivalence.t_cdf(-0.1 / se, 3), places=12)
        self.assertAlmostEqual(tost.p_difference, 0.0917211, places=6)  # SciPy ttest_rel
        # The verdict agrees with the interval: a margin just inside the upper end fails.
        tight = equivalence.paired_tost(before, after, (0.1 + half) / 2.5 * 0.999, 0.05)
        self.assertFalse(tight.equivalent)

    def test_seeds_needed_by_hand(self):
        # sd = 1, margin = 0.05: t(0.95, n - 1) / sqrt(n) first falls below 0.05 at n = 1085
        # (1084: 0.0500016; 1085: 0.0499786).
        self.assertEqual(equivalence.seeds_needed(1.0, 0.05, 0.05), 1085)
        # sd = 1, margin = 1: n = 4 gives 2.353 / 2 = 1.18, n = 5 gives 2.132 / 2.236 = 0.953.
        self.assertEqual(equivalence.seeds_needed(1.0, 1.0, 0.05), 5)
        self.assertEqual(equivalence.seeds_needed(0.0, 1.0, 0.05), 2)
        self.assertTrue(math.isinf(equivalence.seeds_needed(1.0, 0.0, 0.05)))


class Pairing(unittest.TestCase):
    def test_pairs_by_seed_whatever_the_order(self):
        rng = random.Random(6)
        rows = noisy_runs(30, rng)
        after = list(reversed(rerun(rows, rng, 0.01)))
        code, out, _ = run_pair(runs_csv(rows), runs_csv(after))
        self.assertEqual(code, 0, out)
        # Paired, the 1 % noise gives an interval of a fraction of a percent; unpaired (the
        # reversed order) it would be as wide as the 30 % spread between seeds.
        for line in verdicts(out):
            self.assertLess(abs(float(column_of(out, line, "ci90_high_pct"))), 1.0)

    def test_unpaired_runs_are_an_error_unless_seeds_restrict(self):
        rows = noisy_runs(30, random.Random(7))
        code, _, err = run_pair(runs_csv(rows), runs_csv(rows[1:]))
        self.assertEqual(code, 2)
        self.assertIn("has no run of phd3 N=10 for seed(s) 1 ", err)
        code, _, err = run_pair(runs_csv(rows[1:]), runs_csv(rows))
        self.assertEqual(code, 2)
        self.assertIn("seed(s) 1 ", err)
        code, out, _ = run_pair(runs_csv(rows), runs_csv(rows[1:]), "--seeds", "2-30")
        self.assertEqual(code, 0, out)
        self.assertEqual(column_of(out, verdicts(out)[0], "n"), "29")
        # A group AFTER has and BEFORE has not.
        extra = rows + noisy_runs(5, random.Random(8), name="phd1")
        code, _, err = run_pair(runs_csv(rows), runs_csv(extra))
        self.assertEqual(code, 2)
        self.assertIn("runs of phd1 N=10", err)

    def test_value_missing_in_one_run_is_an_error_and_empty_column_not_tested(self):
        rows = noisy_runs(10, random.Random(9))
        after = list(rows)
        e, n, s, r, _ = after[3]
        after[3] = (e, n, s, r, float("nan"))
        code, _, err = run_pair(runs_csv(rows), runs_csv(after))
        self.assertEqual(code, 2)
        self.assertIn("line 5: gospa_m is empty for phd3 N=10 seed 4", err)
        no_map = [(e, n, s, r, float("nan")) for e, n, s, r, _ in rows]
        code, out, _ = run_pair(runs_csv(no_map), runs_csv(no_map))
        self.assertEqual(code, 0, out)
        self.assertIn("NOT TESTED", out)
        self.assertIn("1 of 1 EQUIVALENT", out)

    def test_non_finite_values_are_an_error(self):
        rows = noisy_runs(10, random.Random(10))
        for bad in ("nan", "inf", "-inf"):
            text = runs_csv(rows).replace(f",{rows[2][3]:.10g},", f",{bad},")
            code, _, err = run_pair(runs_csv(rows), text)
            self.assertEqual(code, 2, bad)
            self.assertIn(f"line 4, column pos_rmse_m: '{bad}' is not a finite number", err)

    def test_estimator_map_pairs_other_names_and_tests_only_those(self):
        rows = noisy_runs(20, random.Random(11))
        renamed = [("authors", n, s, r, g) for _, n, s, r, g in rows]
        code, out, _ = run_pair(runs_csv(rows), runs_csv(renamed), "--estimator-map",
                                "phd3=authors")
        self.assertEqual(code, 0, out)
        self.assertIn("phd3=authors", out)
        # Both in one folder: only the mapped estimator is tested, against its partner.
        both = runs_csv(rows + renamed)
        code, out, _ = run_pair(both, both, "--estimator-map", "phd3=authors")
        self.assertEqual(code, 0, out)
        self.assertIn("2 of 2 EQUIVALENT", out)
        code, _, err = run_pair(both, both, "--estimator-map", "phd9=authors")
        self.assertEqual(code, 2)
        self.assertIn("no runs of estimator 'phd9'", err)

    def test_column_adds_to_the_default_columns(self):
        rows = noisy_runs(10, random.Random(12))
        code, out, _ = run_pair(runs_csv(rows), runs_csv(rows), "--column", "ms_per_step_mean")
        self.assertEqual(code, 0, out)
        self.assertIn("3 of 3 EQUIVALENT", out)
        code, out, _ = run_pair(runs_csv(rows), runs_csv(rows), "--metric", "gospa_m")
        self.assertIn("1 of 1 EQUIVALENT", out)

    def test_scenarios_must_match(self):
        rows = noisy_runs(10, random.Random(13))
        folders = Folders(runs_csv(rows), runs_csv(rows))
        try:
            for folder, name, data_dir in ((folders.before, "paper-synthetic", "/a"),
                                           (folders.after, "paper-synthetic", "/b")):
                (folder / "config.json").write_text(json.dumps({"scenario": {
                    "name": name, "options": {"data_dir": data_dir, "steps": 0}}}))
            code, out, _ = folders.run()
            self.assertEqual(code, 0, out)  # the data folder's path does not matter
            self.assertTrue(verdicts(out)[0].startswith("paper-synthetic"))
            (folders.after / "config.json").write_text(json.dumps({"scenario": {
                "name": "paper-synthetic", "options": {"steps": 300}}}))
            code, _, err = folders.run()
            self.assertEqual(code, 2)
            self.assertIn("scenario option 'steps' differs", err)
            (folders.after / "config.json").write_text(json.dumps({"scenario": {
                "name": "victoria-park", "options": {"steps": 0}}}))
            code, _, err = folders.run()
            self.assertEqual(code, 2)
            self.assertIn("scenarios differ", err)
        finally:
            folders.close()

    def test_sweep_root_compares_every_folder(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            for side in ("before", "after"):
                for folder in ("pd-0.5", "pd-0.9"):
                    (root / side / folder).mkdir(parents=True)
                    (root / side / folder / "runs.csv").write_text(
                        runs_csv(noisy_runs(10, random.Random(folder))))
                    write_config(root / side / folder)
                (root / side / "sweep.json").write_text(
                    json.dumps({"folders": ["pd-0.5", "pd-0.9"]}))
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                code = equivalence.main([str(root / "before"), str(root / "after"),
                                         "--csv", str(root / "eq.csv")])
            self.assertEqual(code, 0, out.getvalue())
            self.assertIn("# pd-0.9", out.getvalue())
            self.assertIn("4 of 4 EQUIVALENT", out.getvalue())
            written = (root / "eq.csv").read_text().splitlines()
            self.assertEqual(len(written), 5)
            self.assertTrue(written[0].startswith("folder,scenario,estimator,N,column,n,"))


class BadInput(unittest.TestCase):
    def test_missing_file_and_unknown_column_exit_2(self):
        rows = noisy_runs(5, random.Random(14))
        folders = Folders(runs_csv(rows), runs_csv(rows))
        try:
            code, _, err = folders.run("--column", "no_such_column")
            self.assertEqual(code, 2)
            self.assertIn("no column 'no_such_column'", err)
            (folders.after / "runs.csv").unlink()
            code, _, err = folders.run()
            self.assertEqual(code, 2)
            self.assertIn("missing:", err)
        finally:
            folders.close()

    def test_malformed_values_and_options_exit_2(self):
        bad = COLUMNS + "\nphd3,ten,1,100,1,1,0.1\n"
        code, _, err = run_pair(bad, bad)
        self.assertEqual(code, 2)
        self.assertIn("line 2", err)
        rows = runs_csv(noisy_runs(5, random.Random(15)))
        with contextlib.redirect_stderr(io.StringIO()):
            self.assertEqual(run_pair(rows, rows, "--margin", "-1")[0], 2)
            self.assertEqual(run_pair(rows, rows, "--estimator-map", "phd3")[0], 2)
            self.assertEqual(run_pair(rows, rows, "--seeds", "x-3")[0], 2)
        text = COLUMNS + "\nphd3,10,1,100,abc,1,0.1\nphd3,10,2,100,1,1,0.1\n"
        code, _, err = run_pair(text, text)
        self.assertEqual(code, 2)
        self.assertIn("line 2, column pos_rmse_m: 'abc' is not a number", err)
        twice = COLUMNS + "\nphd3,10,1,100,1,1,0.1\nphd3,10,1,100,1,1,0.1\n"
        code, _, err = run_pair(twice, twice)
        self.assertEqual(code, 2)
        self.assertIn("appears twice", err)

    def test_missing_config_is_an_error_not_a_skipped_check(self):
        rows = runs_csv(noisy_runs(5, random.Random(16)))
        folders = Folders(rows, rows)
        try:
            (folders.after / "config.json").unlink()
            code, out, err = folders.run()
            self.assertEqual(code, 2)
            self.assertNotIn("EQUIVALENT", out)
            self.assertIn(f"missing: {folders.after / 'config.json'}", err)
        finally:
            folders.close()

    def test_unwritable_csv_is_one_line_naming_it(self):
        rows = runs_csv(noisy_runs(5, random.Random(17)))
        code, _, err = run_pair(rows, rows, "--csv", "/proc/nonexistent/x.csv")
        self.assertEqual(code, 2)
        self.assertIn("--csv /proc/nonexistent/x.csv", err.splitlines()[-1])
        self.assertNotIn("Traceback", err)

    def test_byte_order_mark_is_accepted(self):
        rows = runs_csv(noisy_runs(5, random.Random(18)))
        code, out, _ = run_pair("\ufeff" + rows, rows)
        self.assertEqual(code, 0, out)
        self.assertIn("2 of 2 EQUIVALENT", out)

    def test_sweep_json_of_the_wrong_shape_exit_2(self):
        rows = runs_csv(noisy_runs(5, random.Random(19)))
        folders = Folders(rows, rows)
        try:
            (folders.before / "sweep.json").write_text(json.dumps({"folders": [1, 2]}))
            code, _, err = folders.run()
            self.assertEqual(code, 2)
            self.assertIn("sweep.json", err)
        finally:
            folders.close()


if __name__ == "__main__":
    unittest.main()
