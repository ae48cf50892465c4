"""Sweeps over any parameter: sweep.csv with one leading column per swept parameter gives a line
plot (one parameter) or heat maps (two) in the sensitivity section."""

import contextlib
import io
import json
import math
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder

import make_report
from phdslam_reports.csv_table import ResultsFormatError
from phdslam_reports.figures.sweep_heat_map import heat_map_grids, plot_sweep_heat_maps
from phdslam_reports.sweep_table import read_sweep_table, sweep_root_of


def write_sweep(root: Path, parameters: list[tuple[str, list]], folders: list[str]) -> None:
    """sweep.json and sweep.csv of the point folders, as 'phdslam run' writes them."""
    (root / "sweep.json").write_text(json.dumps({
        "parameters": [{"parameter": p, "values": v} for p, v in parameters],
        "folders": folders}), encoding="utf-8")
    points = [[]]
    for _, values in parameters:
        points = [p + [v] for p in points for v in values]
    header, rows = None, []
    for point, folder in zip(points, folders):
        lines = (root / folder / "summary.csv").read_text(encoding="utf-8").splitlines()
        header = header or lines[0]
        rows += [",".join(f"{v:.10g}" if isinstance(v, (int, float)) else str(v)
                          for v in point) + "," + line for line in lines[1:] if line]
    (root / "sweep.csv").write_text(
        ",".join(p for p, _ in parameters) + "," + header + "\n" + "\n".join(rows) + "\n",
        encoding="utf-8")


class SweepGridTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name) / "grid"
        self.folders = []
        for clutter in (2, 8):
            for landmarks in (40, 80, 160):
                name = f"sweep-clutter_rate-{clutter}-landmarks-{landmarks}"
                make_results_folder(self.root / name, FixtureSpec(
                    groups=(("phd3", 4), ("odometry", 1)), steps=10, seeds=(1, 2),
                    scenario="generated", clutter_rate=clutter, landmarks=landmarks // 8))
                self.folders.append(name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_the_table_keeps_the_parameters_and_every_row(self):
        write_sweep(self.root, [("clutter_rate", [2, 8]), ("landmarks", [40, 80, 160])],
                    self.folders)
        table = read_sweep_table(self.root)
        self.assertEqual(table.parameters, ("clutter_rate", "landmarks"))
        self.assertEqual(table.values, (("2", "8"), ("40", "80", "160")))
        self.assertEqual(len(table.rows), 6 * 2)
        self.assertEqual(sweep_root_of(self.root / self.folders[3]), self.root)
        grids = heat_map_grids(table)
        self.assertEqual(sorted(grids), [("odometry", 1), ("phd3", 4)])
        gospa = grids[("phd3", 4)]["gospa_mean_m"]
        self.assertEqual(gospa.shape, (2, 3))
        self.assertTrue(all(math.isfinite(v) for v in gospa.flat))
        # Cell (clutter 8, landmarks 80) is that point's summary row.
        summary = (self.root / "sweep-clutter_rate-8-landmarks-80" / "summary.csv").read_text()
        header, *rows = summary.splitlines()
        row = next(r.split(",") for r in rows if r.startswith("phd3,4,"))
        self.assertAlmostEqual(gospa[1, 1], float(row[header.split(",").index("gospa_mean_m")]))
        self.assertIsNotNone(plot_sweep_heat_maps(table))

    def test_the_report_draws_heat_maps_for_a_grid(self):
        write_sweep(self.root, [("clutter_rate", [2, 8]), ("landmarks", [40, 80, 160])],
                    self.folders)
        with contextlib.redirect_stdout(io.StringIO()):
            self.assertEqual(make_report.main([str(self.root)]), 0)
        html = (self.root / "report" / "index.html").read_text(encoding="utf-8")
        self.assertIn("Sensitivity: parameter sweeps", html)
        self.assertIn("clutter_rate \u00d7 landmarks", html)
        self.assertIn("sweep point clutter_rate = 8, landmarks = 80;", html)
        self.assertTrue((self.root / "report" / "sweep1-heat-map.png").is_file())
        self.assertFalse((self.root / "report" / "fig5-sensitivity.png").exists())

    def test_the_report_draws_lines_for_one_parameter(self):
        folders = [f for f in self.folders if "clutter_rate-2-" in f]
        for folder in folders:
            (self.root / folder).rename(self.root / folder.replace("clutter_rate-2-", ""))
        folders = [f.replace("clutter_rate-2-", "") for f in folders]
        write_sweep(self.root, [("landmarks", [40, 80, 160])], folders)
        with contextlib.redirect_stdout(io.StringIO()):
            self.assertEqual(make_report.main([str(self.root)]), 0)
        self.assertTrue((self.root / "report" / "sweep1-lines.png").is_file())

    def test_leading_columns_must_be_the_swept_parameters(self):
        write_sweep(self.root, [("clutter_rate", [2, 8]), ("landmarks", [40, 80, 160])],
                    self.folders)
        spec = json.loads((self.root / "sweep.json").read_text())
        spec["parameters"][1]["parameter"] = "speed"
        (self.root / "sweep.json").write_text(json.dumps(spec))
        with self.assertRaises(ResultsFormatError) as caught:
            read_sweep_table(self.root)
        self.assertIn("sweep.csv", str(caught.exception))
        self.assertIn("speed", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
