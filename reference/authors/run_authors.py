#!/usr/bin/env python3
"""Runs the authors' PHD-SLAM release (MATLAB + C MEX) under GNU Octave on a `phdslam export`
folder, writes its estimates in the format `phdslam ingest` reads, and optionally ingests them as
estimator `authors-phd3` (or `authors-phd1`) into a results folder.

The release is not part of phdslam: give the path of your copy with --release or the environment
variable PHDSLAM_AUTHORS_RELEASE (the folder holding "Shared Files" and "Synthetic Data").

    run_authors.py --export EXPORT --out OUTPUTS [--seeds 1-3] [--variant phd3] [--particles 10]
                   [--trace TRACES [--map-every 100 | --draws-only]]
                   [--ingest RESULTS --phdslam PATH]

Every argument is checked before Octave starts: export.json must be an object whose "seeds" is a
non-empty list of integers >= 1, --seeds a list of those seeds (1-5 or 1,3,7), --map-every >= 0
(and only with --trace), --out a folder or a new name in an existing folder.

Exit codes: 0 done, 1 a failure (message on stderr), 2 usage, 77 Octave, mkoctfile or the release
missing (the message says which; CTest treats 77 as "skipped").
"""
import argparse
import hashlib
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SKIP = 77
# The release's MEX sources, each with the model and linear-algebra sources it is linked with
# (as the release's own CompileCLibraries.m builds them for the synthetic data set).
MEX_SOURCES = {
    "cost_matrix": ["cost_matrix.c", "MODELS", "linearAlgebra.c"],
    "gmiplid": ["gmiplid.c", "MODELS", "linearAlgebra.c"],
    "hypothesisReductionAlgorithm": ["hypothesisReductionAlgorithm.c", "linearAlgebra.c"],
    "kBest2DAssign": ["kBest2DAssign.cpp", "Shared_C++_Code/ShortestPathCPP.cpp"],
    "posterior_est": ["posterior_est.c"],
    "predict": ["predict.c", "MODELS", "linearAlgebra.c"],
    "sample": ["sample.c", "linearAlgebra.c"],
    "update": ["update.c", "MODELS", "linearAlgebra.c"],
}
# Built under another name because a recording wrapper of ours (octave/recording/) takes the name.
WRAPPED = {"sample", "hypothesisReductionAlgorithm"}


class Skip(Exception):
    """A prerequisite (Octave, mkoctfile, the release) is missing."""


MAX_SEEDS = 100000


def seed_number(text, whole):
    """One seed of --seeds, an integer >= 1."""
    if not text.strip().isdigit() or int(text) < 1:
        raise ValueError(f"--seeds {whole!r}: {text!r} is not a seed (an integer >= 1); give "
                         "seeds as 1-5 or 1,3,7")
    return int(text)


def parse_seeds(text):
    seeds = []
    for part in text.split(","):
        if "-" in part:
            a, b = part.split("-", 1)
            first, last = seed_number(a, text), seed_number(b, text)
            if last < first:
                raise ValueError(f"--seeds {text!r}: the range {part!r} is empty (a > b)")
            if last - first >= MAX_SEEDS:
                raise ValueError(f"--seeds {text!r}: more than {MAX_SEEDS} seeds")
            seeds.extend(range(first, last + 1))
        else:
            seeds.append(seed_number(part, text))
        if len(seeds) > MAX_SEEDS:
            raise ValueError(f"--seeds {text!r}: more than {MAX_SEEDS} seeds")
    return seeds


def exported_seeds(export):
    """The seeds of a `phdslam export` folder's export.json, a list of integers >= 1."""
    path = os.path.join(export, "export.json")
    if not os.path.isfile(path):
        raise ValueError(f"{path}: not found (--export must be a `phdslam export` folder)")
    try:
        with open(path, encoding="utf-8-sig") as f:
            exported = json.load(f)
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise ValueError(f"{path}: not a readable JSON file ({e})") from None
    seeds = exported.get("seeds") if isinstance(exported, dict) else None
    if (not isinstance(seeds, list) or not seeds or
            not all(isinstance(s, int) and not isinstance(s, bool) and s >= 1 for s in seeds)):
        raise ValueError(f"{path}: expected an object whose 'seeds' is a non-empty list of "
                         "integers >= 1 (the file `phdslam export` writes)")
    return seeds


