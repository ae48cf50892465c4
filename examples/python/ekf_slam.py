#!/usr/bin/env python3
"""EKF-SLAM with nearest-neighbour data association, run on the files of `phdslam export` and
written in the layout `phdslam ingest` reads: the worked example of validating an external filter
(validation/EXPORT_FORMAT.md). Needs numpy only; under a python3 without it, it runs again under
/usr/bin/python3 (Debian's python3-numpy) when that has it.

    ekf_slam.py EXPORT OUT [--seeds 1,2,3]

For every seed of EXPORT (or the given ones) it writes OUT/seed-<s>/trajectory.tum, map.csv (the
confirmed landmarks with their covariances), pose_cov.csv, association.csv and timing.csv, and
OUT/parameters.json.

The filter: the state is the pose and every landmark; the prediction uses the export's motion
model (velocity model, models.json) with the control noise; at each scan the predicted
measurements of the landmarks inside the enlarged field of view are matched one-to-one to the
measurements by increasing Mahalanobis distance (global nearest neighbour, gate chi2_2(0.99)),
the matched pairs update the state in one EKF update (P - K S K', then symmetrised), and a
measurement farther than the new-landmark gate from every landmark starts a tentative landmark.
A landmark that was in the field of view `min_expected` times and detected in fewer than
`min_hit_ratio` of them is removed (clutter); one detected `confirm_hits` times is reported.
"""
import argparse
import json
import math
import os
import sys
import time

SYSTEM_PYTHON = "/usr/bin/python3"
try:
    import numpy as np
except ImportError:
    # Another python3 (pyenv's, say) first on PATH without numpy: run once more under Debian's,
    # as the report scripts do; else say what to install.
    if (os.path.exists(SYSTEM_PYTHON) and not os.environ.get("PHDSLAM_EKF_RESTARTED")
            and os.path.realpath(SYSTEM_PYTHON) != os.path.realpath(sys.executable)):
        os.environ["PHDSLAM_EKF_RESTARTED"] = "1"
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON, os.path.abspath(__file__), *sys.argv[1:]])
    sys.exit(f"ekf_slam.py: {sys.executable} cannot import numpy; install python3-numpy "
             f"(Debian) and run the script with {SYSTEM_PYTHON}")

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import phdslam_reader as pr  # noqa: E402

PARAMETERS = {
    "association_gate": 9.21,      # chi2_2(0.99): largest Mahalanobis distance of a match
    "new_landmark_gate": 25.0,     # a measurement farther than this from every landmark is new
    "min_expected": 4,             # detections expected before a landmark can be removed
    "min_hit_ratio": 0.5,          # removed when detected in fewer of the expected scans
    "confirm_hits": 3,             # detections before a landmark is reported in the map
}


def wrap(a):
    return (a + math.pi) % (2.0 * math.pi) - math.pi


def predict_velocity(x, u, dt):
    """Velocity motion model and its Jacobians Fx, Fu (src/models/velocity_motion_model.cc)."""
    v, w = u
    th = x[2]
    fx = np.eye(3)
    fu = np.zeros((3, 2))
    if abs(w) < 1e-9:
        c, s = math.cos(th), math.sin(th)
        new = np.array([x[0] + v * dt * c, x[1] + v * dt * s, th + w * dt])
        fx[0, 2], fx[1, 2] = -v * dt * s, v * dt * c
        fu[:] = [[dt * c, -0.5 * v * dt * dt * s], [dt * s, 0.5 * v * dt * dt * c], [0.0, dt]]
        return new, fx, fu
    th1 = th + w * dt
    s0, c0, s1, c1 = math.sin(th), math.cos(th), math.sin(th1), math.cos(th1)
    new = np.array([x[0] + v / w * (s1 - s0), x[1] + v / w * (c0 - c1), th1])
    fx[0, 2], fx[1, 2] = v / w * (c1 - c0), v / w * (s1 - s0)
    fu[0, 0], fu[1, 0] = (s1 - s0) / w, (c0 - c1) / w
    fu[0, 1] = v / (w * w) * (s0 - s1) + v * dt / w * c1
    fu[1, 1] = v / (w * w) * (c1 - c0) + v * dt / w * s1
    fu[2, 1] = dt
    return new, fx, fu


