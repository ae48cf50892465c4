"""The delta-GLMB-SLAM paper's numbers (phdslam_reports.glmb_paper): per-step RMSE with the
heading wrapped, mean +- std per clutter rate, and the report section, on hand-made results."""

import json
import math
import tempfile
import unittest
from pathlib import Path

import fixture  # noqa: F401  (first: puts reports/ on sys.path, checks the interpreter)
import numpy as np
from phdslam_reports import glmb_paper
from phdslam_reports.report import build_report
from phdslam_reports.results import STEPS_COLUMNS, Group, ResultsFolder


def write_run(folder: Path, rows: list[dict[str, float]], map_ospa: list[float] | None) -> None:
    """A steps.csv (every STEPS_COLUMNS column; map_ospa_m last when given) and a map.csv."""
    folder.mkdir(parents=True, exist_ok=True)
    header = list(STEPS_COLUMNS) + (["map_ospa_m"] if map_ospa is not None else [])
    lines = [",".join(header)]
    for k, row in enumerate(rows):
        values = {c: 0.0 for c in STEPS_COLUMNS}
        values.update(step=k, t=0.2 * k, **row)
        cells = [repr(float(values[c])) for c in STEPS_COLUMNS]
        if map_ospa is not None:
            cells.append(repr(map_ospa[k]))
        lines.append(",".join(cells))
    (folder / "steps.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    (folder / "map.csv").write_text("x,y,weight,pxx,pxy,pyy\n1,1,1,0.01,0,0.01\n",
                                    encoding="utf-8")


def write_folder(root: Path, clutter: float, runs: dict[str, list[tuple]]) -> Path:
    """A glmb-sim results folder: runs[estimator] = [(steps rows, map_ospa), ...] (N = 10)."""
    root.mkdir(parents=True, exist_ok=True)
    (root / "config.json").write_text(json.dumps({
        "scenario": {"name": "glmb-sim", "options": {"clutter_rate": clutter}},
        "metrics": {"gospa_c": 20.0, "gospa_p": 2.0, "gps_window_s": 0.025, "map_ospa_c": 0.5},
        "estimators": {e: {} for e in runs}, "seeds": [1, 2]}), encoding="utf-8")
    (root / "truth_map.csv").write_text("x,y,weight,pxx,pxy,pyy\n1,1,1,,,\n", encoding="utf-8")
    for estimator, seeds in runs.items():
        for seed, (rows, ospa) in enumerate(seeds, start=1):
            write_run(root / "runs" / f"{estimator}-N10" / f"seed-{seed}", rows, ospa)
    return root


def pose_rows(errors: list[tuple[float, float, float]], ms: float = 1.0) -> list[dict]:
    """Rows with true pose (1, 2, pi - 0.05) and the given (dx, dy, dtheta) errors."""
    rows = []
    for dx, dy, dth in errors:
        truth = math.pi - 0.05
        rows.append({"x": 1 + dx, "y": 2 + dy, "theta": truth + dth, "x_true": 1.0,
                     "y_true": 2.0, "theta_true": truth, "ms": ms})
    return rows


class PerStepRmseTest(unittest.TestCase):
    def test_root_mean_square_over_runs_per_step(self):
        a = {"x": np.array([1.0, 3.0]), "x_true": np.zeros(2), "y": np.zeros(2),
             "y_true": np.zeros(2), "theta": np.zeros(2), "theta_true": np.zeros(2)}
        b = dict(a, x=np.array([-1.0, 4.0]), y=np.array([0.0, 2.0]))
        r = glmb_paper.per_step_rmse([a, b])
        np.testing.assert_allclose(r.x, [1.0, math.sqrt((9 + 16) / 2)])
        np.testing.assert_allclose(r.y, [0.0, math.sqrt(2.0)])
        self.assertEqual(r.runs, 2)

    def test_heading_difference_is_wrapped(self):
        # 179 deg estimated against -179 deg true: 2 deg, not 358 deg.
        run = {"x": np.zeros(1), "x_true": np.zeros(1), "y": np.zeros(1), "y_true": np.zeros(1),
               "theta": np.radians([179.0]), "theta_true": np.radians([-179.0])}
        other = dict(run, theta=np.radians([-178.0]), theta_true=np.radians([178.0]))
        r = glmb_paper.per_step_rmse([run, other])
        np.testing.assert_allclose(r.heading_deg, [math.sqrt((4 + 16) / 2)], rtol=1e-9)

    def test_shorter_runs_leave_their_missing_steps_out(self):
        long = {c: np.zeros(3) for c in ("x", "y", "theta", "x_true", "y_true", "theta_true")}
        long["x"] = np.array([1.0, 1.0, 2.0])
        short = {c: np.zeros(2) for c in long}
        r = glmb_paper.per_step_rmse([long, short])
        np.testing.assert_allclose(r.x, [math.sqrt(0.5), math.sqrt(0.5), 2.0])


class MeanStdTest(unittest.TestCase):
    def test_sample_standard_deviation(self):
        m = glmb_paper.mean_std([1.0, 2.0, 3.0, math.nan])
        self.assertAlmostEqual(m.mean, 2.0)
        self.assertAlmostEqual(m.std, 1.0)
        self.assertEqual(m.count, 3)
        self.assertTrue(math.isnan(glmb_paper.mean_std([4.0]).std))
        self.assertEqual(glmb_paper.mean_std([]).count, 0)


