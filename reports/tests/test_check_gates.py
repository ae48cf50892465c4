"""ci/check_gates.py and ci/check-gates.sh: bands, placeholders, run counts, malformed input."""

import contextlib
import importlib.util
import io
import os
import subprocess
import sys
import tempfile
import textwrap
import unittest
from pathlib import Path

from fixture import REPORTS_DIR

CI_DIR = REPORTS_DIR.parent / "ci"
_spec = importlib.util.spec_from_file_location("check_gates", CI_DIR / "check_gates.py")
check_gates = importlib.util.module_from_spec(_spec)
sys.modules["check_gates"] = check_gates
_spec.loader.exec_module(check_gates)

SUMMARY = textwrap.dedent("""\
    estimator,particles,runs,steps,pos_rmse_m,heading_rmse_deg,gospa_mean_m,gospa_std_m,ess_pct,resampling_pct,ms_per_step_mean,failed_runs
    odometry,1,5,4000,161.2202013,13.80902375,182.09,1.08,100,0,0.004,0
    phd3,10,5,4000,2.7,0.35,,,49,5,1.1,0
    """)

THRESHOLDS = textwrap.dedent("""\
    regression:
      scenario: paper-synthetic
      seeds: 1-5
      steps: 4000
      runs:
        - estimators: [odometry]
          particles: [1]
        - estimators: [phd3]
          particles: [1, 10]
    gates:
      - estimator: odometry
        particles: 1
        metric: pos_rmse_m
        band: [161.0, 161.5]
        reason: measured 161.22 m
      - estimator: phd3
        particles: 10
        metric: pos_rmse_m
        band: [2.5, 2.9]
        reason: measured 2.7 m
    """)


def run_check(thresholds: str, summary: str, *extra: str) -> tuple[int, str, str]:
    with tempfile.TemporaryDirectory() as tmp:
        t, s = Path(tmp) / "thresholds.yaml", Path(tmp) / "summary.csv"
        t.write_text(thresholds)
        s.write_text(summary)
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = check_gates.main([str(t), str(s), *extra])
        return code, out.getvalue(), err.getvalue().replace(str(t), "THRESHOLDS")


def line_of(output: str, metric: str, estimator: str) -> str:
    return next(line for line in output.splitlines()
                if line.startswith(estimator) and f" {metric} " in line)


class CheckGatesTest(unittest.TestCase):
    def test_all_inside_passes(self):
        code, out, _ = run_check(THRESHOLDS, SUMMARY)
        self.assertEqual(code, 0, out)
        self.assertIn("PASS", line_of(out, "pos_rmse_m", "odometry"))
        self.assertIn("measured 161.22 m", line_of(out, "pos_rmse_m", "odometry"))
        self.assertIn("2 of 2 gates passed", out)

    def test_value_outside_band_fails_and_names_the_metric(self):
        code, out, _ = run_check(THRESHOLDS.replace("[2.5, 2.9]", "[2.0, 2.6]"), SUMMARY)
        self.assertEqual(code, 1)
        line = line_of(out, "pos_rmse_m", "phd3")
        self.assertIn("FAIL: above band", line)
        self.assertIn("2.7", line)
        self.assertIn("[2, 2.6]", line)
        self.assertIn("PASS", line_of(out, "pos_rmse_m", "odometry"))

    def test_missing_band_fails(self):
        code, out, _ = run_check(THRESHOLDS.replace("[2.5, 2.9]", "null"), SUMMARY)
        self.assertEqual(code, 1)
        self.assertIn("FAIL: no band (placeholder)", line_of(out, "pos_rmse_m", "phd3"))

    def test_missing_row_column_or_value_fails(self):
        extra = [("phd3", 1, "pos_rmse_m", "[1, 5]", "no such row"),
                 ("phd3", 10, "gospa_mean_m", "[30, 40]", "empty cell"),
                 ("phd3", 10, "da_tpr", "[0.9, 1]", "no column")]
        text = THRESHOLDS + "".join(
            f"  - estimator: {e}\n    particles: {n}\n    metric: {m}\n    band: {b}\n"
            f"    reason: {r}\n" for e, n, m, b, r in extra)
        code, out, _ = run_check(text, SUMMARY)
        self.assertEqual(code, 1)
        self.assertIn("FAIL: no row in summary.csv", out)
        self.assertIn("FAIL: value empty", line_of(out, "gospa_mean_m", "phd3"))
        self.assertIn("FAIL: no column 'da_tpr'", out)

    def test_fewer_runs_than_seeds_fail_unless_waived(self):
        summary = SUMMARY.replace("phd3,10,5,", "phd3,10,3,")
        code, out, _ = run_check(THRESHOLDS, summary)
        self.assertEqual(code, 1)
        self.assertIn("FAIL: 3 of 5 runs finished", line_of(out, "pos_rmse_m", "phd3"))
        code, _, _ = run_check(THRESHOLDS, summary, "--no-run-count")
        self.assertEqual(code, 0)

    def test_malformed_thresholds_exit_2_naming_the_entry(self):
        for bad, expected in (
            ("[161.0, 161.5]", "gates[0]: band [161.5, 161.0] must be finite with low <= high"),
            ("band: [161.0, 161.5]", "gates[0]: unknown key(s) ['bnad']"),
            ("seeds: 1-5", "regression: seeds must look like"),
        ):
            replacement = {"[161.0, 161.5]": "[161.5, 161.0]",
                           "band: [161.0, 161.5]": "bnad: [161.0, 161.5]",
                           "seeds: 1-5": "seeds: one-five"}[bad]
            code, _, err = run_check(THRESHOLDS.replace(bad, replacement), SUMMARY)
            self.assertEqual(code, 2, bad)
            self.assertIn(f"THRESHOLDS: {expected}", err)

    def test_malformed_summary_exit_2(self):
        code, _, err = run_check(THRESHOLDS, SUMMARY.replace("161.2202013", "fast"))
        self.assertEqual(code, 2)
        self.assertIn("line 2, column 'pos_rmse_m': 'fast' is not a number", err)

    def test_run_arguments(self):
        with tempfile.TemporaryDirectory() as tmp:
            t = Path(tmp) / "t.yaml"
            t.write_text(THRESHOLDS)
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                self.assertEqual(check_gates.main([str(t), "--run-args"]), 0)
        lines = out.getvalue().splitlines()
        self.assertEqual(lines[1].split("\t"), [
            "--scenario", "paper-synthetic", "--estimator", "phd3", "--particles", "1,10",
            "--seeds", "1-5", "--steps", "4000"])

    def test_repository_thresholds_are_well_formed(self):
        regression, gates = check_gates.load_thresholds(CI_DIR / "thresholds.yaml")
        self.assertGreaterEqual(regression.seed_count(), 1)
        self.assertTrue(gates)
        for gate in gates:
            if gate.band is None:
                self.assertIn("PLACEHOLDER", gate.reason, gate)
            else:
                self.assertLessEqual(gate.band[0], gate.band[1], gate)
        gated = {g.estimator for g in gates}
        run = {e for r in regression.runs for e in r.estimators}
        self.assertLessEqual(gated, run, "every gated estimator is part of the regression run")


