#!/usr/bin/env python3
"""End-to-end check of the posterior Cramer-Rao bounds against a dense Fisher information.

Runs `phdslam export` and `phdslam run --estimator pcrb,pcrb-smoother` on one seed of the
synthetic scenario, then builds the Fisher information of the whole graph at the truth from the
exported files alone (docs/algorithms/pcrb.md section 1): the odometry as a measurement of the
control that moves one true pose to the next (the exact inverse of the unicycle, with the
no-sideways-slip constraint as a stiff third residual), each labelled detection as a range-bearing
measurement, Jacobians by central differences, the initial pose known. Its dense inverse gives

- the smoothing bound: the marginal of every pose and landmark, against pcrb-smoother's
  steps.csv and map.csv;
- the filtering bound at a few steps k: the marginal of pose k of the graph cut after step k,
  against pcrb's steps.csv.

Nothing of the C++ implementation is shared (model, Jacobians, recursion, file reading), so a
wrong Jacobian, a step misaligned between data and truth, a detection left out or a recursion that
differs from the batch inverse shows as a relative difference above the tolerance. The clutter
rate is 0 so that the conditioned bound's clutter factor is 1 exactly.

    dense_fisher_check.py PHDSLAM_BINARY WORK_DIR [--steps 300] [--seed 1] [--mse-distribution]

With --mse-distribution it also prints the distribution of one run's mean squared position error
for an efficient estimator (the errors Gaussian with the dense smoothing covariance): its mean
(the squared smoothing bound), standard deviation, effective degrees of freedom 2 mean^2 / var,
the share of the largest eigenvalues and, by simulation, its quantiles and the spread of the
efficiency ratio over n seeds (docs/algorithms/pcrb.md section 8).

Exit 0 when every compared entry agrees to the tolerance, 1 when one does not, 2 for bad input.
"""
import argparse
import csv
import json
import math
import pathlib
import subprocess
import sys

import numpy as np

LATERAL_STD = 1e-5  # m: the unicycle's no-sideways-slip constraint, stiff but well conditioned
TOLERANCE = 2e-3  # relative, on standard deviations: the files carry about 10 digits
FD_STEP = 1e-6


def fail(message, code=2):
    print(f"dense_fisher_check: {message}", file=sys.stderr)
    sys.exit(code)


def run(command):
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        fail(f"'{' '.join(command)}' exited {result.returncode}: {result.stderr.strip()}")


