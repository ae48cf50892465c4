"""Tests of the accuracy gates (ci/gates.py and its modules, ci/check-gates.sh): the three tiers on
made-up results, the statistics against known values, and every kind of bad input."""

from __future__ import annotations

import contextlib
import csv
import io
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import textwrap
import unittest
from pathlib import Path

CI = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(CI))

import gate_stats  # noqa: E402
import gates  # noqa: E402

COLUMNS = ["estimator", "particles", "seed", "steps", "pos_rmse_m", "gospa_m", "pos_err_count",
           "ms_per_step_mean", "ms_run"]

GATES_YAML = """\
version: 1
baseline: baseline
family_false_alarm: 0.05
power: 0.8
margin: {margin}
suites:
  - name: toy
    scenario: paper-synthetic
    steps: 100
    seeds: 1-{seeds}
    runs:
      - estimators: [phd3]
        particles: [1]
paired:
  - suite: toy
    estimator: phd3
    particles: 1
    metric: pos_rmse_m
    spread: {{redraw: 0.2, keep: 0.05}}
    reason: made up for the test
  - suite: toy
    estimator: phd3
    particles: 1
    metric: gospa_m
    spread: {{redraw: 0.2, keep: 0.05}}
    reason: made up for the test
anchors:
  - suite: toy
    estimator: phd3
    particles: 1
    metric: pos_rmse_m
    statistic: pooled-rmse
    tolerance: 0.1
    references:
      - {{source: made-up paper, value: 2.3, se: 0.05}}
    reason: made up for the test
"""


def runs_text(seeds: int, scale: float = 1.0, noise: float = 0.0, seed: int = 7,
              estimator: str = "phd3") -> str:
    rng = random.Random(seed)
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(COLUMNS)
    for s in range(1, seeds + 1):
        base = random.Random(s)
        pos = 2.0 * math.exp(0.3 * base.gauss(0, 1))
        gospa = 40.0 * math.exp(0.2 * base.gauss(0, 1))
        # a neutral re-draw: pairs of seeds moved by exp(+e) and exp(-e), so no net change
        if s % 2 == 1:
            e = noise * abs(rng.gauss(0, 1))
        jitter = math.exp(e if s % 2 == 1 else -e) if noise else 1.0
        w.writerow([estimator, 1, s, 100, f"{pos * scale * jitter:.10g}",
                    f"{gospa * scale * jitter:.10g}", 100, f"{rng.random():.6g}", "12.5"])
    return out.getvalue()


def run_gates(*argv: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = gates.main(list(argv))
    return code, out.getvalue(), err.getvalue()


class Workspace:
    """A gates file, its baseline and one results folder in a temporary folder."""

    def __init__(self, root: Path, seeds: int = 400, margin: float = 0.05):
        self.root = root
        root.mkdir(parents=True, exist_ok=True)
        self.gates = root / "gates.yaml"
        self.gates.write_text(GATES_YAML.format(seeds=seeds, margin=margin), encoding="utf-8")
        self.seeds = seeds

    def results(self, name: str, text: str, scenario: str = "paper-synthetic") -> Path:
        folder = self.root / name / "toy"
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "runs.csv").write_text(text, encoding="utf-8")
        (folder / "config.json").write_text(json.dumps({"scenario": {"name": scenario}}),
                                            encoding="utf-8")
        return folder.parent

    def store_baseline(self) -> None:
        results = self.results("base", runs_text(self.seeds))
        code, _, err = run_gates("update-baseline", "--gates", str(self.gates), "--results",
                                 str(results))
        assert code == 0, err

    def check(self, results: Path, *extra: str) -> tuple[int, str, str]:
        return run_gates("check", "--gates", str(self.gates), "--results", str(results), *extra)


