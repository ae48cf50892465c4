#!/usr/bin/env python3
"""CTest authors_fixture_replay: replays phd3 (phdslam_authors_replay) on the draws of the golden
fixture (fixture/, made by make_fixture.py from the authors' release) and compares every step with
the states the release recorded (compare_traces.py) within the fixture's stated tolerance.

    check_fixture.py --replay PATH --fixture DIR --work DIR
"""
import argparse
import gzip
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import compare_traces  # noqa: E402


def gunzip_folder(src, dst):
    os.makedirs(dst, exist_ok=True)
    for name in os.listdir(src):
        if name.endswith(".gz"):
            with gzip.open(os.path.join(src, name), "rb") as f, \
                    open(os.path.join(dst, name[:-3]), "wb") as g:
                g.write(f.read())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--replay", required=True)
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    with open(os.path.join(args.fixture, "fixture.json"), encoding="utf-8") as f:
        meta = json.load(f)
    shutil.rmtree(args.work, ignore_errors=True)
    tol = meta["tolerance"]
    failed = False
    for s in meta["seeds"]:
        authors = os.path.join(args.work, "authors", f"seed-{s}")
        ours = os.path.join(args.work, "phdslam", f"seed-{s}")
        gunzip_folder(os.path.join(args.fixture, f"seed-{s}"), authors)
        cmd = [args.replay, "--draws", os.path.join(authors, "draws.csv"), "--trace", ours,
               "--scenario", meta["scenario"], "--seed", str(s), "--steps", str(meta["steps"]),
               "--variant", meta["variant"], "--particles", str(meta["particles"]),
               "--map-every", str(meta["map_every"])]
        if subprocess.run(cmd).returncode != 0:
            print(f"seed {s}: the replay failed: {' '.join(cmd)}")
            failed = True
            continue
        result = compare_traces.compare(authors, ours, tol["rtol"], tol["atol"])
        for q in result["quantities"]:
            print(f"seed {s}: {q['quantity']:28s} n={q['compared']:7d} "
                  f"max|diff|={q['max_diff']:.3g}")
            if q["compared"] == 0:
                print(f"seed {s}: nothing compared for {q['quantity']}")
                failed = True
        first = result["first_divergence"]
        if first is not None:
            print(f"seed {s}: diverges from the authors' release at step "
                  f"{first['first_divergence_step']}, {first['quantity']}: "
                  f"{first['first_divergence']}")
            failed = True
        else:
            print(f"seed {s}: all {meta['steps']} steps agree within rtol {tol['rtol']}, "
                  f"atol {tol['atol']}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
