"""The small tools (reports/step_means.py, glmb_runs.py, pcrb_efficiency.py and the authors'
fixture tools compare_traces.py, check_fixture.py, make_fixture.py) on bad input: each ends in one
line naming the file (and the line or field) and a non-zero exit, never a traceback."""

import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
REPORTS = ROOT / "reports"
AUTHORS = ROOT / "reference" / "authors"


def run(script: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(script), *args], capture_output=True, text=True,
                          timeout=120, check=False)


class ToolErrorsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp())

    def expect_one_line(self, result: subprocess.CompletedProcess, *names: str) -> None:
        self.assertNotEqual(result.returncode, 0, result.stdout)
        self.assertNotIn("Traceback", result.stderr)
        lines = [line for line in result.stderr.splitlines() if line.strip()]
        self.assertEqual(len(lines), 1, result.stderr)
        for name in names:
            self.assertIn(name, lines[0])

    def steps_folder(self, text: str) -> Path:
        run_dir = self.tmp / "results" / "runs" / "phd3-N1" / "seed-1"
        run_dir.mkdir(parents=True)
        (run_dir / "steps.csv").write_text(text, encoding="utf-8")
        return run_dir / "steps.csv"

    def test_step_means_names_the_file_line_and_column(self):
        steps = self.steps_folder("step,pos_err_m,map_ospa_m\n0,1.5,2\n1,abc,3\n")
        self.expect_one_line(run(REPORTS / "step_means.py", str(self.tmp / "results"),
                                 str(self.tmp / "out")), str(steps), "line 3", "pos_err_m")
        self.assertFalse((self.tmp / "out" / "runs.csv").exists())

    def test_step_means_line_cut_short_and_missing_column(self):
        steps = self.steps_folder("step,pos_err_m,map_ospa_m\n0,1.5,2\n1,2\n")
        self.expect_one_line(run(REPORTS / "step_means.py", str(self.tmp / "results"),
                                 str(self.tmp / "out")), str(steps), "line 3")
        steps.write_text("step,pos_err_m\n0,1.5\n", encoding="utf-8")
        self.expect_one_line(run(REPORTS / "step_means.py", str(self.tmp / "results"),
                                 str(self.tmp / "out")), str(steps), "map_ospa_m")
        self.expect_one_line(run(REPORTS / "step_means.py", str(self.tmp / "nowhere"),
                                 str(self.tmp / "out")), "nowhere")

    def test_step_means_reads_a_byte_order_mark_and_skips_empty_cells(self):
        self.steps_folder("\ufeffstep,pos_err_m,map_ospa_m\n0,1,\n1,3,4\n")
        result = run(REPORTS / "step_means.py", str(self.tmp / "results"), str(self.tmp / "out"))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual((self.tmp / "out" / "runs.csv").read_text().splitlines()[1],
                         "phd3,1,1,2.0,4.0")

    def test_sweep_json_of_the_wrong_shape(self):
        for text in ("[1, 2]", '{"folders": null}', '{"folders": [1]}', '{"folders": ["../x"]}',
                     "{"):
            root = self.tmp / f"sweep-{abs(hash(text))}"
            root.mkdir()
            (root / "sweep.json").write_text(text, encoding="utf-8")
            for script in ("glmb_runs.py", "pcrb_efficiency.py"):
                args = [str(root)] + ([str(self.tmp / "out")] if script == "glmb_runs.py" else [])
                with self.subTest(script=script, text=text):
                    self.expect_one_line(run(REPORTS / script, *args), "sweep.json")

    def trace(self, name: str, text: str) -> Path:
        for side in ("authors", "phdslam"):
            (self.tmp / side).mkdir(exist_ok=True)
        (self.tmp / "phdslam" / name).write_text("step,particle,prior_x\n1,0,1\n",
                                                  encoding="utf-8")
        path = self.tmp / "authors" / name
        path.write_text(text, encoding="utf-8")
        return path

    def test_compare_traces_bad_files(self):
        header = "step,particle,prior_x\n"
        for text, names in [("\ufeff" + header, ["byte-order mark"]),
                            (header + "1,0\n", ["line 2", "cut short"]),
                            (header + "x,0,1\n", ["line 2", "'step'"]),
                            ("", ["empty"])]:
            path = self.trace("particles.csv", text)
            with self.subTest(text=text):
                result = run(AUTHORS / "compare_traces.py", str(self.tmp / "authors"),
                             str(self.tmp / "phdslam"))
                self.assertEqual(result.returncode, 2, result.stderr)
                self.expect_one_line(result, str(path), *names)
        result = run(AUTHORS / "compare_traces.py", str(self.tmp / "nowhere"),
                     str(self.tmp / "phdslam"))
        self.expect_one_line(result, "nowhere")

    def test_check_fixture_of_the_wrong_shape(self):
        fixture = self.tmp / "fixture"
        fixture.mkdir()
        meta = ('{"scenario": "paper-synthetic", "seeds": %s, "steps": 3, "particles": 1, '
                '"variant": "phd3", "map_every": 1, "tolerance": {"rtol": %s, "atol": 0}}')
        for text, name in [(None, "fixture.json"), ("[1, 2]", "fixture.json"),
                           ('{"seeds": null}', "'scenario'"), (meta % ("null", "0"), "'seeds'"),
                           (meta % ('["1"]', "0"), "'seeds'"), (meta % ("[1]", "NaN"), "rtol"),
                           (meta % ("[1]", "0"), "seed-1")]:
            if text is not None:
                (fixture / "fixture.json").write_text(text, encoding="utf-8")
            with self.subTest(text=text):
                self.expect_one_line(run(AUTHORS / "check_fixture.py", "--replay", "/bin/true",
                                         "--fixture", str(fixture), "--work",
                                         str(self.tmp / "work")), name)
        (fixture / "seed-1").mkdir()
        (fixture / "seed-1" / "draws.csv.gz").write_bytes(b"not gzip")
        self.expect_one_line(run(AUTHORS / "check_fixture.py", "--replay", "/bin/true",
                                 "--fixture", str(fixture), "--work", str(self.tmp / "work")),
                             "draws.csv.gz")

    def test_make_fixture_checks_before_removing_the_old_fixture(self):
        out = self.tmp / "fixture"
        out.mkdir()
        (out / "keep").write_text("old", encoding="utf-8")
        common = ["--steps", "3", "--particles", "1", "--map-every", "1", "--rtol", "0",
                  "--atol", "0", "--reason", "r", "--provenance", "p", "--out", str(out)]
        result = run(AUTHORS / "make_fixture.py", "--traces", str(self.tmp / "t"), "--seeds",
                     "1,x", *common)
        self.assertEqual(result.returncode, 2)
        self.assertIn("--seeds", result.stderr)
        self.assertNotIn("Traceback", result.stderr)
        self.expect_one_line(run(AUTHORS / "make_fixture.py", "--traces", str(self.tmp / "t"),
                                 "--seeds", "1", *common), "seed-1", "draws.csv")
        self.assertTrue((out / "keep").is_file())


if __name__ == "__main__":
    unittest.main()
