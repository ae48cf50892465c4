"""The numbers behind the delta-GLMB-SLAM paper's figures (Moratuwage, Adams & Inostroza, Sensors
2019, Figs. 2-6) from results of scenario glmb-sim: per clutter rate, the RMSE in x, y and heading
at every step over the runs (heading wrapped), the map OSPA mean and standard deviation over the
runs, and the time per step mean and standard deviation.

Definitions (validation/REPRODUCTION.md uses the same):
  * RMSE_k = sqrt(mean over runs of (estimate_k - truth_k)^2), per step k, for x, y and the
    heading; the heading difference is wrapped to [-pi, pi) before squaring and reported in
    degrees. Runs missing a step (shorter runs) are left out of that step's mean.
  * OSPA of a run = the mean over its steps of map_ospa_m (steps.csv, `phdslam run --map-ospa`,
    cut-off in config.json metrics.map_ospa_c, default 5 m); mean +- std over the runs (sample
    standard deviation, ddof = 1).
  * Time per step: the steps.csv column ms of every step of every run pooled; mean +- std
    (ddof = 1).
  * False landmarks of a run: the estimates of its final map (map.csv) left without a true
    landmark closer than the OSPA cut-off c by the optimal assignment on min(d, c) (the false
    part of the final-map OSPA at c; truth_map.csv, every landmark); mean over runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable, Sequence

import numpy as np
from scipy.optimize import linear_sum_assignment

from .results import Group, ResultsFolder
from .stats import stack_ragged

GLMB_SCENARIO = "glmb-sim"
DEFAULT_MAP_OSPA_CUTOFF = 5.0


def wrap_angle(angle: np.ndarray) -> np.ndarray:
    """Angles wrapped to [-pi, pi)."""
    return (np.asarray(angle, dtype=float) + math.pi) % (2.0 * math.pi) - math.pi


@dataclass(frozen=True)
class PoseRmse:
    """Per-step RMSE over the runs of one group."""

    x: np.ndarray  # m
    y: np.ndarray  # m
    heading_deg: np.ndarray  # deg, of the wrapped difference
    runs: int


def per_step_rmse(runs: Sequence[dict[str, np.ndarray]]) -> PoseRmse:
    """RMSE per step over ``runs``, each a dict of the steps.csv columns x, y, theta, x_true,
    y_true, theta_true (arrays, possibly of unequal length)."""
    if not runs:
        empty = np.zeros(0)
        return PoseRmse(empty, empty, empty, 0)

    def rms(errors: list[np.ndarray]) -> np.ndarray:
        matrix = stack_ragged(errors)
        with np.errstate(invalid="ignore"):
            counts = np.sum(np.isfinite(matrix), axis=0)
            sums = np.nansum(matrix * matrix, axis=0)
            return np.where(counts > 0, np.sqrt(sums / np.maximum(counts, 1)), np.nan)

    ex = [np.asarray(r["x"], float) - np.asarray(r["x_true"], float) for r in runs]
    ey = [np.asarray(r["y"], float) - np.asarray(r["y_true"], float) for r in runs]
    eh = [np.degrees(wrap_angle(np.asarray(r["theta"], float) - np.asarray(r["theta_true"], float)))
          for r in runs]
    return PoseRmse(rms(ex), rms(ey), rms(eh), len(runs))


@dataclass(frozen=True)
class MeanStd:
    """Mean and sample standard deviation (ddof = 1; NaN for fewer than two values)."""

    mean: float
    std: float
    count: int


def mean_std(values: Iterable[float]) -> MeanStd:
    """Mean and sample standard deviation of the finite ``values``."""
    array = np.asarray([v for v in values if math.isfinite(v)], dtype=float)
    if array.size == 0:
        return MeanStd(math.nan, math.nan, 0)
    std = float(np.std(array, ddof=1)) if array.size > 1 else math.nan
    return MeanStd(float(np.mean(array)), std, int(array.size))


@dataclass(frozen=True)
class ClutterPoint:
    """One group (estimator, N) at one clutter rate."""

    clutter_rate: float
    group: Group
    rmse: PoseRmse
    ospa: MeanStd  # over runs of the per-run mean map OSPA (count 0 without map_ospa_m)
    step_ms: MeanStd  # over every step of every run
    folder: ResultsFolder
    false_landmarks: MeanStd  # over runs (count 0 without map.csv or truth_map.csv)


def false_landmarks(estimate: np.ndarray, truth: np.ndarray, cutoff: float) -> int:
    """Rows of ``estimate`` (n x 2) not assigned to a row of ``truth`` (m x 2) closer than
    ``cutoff`` by the optimal assignment on min(distance, cutoff)."""
    estimate = np.asarray(estimate, dtype=float).reshape(-1, 2)
    truth = np.asarray(truth, dtype=float).reshape(-1, 2)
    if estimate.shape[0] == 0 or truth.shape[0] == 0:
        return int(estimate.shape[0])
    distance = np.hypot(estimate[:, None, 0] - truth[None, :, 0],
                        estimate[:, None, 1] - truth[None, :, 1])
    rows, cols = linear_sum_assignment(np.minimum(distance, cutoff))
    matched = int(np.sum(distance[rows, cols] < cutoff))
    return int(estimate.shape[0]) - matched


def run_false_landmarks(folder: ResultsFolder, group: Group, seed: int) -> float:
    """false_landmarks of one run's final map at the folder's OSPA cut-off (NaN without the
    run's map.csv or the folder's truth_map.csv)."""
    estimate, truth = folder.run_map(group, seed), folder.truth_map
    if estimate is None or truth is None:
        return math.nan
    return float(false_landmarks(np.column_stack([estimate.num("x"), estimate.num("y")]),
                                 np.column_stack([truth.num("x"), truth.num("y")]),
                                 map_ospa_cutoff(folder)))


def map_ospa_cutoff(folder: ResultsFolder) -> float:
    """The per-step map OSPA cut-off of the folder's runs (config.json metrics.map_ospa_c)."""
    metrics = (folder.config or {}).get("metrics")
    value = metrics.get("map_ospa_c") if isinstance(metrics, dict) else None
    return float(value) if isinstance(value, (int, float)) else DEFAULT_MAP_OSPA_CUTOFF