class StatisticsTest(unittest.TestCase):
    def test_t_quantiles_match_the_tables(self):
        for p, df, expected in ((0.975, 10, 2.228139), (0.995, 12, 3.054540), (0.95, 30, 1.697261),
                                (0.999, 20, 3.551808), (0.975, 1000, 1.962339)):
            self.assertAlmostEqual(gate_stats.student_t_quantile(p, df), expected, delta=3e-3)

    def test_seed_count_and_detectable_effect_are_inverse(self):
        for spread, margin in ((0.5, 0.05), (0.25, 0.05), (0.1, 0.1)):
            n = gate_stats.seeds_needed(spread, margin, 0.003, 0.8, 0.2)
            self.assertLessEqual(gate_stats.minimum_detectable_effect(spread, n, 0.003, 0.8, 0.2),
                                 margin + 1e-12)
            self.assertGreater(gate_stats.minimum_detectable_effect(spread, n - 1, 0.003, 0.8, 0.2),
                               margin)
            self.assertGreaterEqual(gate_stats.power_at(margin, spread, n, 0.003, 0.2), 0.8)

    def test_trimmed_mean_ignores_the_tails(self):
        values = [0.0] * 80 + [10.0] * 10 + [-10.0] * 5
        self.assertEqual(gate_stats.trimmed_mean(values, 0.2), 0.0)
        self.assertEqual(gate_stats.winsorised_sd([1.0] * 10, 0.2), 0.0)

    def test_power_is_what_the_test_delivers(self):
        """Monte Carlo of the Yuen test: regressions of the margin fail at about the planned rate,
        neutral changes at about alpha."""
        rng = random.Random(11)
        spread, margin, alpha = 0.3, 0.1, 0.01
        n = gate_stats.seeds_needed(spread, margin, alpha, 0.8, 0.2)
        fails_at_margin = fails_at_zero = 0
        trials = 400
        for _ in range(trials):
            d = [rng.gauss(0, spread) for _ in range(n)]
            fails_at_zero += gate_stats.yuen_test(d, 0.2, alpha).rejected
            shifted = [v + math.log1p(margin) for v in d]
            fails_at_margin += gate_stats.yuen_test(shifted, 0.2, alpha).rejected
        self.assertGreater(fails_at_margin / trials, 0.72)
        self.assertLess(fails_at_zero / trials, 0.04)


class TiersTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.ws = Workspace(Path(self.tmp.name))
        self.ws.store_baseline()

    def tearDown(self):
        self.tmp.cleanup()

    def test_identical_results_pass_every_tier(self):
        code, out, _ = self.ws.check(self.ws.results("same", runs_text(self.ws.seeds)))
        self.assertEqual(code, 0, out)
        self.assertIn("gates: exact PASS, paired PASS, anchor PASS", out)
        self.assertIn("identical", out)

    def test_timing_columns_are_not_compared(self):
        text = runs_text(self.ws.seeds).replace(",12.5\n", ",99.0\n")
        code, out, _ = self.ws.check(self.ws.results("timing", text))
        self.assertEqual(code, 0, out)

    def test_a_regression_above_the_margin_fails_the_paired_tier(self):
        code, out, _ = self.ws.check(self.ws.results("worse", runs_text(self.ws.seeds, 1.08,
                                                                        noise=0.2)))
        self.assertEqual(code, 1)
        self.assertIn("paired FAIL", out)
        self.assertIn("pos_rmse_m moved in", out)  # the exact tier names the column

    def test_a_neutral_redraw_passes_the_paired_tier_but_not_the_exact_one(self):
        code, out, _ = self.ws.check(self.ws.results("redraw", runs_text(self.ws.seeds,
                                                                         noise=0.2)))
        self.assertEqual(code, 1)
        self.assertIn("exact FAIL, paired PASS, anchor PASS", out)

    def test_an_improvement_passes_the_paired_tier(self):
        code, out, _ = self.ws.check(self.ws.results("better", runs_text(self.ws.seeds, 0.8)),
                                     "--tiers", "paired")
        self.assertEqual(code, 0, out)

    def test_the_anchor_fails_far_from_the_published_value(self):
        code, out, _ = self.ws.check(self.ws.results("far", runs_text(self.ws.seeds, 1.5)),
                                     "--tiers", "anchor")
        self.assertEqual(code, 1)
        self.assertIn("anchor FAIL", out)

    def test_csv_output_has_a_row_per_gate(self):
        path = self.ws.root / "gates.csv"
        self.ws.check(self.ws.results("same", runs_text(self.ws.seeds)), "--csv", str(path))
        with path.open(encoding="utf-8") as f:
            tiers = [row["tier"] for row in csv.DictReader(f)]
        self.assertEqual(tiers, ["exact", "paired", "paired", "anchor"])

    def test_update_refuses_an_inferior_baseline_unless_told(self):
        worse = self.ws.results("worse", runs_text(self.ws.seeds, 1.2))
        code, _, err = run_gates("update-baseline", "--gates", str(self.ws.gates), "--results",
                                 str(worse))
        self.assertEqual(code, 1)
        self.assertIn("REFUSED", err)
        code, _, _ = run_gates("update-baseline", "--gates", str(self.ws.gates), "--results",
                               str(worse), "--accept-inferior", "the model is corrected")
        self.assertEqual(code, 0)
        header = json.loads((self.ws.root / "baseline" / "baseline.json").read_text())
        self.assertEqual(header["accepted_inferior"], "the model is corrected")
        self.assertFalse(all(g["passed"] for g in header["verdict"]["paired"]))
        code, out, _ = self.ws.check(worse, "--tiers", "exact,paired")
        self.assertEqual(code, 0, out)
        self.assertIn("ACCEPTED DESPITE A FAILED PAIRED TIER: the model is corrected", out)


