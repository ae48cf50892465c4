"""ci/equivalence.py: paired TOST of two results folders on synthetic runs whose verdict is known."""

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


def noisy_runs(seeds: int, rng: random.Random) -> list[tuple[str, int, int, float, float]]:
    """Per-seed values that vary like independent filter runs (coefficient of variation 30 %)."""
    return [("phd3", 10, s, 3.0 * (1 + 0.3 * rng.gauss(0, 1)), 40.0 * (1 + 0.3 * rng.gauss(0, 1)))
            for s in range(1, seeds + 1)]


class Folders:
    """BEFORE and AFTER results folders in a temporary directory."""

    def __init__(self, before: str, after: str):
        self._tmp = tempfile.TemporaryDirectory()
        root = Path(self._tmp.name)
        self.before, self.after = root / "before", root / "after"
        for folder, text in ((self.before, before), (self.after, after)):
            folder.mkdir()
            (folder / "runs.csv").write_text(text)

    def run(self, *extra: str) -> tuple[int, str, str]:
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = equivalence.main([str(self.before), str(self.after), *extra])
        return code, out.getvalue(), err.getvalue()

    def close(self) -> None:
        self._tmp.cleanup()


def verdicts(output: str) -> list[str]:
    return [line for line in output.splitlines() if line.startswith("phd3")]


class StudentT(unittest.TestCase):
    def test_quantiles_match_tables(self):
        # Two-sided 90 % critical values of Student's t (standard tables).
        for df, expected in ((1, 6.313752), (4, 2.131847), (9, 1.833113), (30, 1.697261),
                             (199, 1.652547)):
            self.assertAlmostEqual(equivalence.t_quantile(0.95, df), expected, places=5)
        self.assertAlmostEqual(equivalence.t_quantile(0.05, 9), -1.833113, places=5)

    def test_cdf_symmetry_and_known_value(self):
        self.assertAlmostEqual(equivalence.t_cdf(0.0, 7), 0.5, places=12)
        self.assertAlmostEqual(equivalence.t_cdf(2.0, 5) + equivalence.t_cdf(-2.0, 5), 1.0,
                               places=12)
        # df = 1 is the Cauchy distribution: P(T <= t) = 1/2 + atan(t) / pi.
        for t in (-3.0, 0.4, 10.0):
            self.assertAlmostEqual(equivalence.t_cdf(t, 1), 0.5 + math.atan(t) / math.pi,
                                   places=10)


class PairedTost(unittest.TestCase):
    def test_identical_runs_are_equivalent(self):
        rows = noisy_runs(50, random.Random(1))
        folders = Folders(runs_csv(rows), runs_csv(rows))
        code, out, _ = folders.run()
        folders.close()
        self.assertEqual(code, 0, out)
        self.assertEqual(len(verdicts(out)), 2)
        for line in verdicts(out):
            self.assertIn("equivalent", line)
        self.assertIn("2 of 2 shown", out)

    def test_rounding_noise_on_200_seeds_is_equivalent(self):
        # AFTER differs from BEFORE like an independent run with 10 % spread: mean 0, so with
        # 200 seeds the 90 % interval (about +-0.012 x mean) lies well inside +-5 %.
        rng = random.Random(2)
        rows = noisy_runs(200, rng)
        after = [(e, n, s, r * (1 + 0.1 * rng.gauss(0, 1)), g * (1 + 0.1 * rng.gauss(0, 1)))
                 for e, n, s, r, g in rows]
        folders = Folders(runs_csv(rows), runs_csv(after))
        code, out, _ = folders.run()
        folders.close()
        self.assertEqual(code, 0, out)

    def test_shift_of_ten_percent_is_not_equivalent(self):
        rng = random.Random(3)
        rows = noisy_runs(200, rng)
        after = [(e, n, s, r * 1.10 * (1 + 0.02 * rng.gauss(0, 1)), g * 1.10)
                 for e, n, s, r, g in rows]
        folders = Folders(runs_csv(rows), runs_csv(after))
        code, out, _ = folders.run()
        folders.close()
        self.assertEqual(code, 1, out)
        for line in verdicts(out):
            self.assertIn("not shown", line)
        self.assertIn("0 of 2 shown", out)
        # A margin of 15 % accepts the same 10 % shift.
        folders = Folders(runs_csv(rows), runs_csv(after))
        code, out, _ = folders.run("--margin", "0.15")
        folders.close()
        self.assertEqual(code, 0, out)

    def test_too_few_seeds_is_not_shown(self):
        rng = random.Random(4)
        rows = noisy_runs(5, rng)
        after = [(e, n, s, r * (1 + 0.1 * rng.gauss(0, 1)), g * (1 + 0.1 * rng.gauss(0, 1)))
                 for e, n, s, r, g in rows]
        folders = Folders(runs_csv(rows), runs_csv(after))
        code, out, _ = folders.run()
        folders.close()
        # Five seeds of 10 % noise: the interval is wider than +-5 %.
        self.assertEqual(code, 1, out)
        # One seed cannot give an interval at all; --min-seeds raises the floor.
        folders = Folders(runs_csv(rows[:1]), runs_csv(rows[:1]))
        code, out, _ = folders.run()
        folders.close()
        self.assertEqual(code, 1, out)
        self.assertIn("too few seeds (1 < 2)", out)
        folders = Folders(runs_csv(rows), runs_csv(rows))
        code, out, _ = folders.run("--min-seeds", "200")
        folders.close()
        self.assertEqual(code, 1, out)
        self.assertIn("too few seeds (5 < 200)", out)

    def test_interval_and_p_value_by_hand(self):
        before = [1.0, 2.0, 3.0, 4.0]
        after = [1.1, 2.0, 3.2, 4.1]  # d = 0.1, 0, 0.2, 0.1: mean 0.1, sd sqrt(0.02/3)
        tost = equivalence.paired_tost(before, after, 0.2, 0.05, 2)
        se = math.sqrt(0.02 / 3 / 4)
        half = 2.353363 * se  # t(0.95, 3)
        self.assertAlmostEqual(tost.mean_difference, 0.1, places=12)
        self.assertAlmostEqual(tost.ci_low, 0.1 - half, places=5)
        self.assertAlmostEqual(tost.ci_high, 0.1 + half, places=5)
        self.assertAlmostEqual(tost.margin, 0.5, places=12)
        self.assertTrue(tost.equivalent)
        # p = P(T_3 >= (0.5 - 0.1) / se) for the binding upper test.
        self.assertAlmostEqual(tost.p_value, 1 - equivalence.t_cdf(0.4 / se, 3), places=12)
        # The verdict agrees with the interval: a margin just inside the upper end fails.
        tight = equivalence.paired_tost(before, after, (0.1 + half) / 2.5 * 0.999, 0.05, 2)
        self.assertFalse(tight.equivalent)


