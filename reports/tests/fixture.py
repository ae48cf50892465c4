"""A synthetic results folder with the layout of ``phdslam run --out DIR`` (validation/README.md).

The numbers are made up but consistent: summary.csv pools the per-step errors of the runs exactly
as the runner does, so tests can check the report's arithmetic against hand computations.
"""

from __future__ import annotations

import json
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

REPORTS_DIR = Path(__file__).resolve().parent.parent
if str(REPORTS_DIR) not in sys.path:
    sys.path.insert(0, str(REPORTS_DIR))

from phdslam_reports.dependencies import ensure_dependencies  # noqa: E402

ensure_dependencies()

import numpy as np  # noqa: E402

from phdslam_reports.results import RUNS_COLUMNS, STEPS_COLUMNS, SUMMARY_COLUMNS  # noqa: E402

RUNS_EXTRA = ("pos_rmse_std_m", "heading_rmse_std_deg", "map_size", "truth_map_size",
              "pos_err_count", "ms_run")
SUMMARY_EXTRA = ("pos_rmse_std_m", "heading_rmse_std_deg", "gospa_sem_m", "map_size_mean",
                 "pos_err_count", "failed_runs", "ms_per_step_std", "ms_run_mean")
RUNS_DA = ("da_tpr", "da_tnr")
SUMMARY_DA = ("da_tpr", "da_tnr", "da_positives", "da_negatives")
DA_UNSCORED = ("phd1", "odometry")
"""Estimators whose data association is not scored: empty rates, zero counts (as the runner)."""


def da_counts(estimator: str, seed: int) -> tuple[int, int, int, int] | None:
    """The fixture's (true positives, positives, true negatives, negatives) of one run."""
    if estimator in DA_UNSCORED:
        return None
    positives, negatives = 800 + 10 * seed, 450 + 7 * seed
    miss = 0.06 if estimator == "phd2b" else 0.015 + 0.004 * seed
    return (round(positives * (1 - miss)), positives,
            round(negatives * (0.995 - 0.001 * seed)), negatives)


@dataclass
class FixtureSpec:
    """What the fixture folder holds."""

    groups: tuple[tuple[str, int], ...] = (("phd3", 1), ("phd3", 10), ("odometry", 1))
    seeds: tuple[int, ...] = (1, 2, 3)
    steps: int = 60
    scenario: str = "paper-synthetic"
    steps_option: int | None = None  # config.json scenario.options.steps (default: steps)
    pd: float = 0.95
    clutter_rate: float = 5.0
    nees: bool = False
    particles_file: bool = False
    particles_weight_column: str = "log_weight"  # as --particles-trace writes; or "weight"
    scaling: bool = False
    resampling: bool = True
    landmarks: int = 24
    gps_only: bool = False  # real data with GPS: empty truth columns, truth/seed-<s>/gps.csv
    parent_weights: bool = False  # parent_weights.csv/.json at the root
    da_rates: bool = False  # da_* columns in runs.csv and summary.csv, as the runner writes them
    error_scale: dict[str, float] = field(default_factory=lambda: {"odometry": 4.0})


def _fmt(value: float) -> str:
    return "" if value is None or not math.isfinite(value) else f"{value:.10g}"