class FewerSeedsTest(unittest.TestCase):
    def test_the_baseline_moves_to_fewer_seeds_with_a_verdict_but_not_to_more(self):
        with tempfile.TemporaryDirectory() as tmp:
            ws = Workspace(Path(tmp))
            ws.store_baseline()
            ws.gates.write_text(ws.gates.read_text().replace("seeds: 1-400", "seeds: 1-300")
                                .replace("margin: 0.05", "margin: 0.06"))
            results = ws.results("fewer", runs_text(300))
            code, out, err = run_gates("update-baseline", "--gates", str(ws.gates), "--results",
                                       str(results))
            self.assertEqual(code, 0, err)
            self.assertIn("paired tier", out)
            header = json.loads((ws.root / "baseline" / "baseline.json").read_text())
            self.assertEqual(header["suites"]["toy"]["definition"]["seeds"], "1-300")
            self.assertEqual(len(header["verdict"]["paired"]), 2)
            ws.gates.write_text(ws.gates.read_text().replace("seeds: 1-300", "seeds: 1-400"))
            code, _, err = run_gates("update-baseline", "--gates", str(ws.gates), "--results",
                                     str(ws.results("more", runs_text(400))))
            self.assertEqual(code, 2)
            self.assertIn("definition.seeds", err)


class BadInputTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.ws = Workspace(Path(self.tmp.name))
        self.ws.store_baseline()

    def tearDown(self):
        self.tmp.cleanup()

    def assert_bad(self, results: Path, *needles: str) -> None:
        code, _, err = self.ws.check(results)
        self.assertEqual(code, 2, err)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        for needle in needles:
            self.assertIn(needle, err)

    def test_a_baseline_of_another_seed_set(self):
        self.ws.gates.write_text(self.ws.gates.read_text().replace("seeds: 1-400", "seeds: 2-401"))
        self.assert_bad(self.ws.results("r", runs_text(401)), "baseline.json",
                        "definition.seeds", "another scenario, seed set")

    def test_a_baseline_of_another_scenario(self):
        self.ws.gates.write_text(self.ws.gates.read_text().replace("scenario: paper-synthetic",
                                                                   "scenario: generated"))
        self.assert_bad(self.ws.results("r", runs_text(400), scenario="generated"),
                        "definition.scenario")

    def test_results_of_another_scenario(self):
        self.assert_bad(self.ws.results("r", runs_text(400), scenario="glmb-sim"), "config.json",
                        "scenario.name", "glmb-sim")

    def test_a_missing_run(self):
        lines = runs_text(400).splitlines(keepends=True)
        del lines[17]
        self.assert_bad(self.ws.results("r", "".join(lines)), "runs.csv", "seed 17",
                        "is missing")

    def test_a_nan(self):
        text = runs_text(400).replace("phd3,1,5,100,", "phd3,1,5,100,nan#", 1)
        text = text.replace("nan#", "nan,", 1)
        lines = text.splitlines(keepends=True)
        lines[5] = lines[5].split(",")
        lines[5][4] = "nan"
        lines[5] = ",".join(lines[5][:len(COLUMNS)]) + "\n"
        self.assert_bad(self.ws.results("r", "".join(lines)), "runs.csv", "line 6", "pos_rmse_m",
                        "not a finite number")

    def test_a_tampered_header(self):
        path = self.ws.root / "baseline" / "baseline.json"
        header = json.loads(path.read_text())
        header["commit"] = "0123456789ab"
        path.write_text(json.dumps(header))
        self.assert_bad(self.ws.results("r", runs_text(400)), "baseline.json", "checksum",
                        "edited by hand")

    def test_a_tampered_table(self):
        path = self.ws.root / "baseline" / "toy.csv"
        path.write_text(path.read_text().replace("phd3,1,3,", "phd3,1,3,", 1) + "\n")
        self.assert_bad(self.ws.results("r", runs_text(400)), "toy.csv", "SHA-256")

    def test_results_of_another_estimator(self):
        self.assert_bad(self.ws.results("r", runs_text(400, estimator="phd1")), "runs.csv",
                        "field 'estimator'", "no run of phd3 N=1", "phd1 N=1")

    def test_a_byte_order_mark(self):
        self.assert_bad(self.ws.results("r", "\ufeff" + runs_text(400)), "byte-order mark")

    def test_a_duplicated_run(self):
        text = runs_text(400)
        self.assert_bad(self.ws.results("r", text + text.splitlines(keepends=True)[3]),
                        "listed twice")

    def test_a_line_cut_short(self):
        self.assert_bad(self.ws.results("r", runs_text(400)[:-9]), "cut short")

    def test_a_missing_results_file(self):
        self.assert_bad(self.ws.root / "nothing", "missing (runs table)")

    def test_a_gates_file_whose_margin_needs_more_seeds(self):
        ws = Workspace(self.ws.root / "small", seeds=20)
        code, _, err = run_gates("plan", "--gates", str(ws.gates))
        self.assertEqual(code, 2)
        self.assertIn("needs", err)
        self.assertIn("raise its seeds or state the larger margin", err)

    def test_hostile_yaml(self):
        cases = {"two documents": "version: 1\n---\nversion: 1\n",
                 "not a mapping": "[1, 2]\n",
                 "unknown key": self.ws.gates.read_text() + "bogus: 1\n",
                 "deep nesting": "version: 1\nsuites: " + "[" * 5000 + "]" * 5000 + "\n",
                 "a NaN margin": self.ws.gates.read_text().replace("margin: 0.05", "margin: .nan"),
                 "a huge seed range": self.ws.gates.read_text().replace("1-400", "1-99999999")}
        for what, text in cases.items():
            with self.subTest(what):
                path = self.ws.root / "hostile.yaml"
                path.write_text(text)
                code, _, err = run_gates("plan", "--gates", str(path))
                self.assertEqual(code, 2, err)
                self.assertIn("hostile.yaml", err)


