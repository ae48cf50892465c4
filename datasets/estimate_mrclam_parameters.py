#!/usr/bin/env python3
"""Estimates the one model of the `mrclam` scenario from the five robots of one MRCLAM sub-dataset.

Usage: python3 datasets/estimate_mrclam_parameters.py DATA_DIR/utias-mrclam/MRCLAM_Dataset6 [--json]
       python3 datasets/estimate_mrclam_parameters.py DATA_DIR/... --heading-drift 1,10,30,60

Reads the folder's .dat files (the layout of datasets/mrclam.h), follows the scenario's rules
(steps = images, Vicon truth interpolated with the heading unwrapped, steps in truth gaps longer
than 0.5 s left out, commanded odometry held between time stamps and integrated by the unicycle
model) and prints, with the method of each:
  - range and bearing noise: residuals of landmark detections against the Vicon prediction;
  - field of view: the largest |bearing| of any detection and the largest landmark range;
  - detection probability: of the true landmarks inside that field of view of each image (a
    step), which the image detected; the rate falls with range, so the model is
    pD = pd_max (1 - r / fov_range), with pd_max such that the expected number of detections
    equals the observed one: pd_max = detected / sum over (image, landmark inside) of (1 - r / R);
  - clutter rate: detections that are not of a landmark, per step;
  - odometry noise: maximum-likelihood sigma_v, sigma_w of the filters' model (control noise held
    over each sub-interval) from the Vicon relative motion between consecutive steps.
The numbers are the defaults of datasets::MrclamOptions (datasets/mrclam.h).
"""
import argparse
import json
import math
import pathlib
import sys

import numpy as np

MAX_TRUTH_GAP = 0.5  # s, kMrclamMaxTruthGap
OUTLIER_RANGE = 1.0  # m: residuals beyond are outliers (not noise)
OUTLIER_BEARING = 0.2  # rad
ROBOTS = range(1, 6)


def load(path, columns):
    data = np.loadtxt(path, comments="#", ndmin=2)
    if data.shape[1] != columns:
        sys.exit(f"{path}: expected {columns} columns, found {data.shape[1]}")
    return data


def sorted_unique(data, keep):
    """Rows sorted stably by time; of equal time stamps the first or last is kept."""
    data = data[np.argsort(data[:, 0], kind="stable")]
    if keep == "last":
        mask = np.append(np.diff(data[:, 0]) != 0, True)
    else:
        mask = np.insert(np.diff(data[:, 0]) != 0, 0, True)
    return data[mask]


def interpolate_truth(truth, t):
    """Poses at times t and whether each is scored (inside the span, no gap > 0.5 s)."""
    times = truth[:, 0]
    hi = np.searchsorted(times, t, side="right")
    inside = (hi > 0) & (hi < len(times))
    hi_c = np.clip(hi, 1, len(times) - 1)
    lo_c = hi_c - 1
    span = times[hi_c] - times[lo_c]
    a = np.clip((t - times[lo_c]) / span, 0.0, 1.0)[:, None]
    pose = (1 - a) * truth[lo_c, 1:4] + a * truth[hi_c, 1:4]
    exact = np.isin(t, times)
    scored = exact | (inside & (span <= MAX_TRUTH_GAP))
    return pose, scored


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def unicycle(x, v, w, dt):
    if abs(w) < 1e-9:
        return np.array([x[0] + v * dt * math.cos(x[2]), x[1] + v * dt * math.sin(x[2]), x[2]])
    th1 = x[2] + w * dt
    return np.array([x[0] + v / w * (math.sin(th1) - math.sin(x[2])),
                     x[1] + v / w * (math.cos(x[2]) - math.cos(th1)), th1])


def load_robot(folder, robot):
    truth = sorted_unique(load(folder / f"Robot{robot}_Groundtruth.dat", 4), "first")
    truth[:, 3] = np.unwrap(truth[:, 3])
    odometry = sorted_unique(load(folder / f"Robot{robot}_Odometry.dat", 3), "last")
    meas = load(folder / f"Robot{robot}_Measurement.dat", 4)
    meas = meas[np.argsort(meas[:, 0], kind="stable")]
    return truth, odometry, meas