def _write_csv(path: Path, header: list[str], rows: list[list[object]]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    lines = [",".join(header)]
    for row in rows:
        lines.append(",".join(_fmt(v) if isinstance(v, float) else str(v) for v in row))
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def truth_landmarks(count: int) -> np.ndarray:
    """Landmarks on two rings around the circular trajectory."""
    angles = np.linspace(0, 2 * np.pi, count, endpoint=False)
    radii = np.where(np.arange(count) % 2 == 0, 130.0, 70.0)
    return np.column_stack([100 + radii * np.cos(angles), 100 + radii * np.sin(angles)])


GPS_EXTRA_SECONDS = 15.0
"""The fixture's GPS fixes go on this long after the last step (outside the run's time span)."""


def circle_position(t: np.ndarray, steps: int) -> tuple[np.ndarray, np.ndarray]:
    """The fixture's true position at time t (one step per second, one lap per run)."""
    phase = 2 * np.pi * np.asarray(t, dtype=float) / max(steps, 1)
    return 100 + 100 * np.cos(phase), 100 + 100 * np.sin(phase)


def write_gps(path: Path, steps: int, rng: np.random.Generator) -> None:
    """GPS fixes ``t,x,y`` every 0.5 s from 0.25 s to GPS_EXTRA_SECONDS after the last step, with
    an outage over the second quarter of the run."""
    t = np.arange(0.25, steps - 1 + GPS_EXTRA_SECONDS, 0.5)
    t = t[(t < 0.25 * steps) | (t > 0.5 * steps)]
    x, y = circle_position(t, steps)
    x, y = x + rng.normal(0, 0.5, t.size), y + rng.normal(0, 0.5, t.size)
    _write_csv(path, ["t", "x", "y"], [[float(a), float(b), float(c)] for a, b, c in zip(t, x, y)])


PARENT_WEIGHTS_SPREAD = 10.0
"""The fixture's parent_weights.json ``spread``."""


def write_parent_weights(root: Path, parents: int = 40, true_pose: bool = True,
                         meta: bool = True, log_columns: bool = True) -> Path:
    """parent_weights.csv (and .json) as ``phdslam parent-weights --out root`` writes them.

    The parents are drawn around a predicted mean; the single-cluster weights fall off faster with
    the distance to the true pose than the RB-PHD ones: the single-cluster log-weight is the
    RB-PHD one minus missed_mass = 3 + (4/9) d^2 (d: distance to the true position), up to a
    constant, as in the program. ``log_columns`` False writes the older six columns only
    (parent,x,y,theta,sc_weight,rb_weight).
    """
    root = Path(root)
    root.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(2012)
    mean = np.array([100.0, 50.0, 0.3])
    cov = np.array([[4.0, 0.8, 0.01], [0.8, 3.0, 0.0], [0.01, 0.0, 0.01]])
    truth = np.array([101.5, 50.8, 0.32])
    poses = mean + rng.standard_normal((parents, 3)) @ np.linalg.cholesky(cov).T
    d2 = np.sum((poses[:, :2] - truth[:2]) ** 2, axis=1)
    missed = 3.0 + 4.0 / 9.0 * d2  # -0.5 d2 (single-cluster) = -d2 / 18 (RB-PHD) - missed + 3
    weights, log_weights = [], []
    for sigma in (1.0, 3.0):  # single-cluster, RB-PHD
        log_w = -0.5 * d2 / sigma ** 2
        top = log_w.max()
        log_w = log_w - (top + math.log(np.sum(np.exp(log_w - top))))  # log-sum-exp 0
        log_weights.append(log_w)
        weights.append(np.exp(log_w))
    header = ["parent", "x", "y", "theta", "sc_weight", "rb_weight"]
    rows = [[i, float(poses[i, 0]), float(poses[i, 1]), float(poses[i, 2]),
             float(weights[0][i]), float(weights[1][i])] for i in range(parents)]
    if log_columns:
        header += ["sc_log_weight", "rb_log_weight", "missed_mass"]
        for i, row in enumerate(rows):
            row += [float(log_weights[0][i]), float(log_weights[1][i]), float(missed[i])]
    _write_csv(root / "parent_weights.csv", header, rows)
    if meta:
        data = {
            "step": 100, "parents": parents, "measurements": 7, "map_components": 12,
            "previous_pose": [99.0, 49.5, 0.29], "predicted_mean": mean.tolist(),
            "predicted_cov": cov.tolist(), "true_pose": truth.tolist() if true_pose else None,
            "ess_single_cluster": float(1 / np.sum(weights[0] ** 2)),
            "ess_rb_phd": float(1 / np.sum(weights[1] ** 2)),
            "scenario": "paper-synthetic", "seed": 1,
        }
        if log_columns:  # the program writes both together
            data["spread"] = PARENT_WEIGHTS_SPREAD
        (root / "parent_weights.json").write_text(json.dumps(data, indent=2) + "\n",
                                                  encoding="utf-8")
    return root


def make_results_folder(root: Path, spec: FixtureSpec | None = None) -> Path:
    """Writes a results folder under ``root`` and returns its path."""
    spec = spec or FixtureSpec()
    root = Path(root)
    root.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(12345)
    landmarks = truth_landmarks(spec.landmarks)
    if not spec.gps_only:
        _write_csv(root / "truth_map.csv", ["x", "y", "weight", "pxx", "pxy", "pyy"],
                   [[float(x), float(y), 1.0, "", "", ""] for x, y in landmarks])

    k = np.arange(spec.steps)
    phase = 2 * np.pi * k / max(spec.steps, 1)
    x_true, y_true = circle_position(k, spec.steps)
    theta_true = phase + np.pi / 2

    run_rows, summary_rows = [], []
    for estimator, particles in spec.groups:
        scale = spec.error_scale.get(estimator, 1.0) / math.sqrt(particles)
        errs_all, heads_all, gospas, ess_all, res_all, ms_all = [], [], [], [], [], []
        for seed in spec.seeds:
            folder = root / "runs" / f"{estimator}-N{particles}" / f"seed-{seed}"
            dx = np.cumsum(rng.normal(0, 0.3 * scale, spec.steps))
            dy = np.cumsum(rng.normal(0, 0.3 * scale, spec.steps))
            dth = np.cumsum(rng.normal(0, 0.002 * scale, spec.steps))
            x, y, theta = x_true + dx, y_true + dy, theta_true + dth
            pos_err = np.hypot(dx, dy)
            head_err = np.degrees(np.abs(dth))
            ess = np.full(spec.steps, float(particles)) if particles == 1 else \
                rng.uniform(0.3, 1.0, spec.steps) * particles
            resampled = (ess < 0.5 * particles).astype(int) if particles > 1 else \
                np.zeros(spec.steps, int)
            map_components = np.minimum(spec.landmarks, 2 + k // 3)
            ms = rng.uniform(0.5, 1.5, spec.steps) * 0.1 * particles
            header = list(STEPS_COLUMNS) + (["nees", "nis_sum", "nis_count"] if spec.nees else [])
            rows = []
            if spec.gps_only:  # no true poses: empty truth and heading columns
                head_err = np.full(spec.steps, math.nan)
            truth = (x_true, y_true, theta_true) if not spec.gps_only else \
                (head_err, head_err, head_err)
            for i in range(spec.steps):
                row = [i, float(i), float(x[i]), float(y[i]), float(theta[i]), float(truth[0][i]),
                       float(truth[1][i]), float(truth[2][i]), float(pos_err[i]),
                       float(head_err[i]), float(ess[i]), int(resampled[i]),
                       3 if estimator != "odometry" else 0, int(map_components[i]), float(ms[i])]
                if spec.nees:
                    row.append(float(rng.chisquare(3)) if i > 0 else "")
                    count = int(i % 4)  # steps with 0-3 associated measurements
                    row += [float(rng.chisquare(2 * count)) if count else "",
                            count if count else ""]
                rows.append(row)
            _write_csv(folder / "steps.csv", header, rows)
            est_map = landmarks + rng.normal(0, 1.0 * scale, landmarks.shape)
            if estimator == "odometry":
                map_rows = [[float(a), float(b), 1.0, "", "", ""] for a, b in est_map]
            else:
                map_rows = [[float(a), float(b), 0.9, 4.0 * scale, 1.0 * scale, 2.0 * scale]
                            for a, b in est_map]
            _write_csv(folder / "map.csv", ["x", "y", "weight", "pxx", "pxy", "pyy"], map_rows)
            if spec.particles_file and particles > 1:
                prow = []
                weights = 1.0 / np.arange(1, particles + 1)
                weights /= np.sum(weights)
                for i in range(spec.steps):
                    for p in range(particles):
                        w = float(weights[p])
                        prow.append([i, p, float(x[i] + 2 * p), float(y[i] - p),
                                     math.log(w) if spec.particles_weight_column == "log_weight"
                                     else w])
                _write_csv(folder / "particles.csv",
                           ["step", "particle", "x", "y", spec.particles_weight_column], prow)
            (folder / "metrics.json").write_text(json.dumps(
                {"estimator": estimator, "particles": particles, "seed": seed}), encoding="utf-8")
            gospa = float(30.0 * scale + rng.normal(0, 2.0))
            if spec.gps_only:  # no true map
                gospa = math.nan
            rmse = float(np.sqrt(np.mean(pos_err ** 2)))
            hrmse = float(np.sqrt(np.mean(head_err ** 2)))
            ess_pct = float(100 * np.mean(ess / particles))
            res_pct = float(100 * np.mean(resampled))
            run_rows.append([estimator, particles, seed, spec.steps, rmse, hrmse, gospa, ess_pct,
                             res_pct, float(np.mean(ms)), float(np.std(pos_err, ddof=1)),
                             float(np.std(head_err, ddof=1)), spec.landmarks, spec.landmarks,
                             spec.steps, float(np.sum(ms))])
            if spec.da_rates:
                counts = da_counts(estimator, seed)
                run_rows[-1] += ([float(counts[0] / counts[1]), float(counts[2] / counts[3])]
                                 if counts else ["", ""])
            errs_all.append(pos_err)
            heads_all.append(head_err)
            gospas.append(gospa)
            ess_all.append(ess / particles)
            res_all.append(resampled)
            ms_all.append(ms)
        e, h = np.concatenate(errs_all), np.concatenate(heads_all)
        runs = len(spec.seeds)
        g = np.asarray(gospas)
        gstd = float(np.std(g, ddof=1)) if runs > 1 else math.nan
        summary_rows.append([
            estimator, particles, runs, float(spec.steps), float(np.sqrt(np.mean(e ** 2))),
            float(np.sqrt(np.mean(h ** 2))), float(np.mean(g)), gstd,
            float(100 * np.mean(np.concatenate(ess_all))),
            float(100 * np.mean(np.concatenate(res_all))),
            float(np.mean(np.concatenate(ms_all))), float(np.std(e, ddof=1)),
            float(np.std(h, ddof=1)), gstd / math.sqrt(runs), float(spec.landmarks), e.size, 0,
            float(np.std(np.concatenate(ms_all), ddof=1)), float(np.sum(ms_all) / runs),
        ])
        if spec.da_rates:  # pooled over every measurement of every run
            counts = [da_counts(estimator, seed) for seed in spec.seeds]
            if counts[0] is None:
                summary_rows[-1] += ["", "", 0, 0]
            else:
                tp, p, tn, n = (sum(c[i] for c in counts) for i in range(4))
                summary_rows[-1] += [float(tp / p), float(tn / n), p, n]
    da_runs, da_summary = (RUNS_DA, SUMMARY_DA) if spec.da_rates else ((), ())
    _write_csv(root / "runs.csv", list(RUNS_COLUMNS) + list(RUNS_EXTRA) + list(da_runs), run_rows)
    _write_csv(root / "summary.csv", list(SUMMARY_COLUMNS) + list(SUMMARY_EXTRA)
               + list(da_summary), summary_rows)

    parameters = {} if spec.resampling else {"resampling": False}
    config = {
        "program": {"name": "phdslam", "version": "0.1.0"},
        "experiment": "fixture",
        "scenario": {"name": spec.scenario, "options": {
            "steps": spec.steps if spec.steps_option is None else spec.steps_option,
            "detection_probability": spec.pd, "clutter_rate": spec.clutter_rate}},
        "seeds": list(spec.seeds),
        "particles": sorted({n for _, n in spec.groups}),
        "estimators": {
            name: {"description": name, "batch": False, "overrides": {},
                   "parameters": {str(n): dict(parameters) for e, n in spec.groups if e == name}}
            for name in sorted({e for e, _ in spec.groups})
        },
        "metrics": {"gospa_c": 20.0, "gospa_p": 2.0, "gps_window_s": 0.025},
        "jobs": 1,
    }
    (root / "config.json").write_text(json.dumps(config, indent=2), encoding="utf-8")
    if spec.gps_only:
        gps_rng = np.random.default_rng(54321)
        for seed in spec.seeds:
            write_gps(root / "truth" / f"seed-{seed}" / "gps.csv", spec.steps, gps_rng)
    if spec.parent_weights:
        write_parent_weights(root)
    if spec.scaling:
        rows = []
        for estimator, exponent in (("phd3", 1.0), ("phd2b", 3.0)):
            for n in (5, 10, 20, 40, 80):
                rows.append([estimator, n, float(2.0 * n ** exponent), 100])
        _write_csv(root / "scaling.csv", ["estimator", "landmarks_in_fov", "us_per_call",
                                          "calls"], rows)
        map_rows = [[m, n, 0.01 * n * (1.0 + 0.1 * i), 1000 * m + 500 * n]
                    for n in (1, 10) for i, m in enumerate((100, 1000, 10000))]
        map_rows.append([100, 1000, 12.0, 600000])
        _write_csv(root / "map_scaling.csv", ["landmarks", "particles", "ms_per_step",
                                              "map_bytes"], map_rows)
    return root