class FalseLandmarksTest(unittest.TestCase):
    def test_estimates_without_a_true_landmark_within_the_cutoff(self):
        truth = np.array([[0.0, 0.0], [1.0, 0.0]])
        # One close to each truth, one 0.6 m away (false at c = 0.5), one duplicate of the first
        # (only one estimate can take a truth).
        estimate = np.array([[0.1, 0.0], [1.0, 0.2], [3.0, 0.6], [0.0, 0.1]])
        self.assertEqual(glmb_paper.false_landmarks(estimate, truth, 0.5), 2)
        self.assertEqual(glmb_paper.false_landmarks(estimate, truth, 5.0), 2)  # 4 for 2 truths
        self.assertEqual(glmb_paper.false_landmarks(estimate[:2], truth, 0.15), 1)
        self.assertEqual(glmb_paper.false_landmarks(np.zeros((0, 2)), truth, 0.5), 0)
        self.assertEqual(glmb_paper.false_landmarks(estimate, np.zeros((0, 2)), 0.5), 4)


class ClutterPointsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        root = Path(self.tmp.name)
        self.low = write_folder(root / "clutter_rate-1", 1.0, {
            "glmb2": [(pose_rows([(0.1, 0.0, 0.01), (0.3, 0.0, -0.02)], ms=2.0), [0.2, 0.4]),
                      (pose_rows([(-0.1, 0.0, 0.03), (0.1, 0.2, 0.0)], ms=4.0), [0.1, 0.1])],
            "phd3": [(pose_rows([(0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]), [0.5, 0.5])]})
        self.high = write_folder(root / "clutter_rate-15", 15.0, {
            "glmb2": [(pose_rows([(0.2, 0.0, 0.0), (0.2, 0.0, 0.0)], ms=8.0), [0.3, 0.3])]})
        self.folders = [ResultsFolder(self.low), ResultsFolder(self.high)]

    def tearDown(self):
        self.tmp.cleanup()

    def test_points_per_clutter_rate_and_group(self):
        points = glmb_paper.glmb_points(self.folders)
        self.assertEqual([(p.clutter_rate, p.group) for p in points],
                         [(1.0, Group("glmb2", 10)), (1.0, Group("phd3", 10)),
                          (15.0, Group("glmb2", 10))])
        glmb2 = points[0]
        np.testing.assert_allclose(glmb2.rmse.x, [0.1, math.sqrt((0.09 + 0.01) / 2)])
        np.testing.assert_allclose(glmb2.rmse.heading_deg,
                                   np.degrees([math.sqrt((1e-4 + 9e-4) / 2),
                                               math.sqrt(4e-4 / 2)]), rtol=1e-9)
        # Per-run OSPA means 0.3 and 0.1: mean 0.2, std sqrt(0.02).
        self.assertAlmostEqual(glmb2.ospa.mean, 0.2)
        self.assertAlmostEqual(glmb2.ospa.std, math.sqrt(0.02))
        # Time per step pooled over 4 steps: 2, 2, 4, 4.
        self.assertAlmostEqual(glmb2.step_ms.mean, 3.0)
        self.assertAlmostEqual(glmb2.step_ms.std, math.sqrt(4.0 / 3.0))
        self.assertEqual(glmb_paper.map_ospa_cutoff(self.folders[0]), 0.5)

    def test_heading_wrap_applies_across_pi(self):
        # True heading pi - 0.05; the estimate pi + 0.05 written wrapped as -pi + 0.05: the error
        # is 0.1 rad, not 2 pi - 0.1.
        rows = pose_rows([(0.0, 0.0, 0.1)])
        rows[0]["theta"] -= 2.0 * math.pi
        folder = write_folder(Path(self.tmp.name) / "wrap", 5.0, {"glmb1": [(rows, [0.0])]})
        steps = (folder / "runs" / "glmb1-N10" / "seed-1" / "steps.csv").read_text()
        self.assertLess(float(steps.splitlines()[1].split(",")[4]), -3.0)
        point = glmb_paper.glmb_points([ResultsFolder(folder)])[0]
        np.testing.assert_allclose(point.rmse.heading_deg, [math.degrees(0.1)], rtol=1e-9)

    def test_run_rows_for_compare(self):
        rows = glmb_paper.run_rows(ResultsFolder(self.low))
        self.assertEqual([r[:3] for r in rows], [["glmb2", 10, 1], ["glmb2", 10, 2],
                                                 ["phd3", 10, 1]])
        self.assertAlmostEqual(rows[0][3], 0.3)  # mean of 0.2, 0.4
        self.assertEqual(rows[0][4], 0.0)  # map (1, 1) on the true landmark (1, 1)
        self.assertAlmostEqual(rows[0][5], math.sqrt((0.01 + 0.09) / 2))
        self.assertAlmostEqual(rows[1][6], math.sqrt(0.04 / 2))

    def test_other_scenarios_are_ignored(self):
        config = json.loads((self.low / "config.json").read_text())
        config["scenario"]["name"] = "paper-synthetic"
        (self.low / "config.json").write_text(json.dumps(config))
        points = glmb_paper.glmb_points([ResultsFolder(self.low)])
        self.assertEqual(points, [])

    def test_report_has_the_section_with_its_figures(self):
        out = Path(self.tmp.name) / "report"
        report = build_report([self.low, self.high], out)
        section = report.section("glmb-paper")
        self.assertIn("c = 0.5 m", section.body)
        for name in ("glmb-rmse-over-time.png", "glmb-ospa-time.png",
                     "glmb-trajectory-map.png"):
            self.assertTrue((out / name).is_file(), name)
        self.assertIn("0.2 \u00b1", section.body)


if __name__ == "__main__":
    unittest.main()