class CheckGatesScriptTest(unittest.TestCase):
    """ci/check-gates.sh hands `--set NAME:...` only to the runs that hold NAME."""

    def test_run_arguments_are_routed_by_estimator(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            gates_file = root / "gates.yaml"
            gates_file.write_text(textwrap.dedent("""\
                version: 1
                suites:
                  - {name: a, scenario: paper-synthetic, steps: 5, seeds: 1-5,
                     runs: [{estimators: [phd3], particles: [1]}]}
                  - {name: b, scenario: glmb-sim, steps: 5, seeds: 1-5,
                     runs: [{estimators: [glmb2, oracle], particles: [10]}]}
                """))
            log = root / "calls.log"
            fake = root / "build" / "apps" / "phdslam"
            fake.parent.mkdir(parents=True)
            fake.write_text(f"#!/bin/sh\necho \"$*\" >> {log}\nexit 0\n")
            fake.chmod(0o755)
            env = dict(os.environ, PHDSLAM_GATES_FILE=str(gates_file))
            subprocess.run(["bash", str(CI / "check-gates.sh"), str(root / "build"),
                            str(root / "out"), "--", "--set", "glmb2:gibbs_samples=10",
                            "--set", "phd3:max_hypotheses=2", "--jobs", "1"],
                           env=env, capture_output=True, check=False)
            calls = log.read_text().splitlines()
            runs = [c for c in calls if c.startswith("run ")]
            self.assertEqual(len(runs), 2, calls)
            self.assertIn("--set phd3:max_hypotheses=2 --jobs 1", runs[0])
            self.assertNotIn("glmb2", runs[0])
            self.assertIn("--set glmb2:gibbs_samples=10 --jobs 1", runs[1])
            self.assertNotIn("phd3:", runs[1])
            self.assertTrue(any(c.startswith("gate ") for c in calls), calls)


if __name__ == "__main__":
    unittest.main()