def odometry_window(odometry, t0, t1):
    """Relative pose integrated from t0 to t1 and sum of squared sub-interval lengths."""
    times = odometry[:, 0]
    held = np.searchsorted(times, t0, side="right") - 1
    stamps = [t0]
    controls = [odometry[held, 1:3] if held >= 0 else np.zeros(2)]
    i = held + 1
    while i < len(times) and times[i] < t1:
        stamps.append(times[i])
        controls.append(odometry[i, 1:3])
        i += 1
    stamps.append(t1)
    x = np.zeros(3)
    s = 0.0
    for k, u in enumerate(controls):
        dt = stamps[k + 1] - stamps[k]
        x = unicycle(x, u[0], u[1], dt)
        s += dt * dt
    return x, s


def estimate(folder):
    barcodes = load(folder / "Barcodes.dat", 2)
    subject_of = {int(b): int(s) for s, b in barcodes}
    landmarks = load(folder / "Landmark_Groundtruth.dat", 5)
    position = {int(row[0]): row[1:3] for row in landmarks}
    lm_xy = landmarks[:, 1:3]
    lm_subjects = landmarks[:, 0].astype(int)

    range_res, bearing_res, lm_ranges = [], [], []
    all_bearings = []
    per_robot_steps = []
    clutter, steps_total = 0, 0
    e_forward, e_heading, scale = [], [], []
    for robot in ROBOTS:
        truth, odometry, meas = load_robot(folder, robot)
        first = max(odometry[0, 0], truth[0, 0])
        keep = (meas[:, 0] >= first) & (meas[:, 0] <= odometry[-1, 0])
        meas = meas[keep]
        all_bearings.extend(np.abs(meas[:, 3]))
        pose, scored = interpolate_truth(truth, meas[:, 0])
        subjects = np.array([subject_of.get(int(b), 0) for b in meas[:, 1]])
        is_landmark = np.isin(subjects, lm_subjects)
        clutter += int(np.sum(~is_landmark))
        images = np.unique(meas[:, 0])
        steps_total += len(images)
        per_robot_steps.append(images)
        for k in np.nonzero(is_landmark & scored)[0]:
            m = position[subjects[k]]
            d = m - pose[k, :2]
            range_res.append(meas[k, 2] - np.hypot(*d))
            bearing_res.append(wrap(meas[k, 3] - (math.atan2(d[1], d[0]) - pose[k, 2])))
            lm_ranges.append(meas[k, 2])
        # Odometry over each interval between consecutive images, both ends scored.
        img_pose, img_scored = interpolate_truth(truth, images)
        for j in range(1, len(images)):
            if not (img_scored[j - 1] and img_scored[j]):
                continue
            rel, s = odometry_window(odometry, images[j - 1], images[j])
            th0 = img_pose[j - 1, 2]
            d = img_pose[j, :2] - img_pose[j - 1, :2]
            forward = math.cos(th0) * d[0] + math.sin(th0) * d[1]
            e_forward.append(forward - rel[0])
            e_heading.append((img_pose[j, 2] - th0) - rel[2])
            scale.append(s)
        per_robot_steps[-1] = (images, img_pose, img_scored, meas, subjects)

    range_res = np.array(range_res)
    bearing_res = np.array(bearing_res)
    inlier = (np.abs(range_res) <= OUTLIER_RANGE) & (np.abs(bearing_res) <= OUTLIER_BEARING)
    fov_half_angle = math.ceil(max(all_bearings) * 10) / 10
    fov_range = math.ceil(max(lm_ranges))

    # Detection probability: landmarks inside the FOV of each scored image, and which it saw.
    inside_total, detected_total, linear_total = 0, 0, 0.0
    bins = np.arange(0, fov_range + 1, 1.0)
    inside_bins = np.zeros(len(bins) - 1)
    detected_bins = np.zeros(len(bins) - 1)
    for images, img_pose, img_scored, meas, subjects in per_robot_steps:
        for j, t in enumerate(images):
            if not img_scored[j]:
                continue
            x = img_pose[j]
            d = lm_xy - x[:2]
            r = np.hypot(d[:, 0], d[:, 1])
            b = np.array([wrap(a) for a in np.arctan2(d[:, 1], d[:, 0]) - x[2]])
            inside = (r <= fov_range) & (np.abs(b) <= fov_half_angle)
            seen = set(subjects[meas[:, 0] == t])
            detected = inside & np.isin(lm_subjects, list(seen))
            inside_total += int(inside.sum())
            linear_total += float(np.sum(1.0 - r[inside] / fov_range))
            detected_total += int(detected.sum())
            idx = np.clip(np.digitize(r, bins) - 1, 0, len(bins) - 2)
            np.add.at(inside_bins, idx[inside], 1)
            np.add.at(detected_bins, idx[detected], 1)

    e_forward, e_heading, scale = map(np.array, (e_forward, e_heading, scale))
    ok = scale > 0
    return {
        "landmark_detections_scored": int(len(range_res)),
        "outlier_fraction": float(1 - inlier.mean()),
        "range_sigma_m": float(range_res[inlier].std(ddof=1)),
        "range_bias_m": float(range_res[inlier].mean()),
        "bearing_sigma_rad": float(bearing_res[inlier].std(ddof=1)),
        "bearing_bias_rad": float(bearing_res[inlier].mean()),
        "max_abs_bearing_rad": float(max(all_bearings)),
        "max_landmark_range_m": float(max(lm_ranges)),
        "fov_half_angle_rad": fov_half_angle,
        "fov_range_m": float(fov_range),
        "detection_rate_inside_fov": detected_total / inside_total,
        "detection_probability_max": detected_total / linear_total,
        "landmarks_inside_fov": inside_total,
        "detection_rate_by_range_m": {
            f"{bins[i]:.0f}-{bins[i + 1]:.0f}": (detected_bins[i] / inside_bins[i]
                                                 if inside_bins[i] else None)
            for i in range(len(bins) - 1)},
        "steps": steps_total,
        "clutter_detections": clutter,
        "clutter_rate_per_step": clutter / steps_total,
        "odometry_windows": int(ok.sum()),
        "sigma_v_mps": float(math.sqrt(np.mean(e_forward[ok] ** 2 / scale[ok]))),
        "sigma_w_radps": float(math.sqrt(np.mean(e_heading[ok] ** 2 / scale[ok]))),
    }


