#!/usr/bin/env python3
"""Reads the files of `phdslam export` (format version 1, validation/EXPORT_FORMAT.md) and writes
the files `phdslam ingest` reads. Needs numpy only.

    import phdslam_reader as pr
    export = pr.read_export("EXPORT")            # export.json as a dict
    seed = pr.read_seed("EXPORT", 1)             # one Monte Carlo seed's filter inputs
    for k in range(seed.steps):
        seed.times[k]           # time stamp of step k (s)
        seed.controls[k]        # (c, 4) array: t_start, t_end, u1, u2 (c = 0 at step 0)
        seed.measurements[k]    # (m, 2) array: range (m), bearing (rad)
    seed.models["sensor"]["noise_cov"]           # models.json as a dict
    truth = pr.read_truth("EXPORT", 1)           # true poses, map, GPS, measurement origins

Command line: `phdslam_reader.py EXPORT [--seed S] [--json]` checks SHA256SUMS and prints a
summary of seed S, or with --json every input value of seed S (for tests).
"""
import argparse
import hashlib
import json
import math
import os
import sys

import numpy as np

FORMAT_VERSION = 1


def _table(path, columns):
    """A CSV file with a header line as a (rows, len(columns)) float array of the named columns."""
    with open(path, encoding="ascii") as f:
        header = f.readline().strip().split(",")
        missing = [c for c in columns if c not in header]
        if missing:
            raise ValueError(f"{path}: no column {missing[0]!r} in the header {header}")
        index = [header.index(c) for c in columns]
        rows = [line.split(",") for line in f if line.strip()]
    data = np.array([[float(r[i]) for i in index] for r in rows], dtype=float)
    return data.reshape(len(rows), len(columns))


def _split_by_step(data, steps):
    """Rows of `data` (first column: step) grouped per step, columns after the first."""
    step = data[:, 0].astype(int)
    bounds = np.searchsorted(step, np.arange(steps + 1))
    return [data[bounds[k]:bounds[k + 1], 1:] for k in range(steps)]


class Seed:
    """The filter inputs of one seed (seed-<s>/ of an export)."""

    def __init__(self, folder, seed):
        base = os.path.join(folder, f"seed-{seed}")
        with open(os.path.join(base, "models.json"), encoding="utf-8") as f:
            self.models = json.load(f)
        if self.models["format_version"] != FORMAT_VERSION:
            raise ValueError(f"{base}/models.json: format_version {self.models['format_version']}, "
                             f"this reader reads {FORMAT_VERSION}")
        self.seed = seed
        steps = _table(os.path.join(base, "steps.csv"), ["step", "t", "controls", "measurements"])
        self.steps = len(steps)
        self.times = steps[:, 1]
        controls = _table(os.path.join(base, "controls.csv"),
                          ["step", "t_start", "t_end", "u1", "u2"])
        self.controls = _split_by_step(controls, self.steps)
        z = _table(os.path.join(base, "measurements.csv"), ["step", "index", "range", "bearing"])
        self.measurements = [m[:, 1:] for m in _split_by_step(z, self.steps)]
        for k in range(self.steps):
            if len(self.controls[k]) != steps[k, 2] or len(self.measurements[k]) != steps[k, 3]:
                raise ValueError(f"{base}: step {k} has other counts than steps.csv says")
        self.initial_pose = np.array(self.models["initial_pose"], dtype=float)
        self.control_noise_cov = np.array(self.models["motion"]["control_noise_cov"], dtype=float)
        self.measurement_noise_cov = np.array(self.models["sensor"]["noise_cov"], dtype=float)


class Truth:
    """truth/seed-<s>/: true poses (x, y, theta; heading unwrapped), map, GPS fixes (t, x, y) and
    measurement origins; None for what the scenario does not have (real data: GPS only)."""

    def __init__(self, folder, seed, steps):
        base = os.path.join(folder, "truth", f"seed-{seed}")
        self.times = self.poses = self.landmarks = self.gps = self.origins = None
        if os.path.exists(os.path.join(base, "trajectory.tum")):
            tum = np.loadtxt(os.path.join(base, "trajectory.tum"), comments="#", ndmin=2)
            yaw = 2.0 * np.arctan2(tum[:, 6], tum[:, 7])
            self.times = tum[:, 0]
            self.poses = np.column_stack([tum[:, 1], tum[:, 2], np.unwrap(yaw)])
        if os.path.exists(os.path.join(base, "map.csv")):
            self.landmarks = _table(os.path.join(base, "map.csv"), ["x", "y"])
        if os.path.exists(os.path.join(base, "gps.csv")):
            self.gps = _table(os.path.join(base, "gps.csv"), ["t", "x", "y"])
        if os.path.exists(os.path.join(base, "origins.csv")):
            origins = _table(os.path.join(base, "origins.csv"), ["step", "index", "origin"])
            self.origins = [o[:, 1].astype(int) for o in _split_by_step(origins, steps)]