def clutter_rate_of(folder: ResultsFolder) -> float:
    """The folder's clutter rate (config.json scenario options), NaN when not stated."""
    value = folder.scenario_options.get("clutter_rate")
    return float(value) if isinstance(value, (int, float)) else math.nan


def group_point(folder: ResultsFolder, group: Group) -> ClutterPoint | None:
    """The point of one group of a folder, or None when it has no run with steps.csv."""
    seeds = folder.seeds(group)
    if not seeds:
        return None
    runs, ospa, times = [], [], []
    false = [run_false_landmarks(folder, group, seed) for seed in seeds]
    for seed in seeds:
        steps = folder.steps(group, seed)
        runs.append({c: steps.num(c) for c in ("x", "y", "theta", "x_true", "y_true",
                                                "theta_true")})
        if steps.has("map_ospa_m"):
            values = steps.num("map_ospa_m")
            if np.any(np.isfinite(values)):
                ospa.append(float(np.nanmean(values)))
        times.extend(float(v) for v in steps.num("ms"))
    folder.forget_steps()
    return ClutterPoint(clutter_rate_of(folder), group, per_step_rmse(runs), mean_std(ospa),
                        mean_std(times), folder, mean_std(false))


def glmb_points(folders: Sequence[ResultsFolder]) -> list[ClutterPoint]:
    """Every group of every glmb-sim folder, sorted by clutter rate then group."""
    points = []
    for folder in folders:
        if folder.scenario_name != GLMB_SCENARIO:
            continue
        for group in folder.groups():
            point = group_point(folder, group)
            if point is not None:
                points.append(point)
    points.sort(key=lambda p: (p.clutter_rate, p.group))
    return points


RUN_COLUMNS = ("map_ospa_m_mean", "false_landmarks", "x_rmse_m", "y_rmse_m")
"""The per-run columns run_rows writes, for `phdslam compare`."""


def run_rows(folder: ResultsFolder) -> list[list[object]]:
    """One row per run of ``folder``: estimator, particles, seed and RUN_COLUMNS (the run's mean
    map OSPA, its false landmarks, its RMSE in x and in y over the steps)."""
    rows: list[list[object]] = []
    for group in folder.groups():
        for seed in folder.seeds(group):
            steps = folder.steps(group, seed)
            ospa = steps.num("map_ospa_m") if steps.has("map_ospa_m") else np.zeros(0)
            ospa = ospa[np.isfinite(ospa)]
            ex = steps.num("x") - steps.num("x_true")
            ey = steps.num("y") - steps.num("y_true")
            rows.append([group.estimator, group.particles, seed,
                         float(np.mean(ospa)) if ospa.size else math.nan,
                         run_false_landmarks(folder, group, seed),
                         float(np.sqrt(np.nanmean(ex * ex))), float(np.sqrt(np.nanmean(ey * ey)))])
            folder.forget_steps()
    return rows
