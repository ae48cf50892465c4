"""A sweep's root folder (sweep.json) stands for its value folders in make_report."""

import contextlib
import io
import json
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder

import make_report


class SweepRootTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name) / "sweep"
        for pd in (0.5, 0.9):
            make_results_folder(self.root / f"sweep-pd-{pd:g}", FixtureSpec(
                groups=(("phd3", 10),), steps=10, seeds=(1, 2), pd=pd))

    def tearDown(self):
        self.tmp.cleanup()

    def write_sweep(self, folders) -> None:
        (self.root / "sweep.json").write_text(json.dumps(
            {"parameter": "pd", "values": [0.5, 0.9], "folders": folders}), encoding="utf-8")

    def test_the_root_expands_to_its_value_folders_and_gets_the_sensitivity_figure(self):
        self.write_sweep(["sweep-pd-0.5", "sweep-pd-0.9"])
        self.assertEqual(make_report.expand_sweep_roots([self.root]),
                         [self.root / "sweep-pd-0.5", self.root / "sweep-pd-0.9"])
        with contextlib.redirect_stdout(io.StringIO()):
            self.assertEqual(make_report.main([str(self.root)]), 0)
        html = (self.root / "report" / "index.html").read_text(encoding="utf-8")
        self.assertIn('id="sensitivity"', html)
        self.assertTrue(any("sensitivity" in p.name
                            for p in (self.root / "report").glob("*.png")))

    def test_a_malformed_sweep_file_is_named(self):
        self.write_sweep([])
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            self.assertEqual(make_report.main([str(self.root)]), 1)
        self.assertIn("sweep.json", err.getvalue())
        self.assertIn("folders", err.getvalue())


if __name__ == "__main__":
    unittest.main()
