#!/usr/bin/env python3
"""The worked example of validating an external filter (validation/EXPORT_FORMAT.md), end to end:

  1. phdslam export   seeds 1-3 of paper-synthetic, first 300 steps
  2. ekf_slam.py      the Python EKF-SLAM on the exported files
  3. phdslam run      PHD-SLAM 3.0 (N = 10) and odometry on the same seeds, into RESULTS
  4. phdslam ingest   the EKF's outputs into the same RESULTS folder
  5. phdslam compare  one paired comparison table (RESULTS/comparison.csv)
  6. make_report.py   one report (RESULTS/report/index.html)
  7. phdslam gate     an accuracy gate (ci/GATES.md) on the ingested estimator's runs

and checks the outcome: every group has every seed, the comparison pairs the EKF with phd3 on
those seeds, the EKF localises better than dead reckoning and associates most measurements
correctly, and the report shows the EKF beside phd3.

    worked_example.py --phdslam build/release/apps/phdslam --out /tmp/worked-example
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SEEDS, STEPS, NAME = "1-3", "300", "ekf-nn-py"


def step(title, command):
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    print(f"{title}: {time.perf_counter() - start:.1f} s")


def rows(path):
    with open(path, newline="", encoding="ascii") as f:
        return list(csv.DictReader(f))


def check(condition, message):
    if not condition:
        raise SystemExit(f"worked example: {message}")


GATES = """version: 1
suites:
  - name: worked-example
    scenario: paper-synthetic
    seeds: {seeds}
    steps: {steps}
    runs:
      - estimators: [{name}]
        particles: [1]
anchors:
  - suite: worked-example
    estimator: {name}
    particles: 1
    metric: pos_rmse_m
    statistic: pooled-rmse
    band: [0.0, {high}]
    reason: worked example, the ingested estimator gated like a registered one
"""


def gates_exit_code(phdslam, results, high):
    """`phdslam gate`'s exit code for a pooled pos_rmse_m band [0, high] on the ingested
    estimator (the anchor tier: an outside filter has no stored baseline)."""
    path = os.path.join(results, f"gates-{high}.yaml")
    with open(path, "w", encoding="ascii") as f:
        f.write(GATES.format(seeds=SEEDS, steps=STEPS, name=NAME, high=high))
    return subprocess.run([phdslam, "gate", "--gates", path, "--results", results, "--tiers",
                           "anchor"], stdout=subprocess.DEVNULL, check=False).returncode


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--phdslam", required=True, help="the phdslam program")
    parser.add_argument("--out", required=True, help="working folder (emptied first)")
    args = parser.parse_args()
    shutil.rmtree(args.out, ignore_errors=True)
    export, outputs, results = (os.path.join(args.out, d) for d in ("export", "ekf", "results"))
    py = sys.executable
    scenario = ["--scenario", "paper-synthetic", "--seeds", SEEDS, "--steps", STEPS]
    step("export", [args.phdslam, "export", *scenario, "--out", export])
    step("ekf_slam.py", [py, os.path.join(HERE, "ekf_slam.py"), export, outputs])
    step("run phd3", [args.phdslam, "run", *scenario, "--estimator", "phd3", "--particles", "10",
                      "--jobs", "1", "--quiet", "--out", results])
    step("run odometry", [args.phdslam, "run", *scenario, "--estimator", "odometry", "--jobs", "1",
                          "--quiet", "--out", results])
    step("ingest", [args.phdslam, "ingest", "--from", outputs, "--export", export,
                    "--estimator", NAME, "--out", results])
    step("compare", [args.phdslam, "compare", "--out", results,
                     "--metric", "pos_rmse_m,heading_rmse_deg,gospa_m,da_tpr"])
    step("report", [py, os.path.join(REPO, "reports", "make_report.py"), results])

    summary = {(r["estimator"], r["particles"]): r for r in rows(os.path.join(results,
                                                                               "summary.csv"))}
    check(set(summary) == {(NAME, "1"), ("phd3", "10"), ("odometry", "1")},
          f"summary.csv groups {sorted(summary)}")
    for key, r in summary.items():
        check(r["runs"] == "3" and r["steps"] == STEPS, f"{key}: {r['runs']} runs of {r['steps']}")
    ekf, odo = summary[(NAME, "1")], summary[("odometry", "1")]
    check(float(ekf["pos_rmse_m"]) < float(odo["pos_rmse_m"]),
          f"EKF position RMSE {ekf['pos_rmse_m']} not below odometry's {odo['pos_rmse_m']}")
    check(float(ekf["da_tpr"]) > 0.9, f"EKF association TPR {ekf['da_tpr']}")
    pairs = [r for r in rows(os.path.join(results, "comparison.csv"))
             if {r["estimator_a"], r["estimator_b"]} == {NAME, "phd3"}]
    check(sorted(r["metric"] for r in pairs) ==
          ["da_tpr", "gospa_m", "heading_rmse_deg", "pos_rmse_m"],
          f"comparison.csv rows of {NAME} against phd3: {pairs}")
    check(all(r["n"] == "3" for r in pairs), "the comparison does not pair all three seeds")
    with open(os.path.join(results, "report", "index.html"), encoding="utf-8") as f:
        html = f.read()
    check(NAME in html and "phd3" in html, "the report does not show both estimators")
    check(gates_exit_code(args.phdslam, results, 2.0) == 0,
          "a gate pos_rmse_m in [0, 2] m fails on the EKF")
    check(gates_exit_code(args.phdslam, results, 0.1) == 1,
          "a gate pos_rmse_m in [0, 0.1] m passes the EKF")

    print(f"{'estimator':<10} {'N':>3} {'pos RMSE m':>11} {'heading deg':>12} {'GOSPA m':>9} "
          f"{'DA TPR':>7} {'DA TNR':>7} {'ms/step':>8}")
    for (name, n), r in sorted(summary.items()):
        print(f"{name:<10} {n:>3} {float(r['pos_rmse_m']):>11.3f} "
              f"{float(r['heading_rmse_deg']):>12.3f} {float(r['gospa_mean_m']):>9.2f} "
              f"{r['da_tpr'][:6] or '-':>7} {r['da_tnr'][:6] or '-':>7} "
              f"{float(r['ms_per_step_mean'] or 'nan'):>8.3f}")
    for r in pairs:
        print(f"{r['metric']}: {r['estimator_a']} - {r['estimator_b']} median "
              f"{float(r['median_difference']):.4g}, p = {r['p_value']} ({r['method']}, n = {r['n']})")
    print(f"report: {os.path.join(results, 'report', 'index.html')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