class CheckGatesScriptTest(unittest.TestCase):
    """check-gates.sh against a stand-in phdslam that writes a fixed summary.csv."""

    def test_script_runs_the_regression_and_reports_gates(self):
        with tempfile.TemporaryDirectory() as tmp:
            build = Path(tmp) / "build"
            (build / "apps").mkdir(parents=True)
            fake = build / "apps" / "phdslam"
            calls = Path(tmp) / "calls.txt"
            fake.write_text(
                "#!/usr/bin/env bash\n"
                f'echo "$@" >> {calls}\n'
                'while [[ $# -gt 0 ]]; do\n'
                '  if [[ "$1" == --out ]]; then out="$2"; fi\n'
                "  shift\n"
                "done\n"
                'mkdir -p "$out"\n'
                f"cat > \"$out/summary.csv\" <<'CSV'\n{SUMMARY}CSV\n")
            fake.chmod(0o755)
            thresholds = Path(tmp) / "thresholds.yaml"
            thresholds.write_text(THRESHOLDS.replace("[2.5, 2.9]", "null"))
            done = subprocess.run(["bash", str(CI_DIR / "check-gates.sh"), str(build)],
                                  capture_output=True, text=True, timeout=120,
                                  env={**os.environ,
                                       "PHDSLAM_GATES_THRESHOLDS": str(thresholds)})
            self.assertEqual(done.returncode, 1, done.stdout + done.stderr)  # placeholders fail
            self.assertIn("PASS", line_of(done.stdout, "pos_rmse_m", "odometry"))
            self.assertIn("FAIL: no band (placeholder)",
                          line_of(done.stdout, "pos_rmse_m", "phd3"))
            calls_made = calls.read_text().splitlines()
            self.assertEqual(len(calls_made), 2)
            self.assertTrue(calls_made[0].startswith(
                "run --scenario paper-synthetic --estimator odometry --particles 1 --seeds 1-5 "
                "--steps 4000 --out "), calls_made[0])
            self.assertIn("--estimator phd3 --particles 1,10", calls_made[1])

    def test_script_without_program_exits_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            done = subprocess.run(["bash", str(CI_DIR / "check-gates.sh"), tmp],
                                  capture_output=True, text=True, timeout=60)
        self.assertEqual(done.returncode, 2)
        self.assertIn("no phdslam program", done.stderr)


if __name__ == "__main__":
    unittest.main()
