#!/usr/bin/env python3
"""CTest authors_release_adapter: exports two short seeds of paper-synthetic, runs the authors'
release on them under Octave (run_authors.py, recording draws and states), ingests the outputs as
authors-phd3 next to phdslam's own phd3 run, then replays phd3 on the recorded draws and checks
every step against the authors' states (compare_traces.py, the fixture's tolerances); the replay's
--out files, ingested as phd3-replay, score as the authors' run does; a --draws-only recording
writes the same draws and nothing but draws.csv and estimate.csv.
Exit 77 (skipped, with the reason) without Octave or without PHDSLAM_AUTHORS_RELEASE."""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import compare_traces  # noqa: E402
import run_authors  # noqa: E402

SEEDS = [1, 2]
STEPS = 40
PARTICLES = 3


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--phdslam", required=True)
    ap.add_argument("--replay", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    try:
        run_authors.find_tools()
        run_authors.find_release(None)
    except run_authors.Skip as e:
        print(f"skipped: {e}")
        return run_authors.SKIP
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    export = os.path.join(args.work, "export")
    outputs = os.path.join(args.work, "outputs")
    traces = os.path.join(args.work, "traces")
    results = os.path.join(args.work, "results")
    seeds = ",".join(str(s) for s in SEEDS)
    subprocess.run([args.phdslam, "export", "--scenario", "paper-synthetic", "--seeds", seeds,
                    "--steps", str(STEPS), "--out", export], check=True)
    code = subprocess.run([sys.executable, os.path.join(HERE, "run_authors.py"), "--export",
                           export, "--out", outputs, "--particles", str(PARTICLES), "--trace",
                           traces, "--map-every", "10", "--ingest", results, "--phdslam",
                           args.phdslam, "--mex-cache", os.path.join(args.work, "mex")]).returncode
    if code != 0:
        print(f"run_authors.py exited with {code}")
        return 1
    with open(os.path.join(results, "runs.csv"), encoding="ascii") as f:
        runs = [r for r in csv.DictReader(f) if r["estimator"] == "authors-phd3"]
    if len(runs) != len(SEEDS):
        print(f"expected {len(SEEDS)} ingested authors-phd3 runs, found {len(runs)}")
        return 1
    for r in runs:
        rmse = float(r["pos_rmse_m"])
        # 40 steps from a known start: the filter stays within a few metres of the truth.
        if not 0.0 <= rmse < 5.0:
            print(f"authors-phd3 seed {r['seed']}: position RMSE {rmse} m, expected below 5 m")
            return 1
    with open(os.path.join(HERE, "fixture", "fixture.json"), encoding="utf-8") as f:
        tol = json.load(f)["tolerance"]
    failed = False
    for s in SEEDS:
        ours = os.path.join(args.work, "replay", f"seed-{s}")
        subprocess.run([args.replay, "--draws", os.path.join(traces, f"seed-{s}", "draws.csv"),
                        "--trace", ours, "--seed", str(s), "--steps", str(STEPS), "--particles",
                        str(PARTICLES), "--map-every", "10"], check=True)
        result = compare_traces.compare(os.path.join(traces, f"seed-{s}"), ours, tol["rtol"],
                                        tol["atol"])
        first = result["first_divergence"]
        print(f"seed {s}: first divergence: {first}")
        failed = failed or first is not None
        subprocess.run([args.replay, "--draws", os.path.join(traces, f"seed-{s}", "draws.csv"),
                        "--out", os.path.join(args.work, "replay-out", f"seed-{s}"), "--seed",
                        str(s), "--steps", str(STEPS), "--particles", str(PARTICLES)], check=True)
    failed = check_replay_scores(args, export, results) or failed
    failed = check_draws_only(args, export, traces) or failed
    return 1 if failed else 0


def check_replay_scores(args, export, results):
    """phd3 on the authors' draws, ingested, scores as authors-phd3 (the fixture's rtol)."""
    subprocess.run([args.phdslam, "ingest", "--from", os.path.join(args.work, "replay-out"),
                    "--export", export, "--estimator", "phd3-replay", "--particles",
                    str(PARTICLES), "--out", results], check=True)
    with open(os.path.join(results, "runs.csv"), encoding="ascii") as f:
        runs = {(r["estimator"], r["seed"]): r for r in csv.DictReader(f)}
    failed = False
    for s in SEEDS:
        for column in ("pos_rmse_m", "gospa_m"):
            a = float(runs[("authors-phd3", str(s))][column])
            b = float(runs[("phd3-replay", str(s))][column])
            if abs(a - b) > 1e-6 * max(abs(a), abs(b)):
                print(f"seed {s} {column}: authors-phd3 {a}, phd3-replay {b}")
                failed = True
    return failed


def check_draws_only(args, export, traces):
    """--draws-only records the same draws and only draws.csv and estimate.csv."""
    lean = os.path.join(args.work, "traces-draws-only")
    code = subprocess.run([sys.executable, os.path.join(HERE, "run_authors.py"), "--export",
                           export, "--out", os.path.join(args.work, "outputs-draws-only"),
                           "--seeds", str(SEEDS[0]), "--particles", str(PARTICLES), "--trace",
                           lean, "--draws-only", "--mex-cache",
                           os.path.join(args.work, "mex")]).returncode
    seed_dir = f"seed-{SEEDS[0]}"
    files = sorted(os.listdir(os.path.join(lean, seed_dir))) if code == 0 else []
    if files != ["draws.csv", "estimate.csv"]:
        print(f"--draws-only: exit {code}, files {files}, expected draws.csv and estimate.csv")
        return True
    for name in files:
        with open(os.path.join(lean, seed_dir, name), encoding="ascii") as f:
            lean_text = f.read()
        with open(os.path.join(traces, seed_dir, name), encoding="ascii") as f:
            if f.read() != lean_text:
                print(f"--draws-only: {name} differs from the full recording's")
                return True
    return False


if __name__ == "__main__":
    sys.exit(main())