def check_out(out):
    """--out must be a folder (or a name whose parent folder exists)."""
    if os.path.exists(out) and not os.path.isdir(out):
        raise ValueError(f"--out {out}: exists and is not a folder")
    parent = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(parent):
        raise ValueError(f"--out {out}: its parent folder {parent} does not exist")
    if not os.access(parent if not os.path.isdir(out) else out, os.W_OK):
        raise ValueError(f"--out {out}: not writable")


def check_arguments(args):
    """Every argument checked before Octave starts; returns the seeds to run."""
    available = exported_seeds(args.export)
    seeds = parse_seeds(args.seeds) if args.seeds else available
    missing = sorted(set(seeds) - set(available))
    if missing:
        raise ValueError(f"--seeds: seed(s) {', '.join(map(str, missing[:10]))} not in "
                         f"{os.path.join(args.export, 'export.json')}")
    if args.particles < 1:
        raise ValueError("--particles must be >= 1")
    if args.map_every < 0:
        raise ValueError(f"--map-every {args.map_every}: must be >= 0 (0: no maps)")
    if args.map_every and not args.trace:
        raise ValueError("--map-every needs --trace DIR")
    if args.draws_only and not args.trace:
        raise ValueError("--draws-only needs --trace DIR")
    if args.draws_only and args.map_every:
        raise ValueError("--draws-only records no maps: drop --map-every")
    check_out(args.out)
    return seeds


def find_release(given):
    path = given or os.environ.get("PHDSLAM_AUTHORS_RELEASE", "")
    if not path:
        raise Skip("the authors' release is not given: pass --release PATH or set "
                   "PHDSLAM_AUTHORS_RELEASE to your copy of PHD-SLAM-3.0 (github.com/okaltiok/"
                   "PHD-SLAM-3.0)")
    for sub in ("Shared Files/mex source/sample.c", "Shared Files/shared m files/rbpf_phd.m"):
        if not os.path.isfile(os.path.join(path, sub)):
            raise Skip(f"{path} is not a copy of the authors' PHD-SLAM-3.0 release: no '{sub}'")
    return os.path.abspath(path)


def find_tools():
    octave = shutil.which("octave-cli") or shutil.which("octave")
    mkoctfile = shutil.which("mkoctfile")
    if not octave or not mkoctfile:
        raise Skip("GNU Octave is not installed (octave-cli and mkoctfile are needed; Debian: "
                   "apt-get install octave liboctave-dev)")
    return octave, mkoctfile


def release_digest(release):
    """A digest of the release's MEX sources, so a changed copy is rebuilt."""
    h = hashlib.sha256()
    src = os.path.join(release, "Shared Files", "mex source")
    for root, _, files in sorted(os.walk(src)):
        for name in sorted(files):
            if name.endswith((".c", ".cpp", ".h", ".hpp")):
                with open(os.path.join(root, name), "rb") as f:
                    h.update(name.encode() + f.read())
    for ours in ("deep_duplicate.h", os.path.join("mex_include", "matrix.h"),
                 os.path.join("mex_include", "octave_mex_compat.h")):
        with open(os.path.join(HERE, ours), "rb") as f:
            h.update(f.read())
    return h.hexdigest()[:16]


def build_mex(release, mkoctfile, cache):
    """Builds the release's MEX files for Octave into cache/<digest>/ (once per source digest)."""
    out = os.path.join(cache, release_digest(release))
    stamp = os.path.join(out, "built")
    if os.path.isfile(stamp):
        return out
    os.makedirs(out, exist_ok=True)
    src = os.path.join(release, "Shared Files", "mex source")
    models = os.path.join("Synthetic_Data_models", "models.c")
    for name, files in MEX_SOURCES.items():
        target = ("authors_" + name) if name in WRAPPED else name
        sources = [os.path.join(src, models if f == "MODELS" else f) for f in files]
        cmd = [mkoctfile, "--mex", "-R2018a", "-O2", "-o", os.path.join(out, target + ".mex"),
               "-I" + os.path.join(HERE, "mex_include"), "-I" + src,
               "-I" + os.path.join(src, "Synthetic_Data_models"),
               "-I" + os.path.join(src, "Shared_C++_Code")] + sources
        env = dict(os.environ)
        force = "-include " + os.path.join(HERE, "deep_duplicate.h")
        env["CFLAGS"] = (env.get("CFLAGS", "") + " " + force + " -std=gnu11 -O2").strip()
        compat = "-include " + os.path.join(HERE, "mex_include", "octave_mex_compat.h")
        env["CXXFLAGS"] = (env.get("CXXFLAGS", "") + " " + force + " " + compat +
                           " -std=c++17 -O2 -fpermissive -w").strip()
        result = subprocess.run(cmd, cwd=out, env=env, capture_output=True, text=True)
        if result.returncode != 0:
            raise RuntimeError(f"building {name} from the release failed:\n{' '.join(cmd)}\n"
                               f"{result.stdout}{result.stderr}")
    for f in os.listdir(out):
        if f.endswith(".o"):
            os.remove(os.path.join(out, f))
    with open(stamp, "w", encoding="ascii") as f:
        f.write("ok\n")
    return out