class EkfSlam:
    def __init__(self, seed_data, params):
        self.p = params
        self.models = seed_data.models
        self.x = seed_data.initial_pose.copy()
        self.P = np.zeros((3, 3))
        self.Q = seed_data.control_noise_cov
        self.R = seed_data.measurement_noise_cov
        sensor = self.models["sensor"]
        self.view_range = sensor["fov_range"] + sensor["range_buffer"]
        self.view_angle = sensor["fov_half_angle"] + sensor["angle_buffer"]
        self.fov_range = sensor["fov_range"]
        self.fov_angle = sensor["fov_half_angle"]
        self.hits = []       # per landmark: detections
        self.expected = []   # per landmark: scans with the landmark inside the field of view

    @property
    def landmarks(self):
        return (len(self.x) - 3) // 2

    def predict(self, controls):
        for t0, t1, u1, u2 in controls:
            new, fx, fu = predict_velocity(self.x, (u1, u2), t1 - t0)
            self.x[:3] = new
            P = self.P
            P[:3, :3] = fx @ P[:3, :3] @ fx.T + fu @ self.Q @ fu.T
            P[:3, 3:] = fx @ P[:3, 3:]
            P[3:, :3] = P[:3, 3:].T

    def _observation(self, i):
        """Predicted measurement of landmark i and its Jacobian rows (pose, landmark)."""
        j = 3 + 2 * i
        dx, dy = self.x[j] - self.x[0], self.x[j + 1] - self.x[1]
        q = dx * dx + dy * dy
        r = math.sqrt(q)
        z = np.array([r, wrap(math.atan2(dy, dx) - self.x[2])])
        hx = np.array([[-dx / r, -dy / r, 0.0], [dy / q, -dx / q, -1.0]])
        hm = np.array([[dx / r, dy / r], [-dy / q, dx / q]])
        return z, hx, hm

    def _visible(self):
        out = []
        for i in range(self.landmarks):
            j = 3 + 2 * i
            dx, dy = self.x[j] - self.x[0], self.x[j + 1] - self.x[1]
            r = math.hypot(dx, dy)
            b = abs(wrap(math.atan2(dy, dx) - self.x[2]))
            if r <= self.view_range and b <= self.view_angle:
                out.append((i, r <= self.fov_range and b <= self.fov_angle))
        return out

    def update(self, z):
        """One scan; returns the association [(measurement index, landmark index)]."""
        visible = self._visible()
        pairs = []
        best = np.full(len(z), np.inf)
        predictions = {}
        Pxx = self.P[:3, :3]
        for i, _ in visible:
            zi, hx, hm = self._observation(i)
            j = 3 + 2 * i
            Pxm = self.P[:3, j:j + 2]
            cross = hx @ Pxm @ hm.T
            S = hx @ Pxx @ hx.T + cross + cross.T + hm @ self.P[j:j + 2, j:j + 2] @ hm.T + self.R
            predictions[i] = (zi, hx, hm)
            if len(z) == 0:
                continue
            nu = z - zi
            nu[:, 1] = (nu[:, 1] + math.pi) % (2.0 * math.pi) - math.pi
            d2 = np.einsum("ni,ij,nj->n", nu, np.linalg.inv(S), nu)
            best = np.minimum(best, d2)
            pairs += [(d2[m], m, i) for m in np.flatnonzero(d2 <= self.p["association_gate"])]
        pairs.sort()
        used_z, used_l, matches = set(), set(), []
        for _, m, i in pairs:
            if m not in used_z and i not in used_l:
                used_z.add(m)
                used_l.add(i)
                matches.append((m, i))
        if matches:
            H = np.zeros((2 * len(matches), len(self.x)))
            for row, (_, i) in enumerate(matches):
                j = 3 + 2 * i
                H[2 * row:2 * row + 2, :3] = predictions[i][1]
                H[2 * row:2 * row + 2, j:j + 2] = predictions[i][2]
            nu = np.concatenate([z[m] - predictions[i][0] for m, i in matches])
            nu[1::2] = [wrap(b) for b in nu[1::2]]
            R = np.kron(np.eye(len(matches)), self.R)
            S = H @ self.P @ H.T + R
            K = np.linalg.solve(S, H @ self.P).T
            self.x = self.x + K @ nu
            self.P = self.P - K @ S @ K.T
            self.P = 0.5 * (self.P + self.P.T)
        for i, in_fov in visible:
            if in_fov:
                self.expected[i] += 1
            if i in used_l:
                self.hits[i] += 1
        for m in range(len(z)):
            if m not in used_z and best[m] > self.p["new_landmark_gate"]:
                self._add_landmark(z[m])
        matches = [(m, self.x[3 + 2 * i:5 + 2 * i].copy()) for m, i in matches]
        self._remove_clutter()
        return matches

    def _add_landmark(self, zm):
        r, b = zm
        th = self.x[2] + b
        c, s = math.cos(th), math.sin(th)
        m = np.array([self.x[0] + r * c, self.x[1] + r * s])
        gx = np.array([[1.0, 0.0, -r * s], [0.0, 1.0, r * c]])
        gz = np.array([[c, -r * s], [s, r * c]])
        n = len(self.x)
        P = np.zeros((n + 2, n + 2))
        P[:n, :n] = self.P
        cross = gx @ self.P[:3, :n]
        P[n:, :n], P[:n, n:] = cross, cross.T
        P[n:, n:] = gx @ self.P[:3, :3] @ gx.T + gz @ self.R @ gz.T
        self.x = np.concatenate([self.x, m])
        self.P = P
        self.hits.append(1)
        self.expected.append(1)

    def _remove_clutter(self):
        keep = [i for i in range(self.landmarks)
                if self.expected[i] < self.p["min_expected"]
                or self.hits[i] >= self.p["min_hit_ratio"] * self.expected[i]]
        if len(keep) == self.landmarks:
            return
        idx = [0, 1, 2] + [3 + 2 * i + d for i in keep for d in (0, 1)]
        self.x = self.x[idx]
        self.P = self.P[np.ix_(idx, idx)]
        self.hits = [self.hits[i] for i in keep]
        self.expected = [self.expected[i] for i in keep]

    def confirmed_map(self):
        means, covs = [], []
        for i in range(self.landmarks):
            if self.hits[i] >= self.p["confirm_hits"]:
                j = 3 + 2 * i
                means.append(self.x[j:j + 2])
                covs.append(self.P[j:j + 2, j:j + 2])
        return means, covs


