#!/usr/bin/env python3
"""Makes the golden fixture (fixture/) from traces that run_authors.py --trace wrote: per seed the
authors' draws and their per-step states (particles, proposals, states, maps, estimate), gzipped,
and fixture.json with what check_fixture.py needs (scenario, seeds, steps, particles, variant,
map interval, tolerance and its reason, provenance). Data, not code: nothing of the release's
source is copied.

    make_fixture.py --traces TRACES --seeds 1,2 --steps 300 --particles 10 --map-every 50 \
        --rtol R --atol A --reason TEXT --provenance TEXT --out reference/authors/fixture
"""
import argparse
import gzip
import json
import os
import shutil
import sys

FILES = ["draws.csv", "particles.csv", "proposals.csv", "states.csv", "maps.csv", "estimate.csv"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--traces", required=True)
    ap.add_argument("--seeds", required=True)
    ap.add_argument("--steps", type=int, required=True)
    ap.add_argument("--particles", type=int, required=True)
    ap.add_argument("--variant", default="phd3")
    ap.add_argument("--scenario", default="paper-synthetic")
    ap.add_argument("--map-every", type=int, required=True)
    ap.add_argument("--rtol", type=float, required=True)
    ap.add_argument("--atol", type=float, required=True)
    ap.add_argument("--reason", required=True, help="why this tolerance")
    ap.add_argument("--provenance", required=True, help="release commit, Octave version, command")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    try:
        seeds = [int(s) for s in args.seeds.split(",")]
    except ValueError:
        ap.error(f"--seeds: expected a comma list of integers, got {args.seeds!r}")
    if any(s < 0 for s in seeds) or len(set(seeds)) != len(seeds):
        ap.error(f"--seeds: expected distinct seeds >= 0, got {args.seeds!r}")
    for name, value in (("--steps", args.steps), ("--particles", args.particles),
                        ("--map-every", args.map_every)):
        if value < 1:
            ap.error(f"{name}: expected an integer >= 1, got {value}")
    for name, value in (("--rtol", args.rtol), ("--atol", args.atol)):
        if not 0.0 <= value < float("inf"):
            ap.error(f"{name}: expected a number >= 0, got {value}")
    # Every trace file is checked before the old fixture is removed.
    missing = [os.path.join(args.traces, f"seed-{s}", name) for s in seeds for name in FILES
               if not os.path.isfile(os.path.join(args.traces, f"seed-{s}", name))]
    if missing:
        print(f"make_fixture.py: no trace file {missing[0]} (run_authors.py --trace writes it)",
              file=sys.stderr)
        return 2
    try:
        write_fixture(args, seeds)
    except OSError as e:
        print(f"make_fixture.py: {e.filename or args.out}: {e.strerror or e}", file=sys.stderr)
        return 2
    return 0


def write_fixture(args, seeds):
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(args.out)
    for s in seeds:
        src = os.path.join(args.traces, f"seed-{s}")
        dst = os.path.join(args.out, f"seed-{s}")
        os.makedirs(dst)
        for name in FILES:
            with open(os.path.join(src, name), "rb") as f, \
                    gzip.GzipFile(os.path.join(dst, name + ".gz"), "wb", 9, mtime=0) as g:
                g.write(f.read())
    meta = {"scenario": args.scenario, "seeds": seeds, "steps": args.steps,
            "particles": args.particles, "variant": args.variant, "map_every": args.map_every,
            "tolerance": {"rtol": args.rtol, "atol": args.atol, "reason": args.reason},
            "provenance": args.provenance}
    with open(os.path.join(args.out, "fixture.json"), "w", encoding="utf-8") as f:
        json.dump(meta, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    raise SystemExit(main())