def octave_string(s):
    return "'" + s.replace("'", "''") + "'"


def run_octave(octave, release, mex_dir, export, seeds, out, variant, particles, trace, map_every,
               draws_only):
    call = "phdslam_authors_main(%s, %s, %s, [%s], %s, %s, %d, %s, %d, %d)" % (
        octave_string(release), octave_string(mex_dir), octave_string(os.path.abspath(export)),
        " ".join(str(s) for s in seeds), octave_string(os.path.abspath(out)),
        octave_string(variant), particles, octave_string(os.path.abspath(trace) if trace else ""),
        map_every, 1 if draws_only else 0)
    cmd = [octave, "--no-gui", "--norc", "--quiet", "--no-window-system",
           "--path", os.path.join(HERE, "octave"), "--eval", call]
    result = subprocess.run(cmd)
    if result.returncode != 0:
        raise RuntimeError(f"Octave failed (exit {result.returncode}) running {call}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--export", required=True, help="a `phdslam export` folder")
    ap.add_argument("--out", required=True, help="where the outputs (ingest format) go")
    ap.add_argument("--seeds", help="seeds to run (default: every exported seed), e.g. 1-5")
    ap.add_argument("--variant", default="phd3", choices=["phd3", "phd1"],
                    help="phd3: the release as published; phd1: its PHD-SLAM 1.0 (J = 0)")
    ap.add_argument("--particles", type=int, default=10)
    ap.add_argument("--release", help="your copy of the release (else $PHDSLAM_AUTHORS_RELEASE)")
    ap.add_argument("--mex-cache", default=os.path.join(os.path.expanduser("~"), ".cache",
                                                         "phdslam-authors-mex"),
                    help="where the MEX files built from the release are kept")
    ap.add_argument("--trace", help="also record every random draw and the per-step states here")
    ap.add_argument("--map-every", type=int, default=0,
                    help="with --trace: full maps of every particle each this many steps (0: none)")
    ap.add_argument("--draws-only", action="store_true",
                    help="with --trace: record only draws.csv and estimate.csv (what the replay "
                         "needs), not the per-step particle states; for Monte Carlo campaigns")
    ap.add_argument("--ingest", help="then ingest the outputs into this results folder")
    ap.add_argument("--phdslam", default="phdslam", help="the phdslam program (for --ingest)")
    args = ap.parse_args()
    try:
        seeds = check_arguments(args)
    except ValueError as e:
        print(f"run_authors.py: {e}", file=sys.stderr)
        return 2
    try:
        octave, mkoctfile = find_tools()
        release = find_release(args.release)
        mex_dir = build_mex(release, mkoctfile, args.mex_cache)
        os.makedirs(args.out, exist_ok=True)
        run_octave(octave, release, mex_dir, args.export, seeds, args.out, args.variant,
                   args.particles, args.trace, args.map_every, args.draws_only)
        if args.ingest:
            cmd = [args.phdslam, "ingest", "--from", args.out, "--export", args.export,
                   "--seeds", ",".join(str(s) for s in seeds), "--estimator",
                   "authors-" + args.variant, "--particles", str(args.particles),
                   "--out", args.ingest]
            if subprocess.run(cmd).returncode != 0:
                raise RuntimeError("ingest failed: " + " ".join(cmd))
    except Skip as e:
        print(f"run_authors.py: skipped: {e}", file=sys.stderr)
        return SKIP
    except (RuntimeError, OSError) as e:
        print(f"run_authors.py: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