def read_csv(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        fail(f"cannot read '{path}': {e.strerror}")
    return []


def read_truth(export, seed):
    poses = []
    with open(export / "truth" / f"seed-{seed}" / "trajectory.tum", encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                continue
            t = [float(v) for v in line.split()]
            poses.append((t[1], t[2], 2.0 * math.atan2(t[6], t[7])))
    landmarks = [(float(r["x"]), float(r["y"]))
                 for r in read_csv(export / "truth" / f"seed-{seed}" / "map.csv")]
    return np.array(poses), np.array(landmarks)


def control_of(a, b, dt):
    """The control that moves the unicycle from a to b in dt, and the sideways slip."""
    c, s = math.cos(a[2]), math.sin(a[2])
    dx, dy = b[0] - a[0], b[1] - a[1]
    bx, by = c * dx + s * dy, -s * dx + c * dy
    dtheta = b[2] - a[2]
    h = dtheta / 2.0
    along = bx * math.cos(h) + by * math.sin(h)
    lateral = -bx * math.sin(h) + by * math.cos(h)
    ratio = 1.0 + h * h / 6.0 if abs(h) < 1e-4 else h / math.sin(h)
    return np.array([along * ratio / dt, dtheta / dt, lateral])


def range_bearing(x, m):
    dx, dy = m[0] - x[0], m[1] - x[1]
    return np.array([math.hypot(dx, dy), math.atan2(dy, dx) - x[2]])


def jacobian(f, x):
    x = np.asarray(x, dtype=float)
    cols = []
    for j in range(len(x)):
        e = np.zeros(len(x))
        e[j] = FD_STEP
        cols.append((f(x + e) - f(x - e)) / (2.0 * FD_STEP))
    return np.array(cols).T


class Graph:
    """The Fisher information of poses 1..K-1 (pose 0 known) and the landmarks."""

    def __init__(self, steps, landmarks):
        self.steps = steps
        self.n = 3 * (steps - 1) + 2 * landmarks
        self.info = np.zeros((self.n, self.n))

    def pose(self, k):
        return 3 * (k - 1) if k >= 1 else None

    def landmark(self, i):
        return 3 * (self.steps - 1) + 2 * i

    def add(self, blocks, weight):
        for i1, a in blocks:
            for i2, b in blocks:
                self.info[i1:i1 + a.shape[1], i2:i2 + b.shape[1]] += a.T @ weight @ b


def fisher(poses, landmarks, steps, odometry_dt, detections, q_u, r):
    g = Graph(steps, len(landmarks))
    w_odometry = np.linalg.inv(np.diag([q_u[0][0], q_u[1][1], LATERAL_STD ** 2]))
    w_odometry[:2, :2] = np.linalg.inv(np.array(q_u))
    for k in range(1, steps):
        a, b, dt = poses[k - 1], poses[k], odometry_dt[k]
        blocks = [(g.pose(k), jacobian(lambda v: control_of(a, v, dt), b))]
        if k >= 2:
            blocks.append((g.pose(k - 1), jacobian(lambda v: control_of(v, b, dt), a)))
        g.add(blocks, w_odometry)
    w_detection = np.linalg.inv(np.array(r))
    for k, i in detections:
        if k >= steps:
            continue
        x, m = poses[k], landmarks[i]
        blocks = [(g.landmark(i), jacobian(lambda v: range_bearing(x, v), m))]
        if k >= 1:
            blocks.append((g.pose(k), jacobian(lambda v: range_bearing(v, m), x)))
        g.add(blocks, w_detection)
    seen = sorted({i for k, i in detections if k < steps})
    keep = list(range(3 * (steps - 1))) + [g.landmark(i) + j for i in seen for j in range(2)]
    cov = np.linalg.inv(g.info[np.ix_(keep, keep)])
    position = {i: 3 * (steps - 1) + 2 * n for n, i in enumerate(seen)}
    return cov, position


def pose_std(cov, k):
    if k == 0:
        return 0.0, 0.0
    p = 3 * (k - 1)
    return math.sqrt(cov[p, p] + cov[p + 1, p + 1]), math.degrees(math.sqrt(cov[p + 2, p + 2]))


class Comparison:
    def __init__(self):
        self.worst = (0.0, "")
        self.count = 0

    def check(self, what, tool, dense):
        self.count += 1
        scale = max(abs(tool), abs(dense), 1e-12)
        rel = abs(tool - dense) / scale
        if rel > self.worst[0]:
            self.worst = (rel, f"{what}: bound {tool:.9g}, dense {dense:.9g}")


def print_mse_distribution(cov, steps):
    """One run's MSE for an efficient estimator: sum of eigenvalue-weighted chi-squares."""
    position = [3 * (k - 1) + j for k in range(1, steps) for j in range(2)]
    eig = np.linalg.eigvalsh(cov[np.ix_(position, position)] / steps)[::-1]
    mean, var = eig.sum(), 2.0 * (eig ** 2).sum()
    print(f"efficient estimator, one run's position MSE: mean {mean:.4g} m^2 (bound "
          f"{math.sqrt(mean):.4g} m), sd {math.sqrt(var):.4g}, effective dof "
          f"{2 * mean ** 2 / var:.3g}, largest eigenvalues' shares "
          f"{', '.join(f'{x / mean:.3f}' for x in eig[:3])}")
    rng = np.random.default_rng(1)
    runs = (rng.chisquare(1, size=(20000, 60)) * eig[:60]).sum(axis=1) + eig[60:].sum()
    quantiles = np.quantile(runs, [0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0])
    print("quantiles (0, .1, .25, .5, .75, .9, 1) of 20000 simulated runs: "
          + ", ".join(f"{q:.3g}" for q in quantiles))
    for n in (10, 20, 50, 100, 200):
        ratio = np.sqrt(rng.choice(runs, size=(20000, n)).mean(axis=1) / mean)
        print(f"{n} seeds: efficiency ratio sd {ratio.std():.3f}, P(ratio < 0.7) "
              f"{(ratio < 0.7).mean():.4f}, P(ratio < 0.85) {(ratio < 0.85).mean():.4f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary")
    parser.add_argument("work", type=pathlib.Path)
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--mse-distribution", action="store_true")
    args = parser.parse_args()
    if not 10 <= args.steps <= 1000:
        fail(f"--steps must be in [10, 1000], got {args.steps}")
    export, results = args.work / "export", args.work / "results"
    common = ["--scenario", "paper-synthetic", "--seeds", str(args.seed), "--steps",
              str(args.steps), "--clutter-rate", "0"]
    for folder in (export, results):
        subprocess.run(["rm", "-rf", str(folder)], check=True)
    run([args.binary, "export", *common, "--out", str(export)])
    run([args.binary, "run", *common, "--estimator", "pcrb,pcrb-smoother", "--quiet",
         "--out", str(results)])

    seed = args.seed
    models = json.loads((export / f"seed-{seed}" / "models.json").read_text(encoding="utf-8"))
    q_u, r = models["motion"]["control_noise_cov"], models["sensor"]["noise_cov"]
    poses, landmarks = read_truth(export, seed)
    odometry_dt = {int(c["step"]): float(c["t_end"]) - float(c["t_start"])
                   for c in read_csv(export / f"seed-{seed}" / "controls.csv")}
    origin = {(int(o["step"]), int(o["index"])): int(o["origin"])
              for o in read_csv(export / "truth" / f"seed-{seed}" / "origins.csv")}
    detections = [(int(m["step"]), origin[(int(m["step"]), int(m["index"]))])
                  for m in read_csv(export / f"seed-{seed}" / "measurements.csv")]
    detections = [(k, i) for k, i in detections if i >= 0]
    steps = args.steps

    compare = Comparison()
    smoother = read_csv(results / "runs" / "pcrb-smoother-N1" / f"seed-{seed}" / "steps.csv")
    cov, position = fisher(poses, landmarks, steps, odometry_dt, detections, q_u, r)
    if args.mse_distribution:
        print_mse_distribution(cov, steps)
    for row in smoother:
        k = int(row["step"])
        pos, heading = pose_std(cov, k)
        compare.check(f"pcrb-smoother step {k} pos_err_m", float(row["pos_err_m"]), pos)
        compare.check(f"pcrb-smoother step {k} heading_err_deg", float(row["heading_err_deg"]),
                      heading)
    bound_map = read_csv(results / "runs" / "pcrb-smoother-N1" / f"seed-{seed}" / "map.csv")
    by_place = {(round(x, 6), round(y, 6)): i for i, (x, y) in enumerate(landmarks)}
    for row in bound_map:
        i = by_place[(round(float(row["x"]), 6), round(float(row["y"]), 6))]
        p = position[i]
        for key, (a, b) in (("pxx", (0, 0)), ("pxy", (0, 1)), ("pyy", (1, 1))):
            if key == "pxy":
                # An off-diagonal entry is compared on the scale of its diagonal.
                scale = math.sqrt(cov[p, p] * cov[p + 1, p + 1])
                compare.check(f"landmark {i} {key} / sqrt(pxx pyy)", float(row[key]) / scale,
                              cov[p + a, p + b] / scale)
            else:
                compare.check(f"landmark {i} {key}", float(row[key]), cov[p + a, p + b])
    if len(bound_map) != len(position):
        fail(f"pcrb-smoother's map.csv has {len(bound_map)} landmarks, the data "
             f"{len(position)} detected ones", code=1)

    filtering = read_csv(results / "runs" / "pcrb-N1" / f"seed-{seed}" / "steps.csv")
    for k in sorted({steps // 4, steps // 2, steps - 1}):
        cut, _ = fisher(poses, landmarks, k + 1, odometry_dt, detections, q_u, r)
        pos, heading = pose_std(cut, k)
        compare.check(f"pcrb step {k} pos_err_m", float(filtering[k]["pos_err_m"]), pos)
        compare.check(f"pcrb step {k} heading_err_deg", float(filtering[k]["heading_err_deg"]),
                      heading)

    worst, where = compare.worst
    print(f"dense_fisher_check: {compare.count} entries of {steps} steps, seed {seed}; "
          f"largest relative difference {worst:.2e} ({where}); tolerance {TOLERANCE:.0e}")
    sys.exit(0 if worst <= TOLERANCE else 1)


if __name__ == "__main__":
    main()