def heading_drift(folder, sigma_w, windows):
    """Heading residual of the integrated commands against the Vicon heading over windows of at
    least T seconds (consecutive, non-overlapping, every image inside scored), per T: the number
    of windows, the RMS residual and the RMS the model predicts (sigma_w^2 sum dt^2)."""
    robots = []
    for robot in ROBOTS:
        truth, odometry, meas = load_robot(folder, robot)
        first = max(odometry[0, 0], truth[0, 0])
        images = np.unique(meas[(meas[:, 0] >= first) & (meas[:, 0] <= odometry[-1, 0]), 0])
        pose, scored = interpolate_truth(truth, images)
        robots.append((odometry, images, pose, scored))
    rows = []
    for T in windows:
        err, scale = [], []
        for odometry, images, pose, scored in robots:
            a = 0
            for j in range(1, len(images)):
                if images[j] - images[a] < T:
                    continue
                if scored[a:j + 1].all():
                    rel, s = odometry_window(odometry, images[a], images[j])
                    err.append((pose[j, 2] - pose[a, 2]) - rel[2])
                    scale.append(s)
                a = j
        err, scale = np.array(err), np.array(scale)
        rows.append((T, len(err), float(np.sqrt(np.mean(err ** 2))),
                     float(sigma_w * np.sqrt(np.mean(scale)))))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", type=pathlib.Path, help="an MRCLAM_DatasetN folder")
    parser.add_argument("--json", action="store_true", help="print JSON only")
    parser.add_argument("--heading-drift", metavar="T,...",
                        help="instead: the heading residual of the integrated commands over "
                             "windows of at least T s against the model's sigma_w (e.g. 1,10,30,60)")
    args = parser.parse_args()
    if args.heading_drift:
        try:
            windows = [float(t) for t in args.heading_drift.split(",")]
        except ValueError:
            sys.exit(f"--heading-drift: expected seconds separated by commas, got {args.heading_drift!r}")
        if not windows or any(not (t > 0 and math.isfinite(t)) for t in windows):
            sys.exit("--heading-drift: every window must be a positive number of seconds")
        sigma_w = estimate(args.folder)["sigma_w_radps"]
        print(f"window >= T s  windows  RMS heading residual (rad)  model RMS (rad, sigma_w {sigma_w:.4g})")
        for T, n, rms, model in heading_drift(args.folder, sigma_w, windows):
            print(f"{T:13g}  {n:7d}  {rms:26.4f}  {model:.4f}")
        return
    result = estimate(args.folder)
    if args.json:
        print(json.dumps(result, indent=2))
        return
    for key, value in result.items():
        if isinstance(value, dict):
            print(f"{key}:")
            for k, v in value.items():
                print(f"  {k}: {'-' if v is None else f'{v:.4g}'}")
        else:
            print(f"{key}: {value:.6g}" if isinstance(value, float) else f"{key}: {value}")


if __name__ == "__main__":
    main()