def read_export(folder):
    with open(os.path.join(folder, "export.json"), encoding="utf-8") as f:
        manifest = json.load(f)
    if manifest.get("format_version") != FORMAT_VERSION:
        raise ValueError(f"{folder}/export.json: format_version {manifest.get('format_version')}, "
                         f"this reader reads {FORMAT_VERSION}")
    return manifest


def read_seed(folder, seed):
    return Seed(folder, seed)


def read_truth(folder, seed):
    steps = len(_table(os.path.join(folder, f"seed-{seed}", "steps.csv"), ["step"]))
    return Truth(folder, seed, steps)


def verify_checksums(folder):
    """The files of SHA256SUMS whose content differs (or that are missing); [] when all match."""
    bad = []
    with open(os.path.join(folder, "SHA256SUMS"), encoding="ascii") as f:
        for line in f:
            digest, path = line.rstrip("\n").split("  ", 1)
            try:
                with open(os.path.join(folder, path), "rb") as g:
                    if hashlib.sha256(g.read()).hexdigest() != digest:
                        bad.append(path)
            except OSError:
                bad.append(path)
    return bad


# ---- Writers of what `phdslam ingest` reads (one folder per seed: OUT/seed-<s>/) ----

def _number(x):
    return repr(float(x))


def write_trajectory(path, times, poses):
    """TUM trajectory: one pose (x, y, theta) per step, at the step's time stamp."""
    with open(path, "w", encoding="ascii") as f:
        f.write("# t x y z qx qy qz qw\n")
        for t, (x, y, th) in zip(times, poses):
            f.write(f"{_number(t)} {_number(x)} {_number(y)} 0 0 0 "
                    f"{_number(math.sin(th / 2))} {_number(math.cos(th / 2))}\n")


def write_map(path, means, covs=None, weights=None):
    """Final map: x,y[,weight][,pxx,pxy,pyy]."""
    with open(path, "w", encoding="ascii") as f:
        f.write("x,y" + (",weight" if weights is not None else "") +
                (",pxx,pxy,pyy" if covs is not None else "") + "\n")
        for i, m in enumerate(means):
            cells = [_number(m[0]), _number(m[1])]
            if weights is not None:
                cells.append(_number(weights[i]))
            if covs is not None:
                cells += [_number(covs[i][0][0]), _number(covs[i][0][1]), _number(covs[i][1][1])]
            f.write(",".join(cells) + "\n")


def write_pose_covariances(path, covs):
    """Per step the 3x3 pose covariance: step,pxx,pxy,pxt,pyy,pyt,ptt."""
    with open(path, "w", encoding="ascii") as f:
        f.write("step,pxx,pxy,pxt,pyy,pyt,ptt\n")
        for k, p in enumerate(covs):
            f.write(",".join([str(k)] + [_number(p[i][j]) for i, j in
                                         ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))]) + "\n")


def write_timing(path, ms):
    """Wall time of each step (ms): step,ms."""
    with open(path, "w", encoding="ascii") as f:
        f.write("step,ms\n")
        for k, v in enumerate(ms):
            f.write(f"{k},{_number(v)}\n")


def write_associations(path, associations):
    """associations[k]: list of (measurement index, landmark x, landmark y) of step k."""
    with open(path, "w", encoding="ascii") as f:
        f.write("step,index,x,y\n")
        for k, rows in enumerate(associations):
            for i, x, y in rows:
                f.write(f"{k},{i},{_number(x)},{_number(y)}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("export")
    parser.add_argument("--seed", type=int, default=None)
    parser.add_argument("--json", action="store_true",
                        help="print every input value of the seed as JSON")
    args = parser.parse_args()
    manifest = read_export(args.export)
    bad = verify_checksums(args.export)
    if bad:
        print(f"checksum mismatch: {', '.join(bad)}", file=sys.stderr)
        return 1
    seed = read_seed(args.export, args.seed if args.seed is not None else manifest["seeds"][0])
    if args.json:
        json.dump({"times": seed.times.tolist(),
                   "controls": [c.tolist() for c in seed.controls],
                   "measurements": [m.tolist() for m in seed.measurements]}, sys.stdout)
        print()
        return 0
    count = sum(len(m) for m in seed.measurements)
    print(f"{manifest['scenario']} seed {seed.seed}: {seed.steps} steps, {count} measurements; "
          f"checksums OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