class Pairing(unittest.TestCase):
    def test_pairs_by_estimator_particles_seed_and_counts_unpaired(self):
        rng = random.Random(5)
        rows = noisy_runs(30, rng)
        # AFTER lists the runs in another order, lacks seed 1 and has no GOSPA for seed 2.
        after = list(reversed(rows[1:]))
        e, n, s, r, _ = after[-1]
        after[-1] = (e, n, s, r, float("nan"))
        folders = Folders(runs_csv(rows), runs_csv(after))
        code, out, _ = folders.run("--csv", str(Path(tempfile.gettempdir()) / "eq-test.csv"))
        folders.close()
        self.assertEqual(code, 0, out)
        rmse, gospa = verdicts(out)
        self.assertRegex(rmse, r"pos_rmse_m\s+29\s+1\s")
        self.assertRegex(gospa, r"gospa_m\s+28\s+2\s")

    def test_estimator_map_pairs_other_names(self):
        rows = noisy_runs(20, random.Random(6))
        renamed = [("authors", n, s, r, g) for _, n, s, r, g in rows]
        folders = Folders(runs_csv(rows), runs_csv(renamed))
        code, out, _ = folders.run("--estimator-map", "phd3=authors")
        folders.close()
        self.assertEqual(code, 0, out)
        self.assertIn("phd3=authors", out)

    def test_sweep_root_compares_every_folder(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            for side in ("before", "after"):
                for folder in ("pd-0.5", "pd-0.9"):
                    (root / side / folder).mkdir(parents=True)
                    (root / side / folder / "runs.csv").write_text(
                        runs_csv(noisy_runs(10, random.Random(folder))))
                (root / side / "sweep.json").write_text(
                    json.dumps({"folders": ["pd-0.5", "pd-0.9"]}))
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                code = equivalence.main([str(root / "before"), str(root / "after")])
        self.assertEqual(code, 0, out.getvalue())
        self.assertIn("# pd-0.9", out.getvalue())
        self.assertIn("4 of 4 shown", out.getvalue())


class BadInput(unittest.TestCase):
    def test_missing_file_and_unknown_metric_exit_2(self):
        rows = noisy_runs(5, random.Random(7))
        folders = Folders(runs_csv(rows), runs_csv(rows))
        code, _, err = folders.run("--metric", "no_such_column")
        self.assertEqual(code, 2)
        self.assertIn("no column 'no_such_column'", err)
        (folders.after / "runs.csv").unlink()
        code, _, err = folders.run()
        folders.close()
        self.assertEqual(code, 2)
        self.assertIn("missing:", err)

    def test_malformed_values_and_options_exit_2(self):
        bad = COLUMNS + "\nphd3,ten,1,100,1,1,0.1\n"
        folders = Folders(bad, bad)
        code, _, err = folders.run()
        self.assertEqual(code, 2)
        self.assertIn("line 2", err)
        with contextlib.redirect_stderr(io.StringIO()):
            self.assertEqual(folders.run("--margin", "-1")[0], 2)
            self.assertEqual(folders.run("--estimator-map", "phd3")[0], 2)
        folders.close()
        text = COLUMNS + "\nphd3,10,1,100,abc,1,0.1\n"
        folders = Folders(text, text)
        code, _, err = folders.run()
        folders.close()
        self.assertEqual(code, 2)
        self.assertIn("'abc' is not a number", err)


if __name__ == "__main__":
    unittest.main()