def run_seed(export, seed, out, params):
    data = pr.read_seed(export, seed)
    if data.models["motion"]["kind"] != "velocity":
        raise SystemExit(f"seed {seed}: this example implements the velocity motion model only")
    ekf = EkfSlam(data, params)
    poses, covs, ms, associations = [], [], [], []
    for k in range(data.steps):
        start = time.perf_counter()
        ekf.predict(data.controls[k])
        matches = ekf.update(data.measurements[k])
        ms.append(1000.0 * (time.perf_counter() - start))
        poses.append(ekf.x[:3].copy())
        covs.append(ekf.P[:3, :3].copy())
        associations.append([(m, lm[0], lm[1]) for m, lm in matches])
    folder = os.path.join(out, f"seed-{seed}")
    os.makedirs(folder, exist_ok=True)
    pr.write_trajectory(os.path.join(folder, "trajectory.tum"), data.times, poses)
    means, map_covs = ekf.confirmed_map()
    pr.write_map(os.path.join(folder, "map.csv"), means, map_covs)
    pr.write_pose_covariances(os.path.join(folder, "pose_cov.csv"), covs)
    pr.write_timing(os.path.join(folder, "timing.csv"), ms)
    pr.write_associations(os.path.join(folder, "association.csv"), associations)
    return len(means), sum(ms)


def main():
    parser = argparse.ArgumentParser(description="EKF-SLAM with nearest-neighbour association "
                                                 "on a phdslam export")
    parser.add_argument("export")
    parser.add_argument("out")
    parser.add_argument("--seeds", default=None, help="comma list (default: every exported seed)")
    args = parser.parse_args()
    manifest = pr.read_export(args.export)
    bad = pr.verify_checksums(args.export)
    if bad:
        raise SystemExit(f"{args.export}: checksum mismatch: {', '.join(bad)}")
    seeds = ([int(s) for s in args.seeds.split(",")] if args.seeds else manifest["seeds"])
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "parameters.json"), "w", encoding="utf-8") as f:
        json.dump(PARAMETERS, f, indent=2, sort_keys=True)
        f.write("\n")
    for seed in seeds:
        landmarks, total_ms = run_seed(args.export, seed, args.out, PARAMETERS)
        print(f"seed {seed}: {landmarks} landmarks, {total_ms:.0f} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
