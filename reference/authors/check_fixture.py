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


class FixtureError(ValueError):
    """A fixture that cannot be checked: the message names the file and the field."""


def gunzip_folder(src, dst):
    os.makedirs(dst, exist_ok=True)
    for name in sorted(os.listdir(src)):
        if name.endswith(".gz"):
            path = os.path.join(src, name)
            try:
                with gzip.open(path, "rb") as f, open(os.path.join(dst, name[:-3]), "wb") as g:
                    g.write(f.read())
            except (OSError, EOFError) as e:  # a damaged or truncated gzip file
                raise FixtureError(f"{path}: not a complete gzip file ({e})") from None


# fixture.json's keys and the type each must have (what make_fixture.py writes).
FIXTURE_KEYS = {"scenario": str, "seeds": list, "steps": int, "particles": int, "variant": str,
                "map_every": int, "tolerance": dict}


def read_fixture(path):
    """fixture.json, checked: every key of FIXTURE_KEYS of its type, integer seeds, numeric
    tolerances. FixtureError names the file and the key."""
    try:
        with open(path, encoding="utf-8") as f:
            meta = json.load(f)
    except OSError as e:
        raise FixtureError(f"{path}: cannot read ({e.strerror or e})") from None
    except ValueError as e:
        raise FixtureError(f"{path}: not valid JSON ({e})") from None
    if not isinstance(meta, dict):
        raise FixtureError(f"{path}: expected a JSON object, got {type(meta).__name__}")
    for key, kind in FIXTURE_KEYS.items():
        if not isinstance(meta.get(key), kind) or isinstance(meta.get(key), bool):
            raise FixtureError(f"{path}: key '{key}' must be a {kind.__name__}, got "
                               f"{json.dumps(meta.get(key))}")
    if not meta["seeds"] or not all(isinstance(s, int) and not isinstance(s, bool) and s >= 0
                                    for s in meta["seeds"]):
        raise FixtureError(f"{path}: key 'seeds' must be a non-empty list of seeds (integers "
                           f">= 0), got {json.dumps(meta['seeds'])}")
    for key in ("rtol", "atol"):
        value = meta["tolerance"].get(key)
        if not isinstance(value, (int, float)) or isinstance(value, bool) or \
                not 0.0 <= value < float("inf"):
            raise FixtureError(f"{path}: key 'tolerance.{key}' must be a number >= 0, got "
                               f"{json.dumps(value)}")
    return meta


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--replay", required=True)
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    try:
        return check(args)
    except (OSError, ValueError) as e:  # FixtureError, compare_traces.TraceError, I/O
        print(f"check_fixture.py: {e}", file=sys.stderr)
        return 2


def check(args):
    meta = read_fixture(os.path.join(args.fixture, "fixture.json"))
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
        try:
            replayed = subprocess.run(cmd, check=False).returncode
        except OSError as e:
            raise FixtureError(f"--replay {args.replay}: cannot run ({e.strerror or e})") from None
        if replayed != 0:
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
