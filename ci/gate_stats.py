"""Statistics of the paired accuracy gates (ci/GATES.md, "The paired tier").

A paired gate compares the per-seed values of one metric, new against baseline, on the same seeds.
Per seed it takes the log ratio d = ln(new / baseline), so a change that scales the metric by
(1 + e) moves d by ln(1 + e) whatever the seed's own size, and a divergent run weighs no more than
a ratio can. The location of d is Yuen's trimmed mean (20 % off each end by default): the heavy
tails of the per-seed differences (a few divergent runs, ci/GATES.md) barely move it, while a
change of most seeds does. The test is one-sided: a gate fails when the trimmed mean is
significantly above 0 at the per-gate level alpha / K (Bonferroni over the K paired gates, so the
family's false-alarm rate is at most alpha under any dependence between gates).

A change below the indifference threshold e0 (0.1 % by default) is never a regression: the null
hypothesis is "the location is at most ln(1 + e0)", so a change of the rounding only, which moves
every seed by a part in a million, passes however many seeds agree on its sign.

Power: with the winsorised standard deviation s_w of d under a neutral change, the trimmed mean's
standard error is s_w / ((1 - 2 g) sqrt(n)) (Yuen 1974), so a regression of the margin m (d shifted
by ln(1 + m)) fails with probability Phi((ln(1 + m) - ln(1 + e0)) / SE - c) for the critical value
c. The seed count that gives power P at the margin is
n = ((c + z_P) s_w / ((1 - 2 g) (ln(1 + m) - ln(1 + e0))))^2, and the minimum detectable effect
with n seeds is (1 + e0) exp((c + z_P) s_w / ((1 - 2 g) sqrt(n))) - 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from statistics import NormalDist

_NORMAL = NormalDist()


def normal_quantile(p: float) -> float:
    """The standard normal quantile of p (0 < p < 1)."""
    return _NORMAL.inv_cdf(p)


def normal_cdf(x: float) -> float:
    return _NORMAL.cdf(x)


def student_t_quantile(p: float, df: int) -> float:
    """The Student t quantile of p with df degrees of freedom (Cornish-Fisher series of the normal
    quantile, Abramowitz & Stegun 26.7.5; relative error below 1e-4 for df >= 10 in the tails used
    here, and exact in the normal limit)."""
    if df < 1:
        raise ValueError("the t distribution needs at least 1 degree of freedom")
    z = normal_quantile(p)
    g1 = (z**3 + z) / 4.0
    g2 = (5 * z**5 + 16 * z**3 + 3 * z) / 96.0
    g3 = (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / 384.0
    g4 = (79 * z**9 + 776 * z**7 + 1482 * z**5 - 1920 * z**3 - 945 * z) / 92160.0
    return z + g1 / df + g2 / df**2 + g3 / df**3 + g4 / df**4


def trim_count(n: int, trim: float) -> int:
    """How many values Yuen's trimmed mean drops from each end of n values."""
    return int(math.floor(trim * n))


def trimmed_mean(values: list[float], trim: float) -> float:
    """The mean of the values left after dropping trim_count() from each end of the sorted list."""
    ordered = sorted(values)
    g = trim_count(len(ordered), trim)
    kept = ordered[g:len(ordered) - g]
    return sum(kept) / len(kept)


def winsorised_sd(values: list[float], trim: float) -> float:
    """The sample standard deviation (n - 1) of the values with the trim_count() lowest set to the
    lowest kept one and the highest likewise."""
    ordered = sorted(values)
    n = len(ordered)
    g = trim_count(n, trim)
    if n < 2:
        return 0.0
    low, high = ordered[g], ordered[n - 1 - g]
    wins = [min(max(v, low), high) for v in ordered]
    mean = sum(wins) / n
    return math.sqrt(sum((v - mean) ** 2 for v in wins) / (n - 1))


@dataclass(frozen=True)
class YuenTest:
    """Yuen's one-sample trimmed-mean test of 'the location of d is at most 0' against 'above 0'."""

    n: int
    kept: int  # h = n - 2 g
    location: float  # trimmed mean of d
    standard_error: float
    statistic: float  # location / standard_error (inf when the standard error is 0 and d > 0)
    critical: float  # t quantile of 1 - alpha with h - 1 degrees of freedom
    rejected: bool  # True: significantly worse than the baseline


def yuen_test(d: list[float], trim: float, alpha: float, indifference: float = 0.0) -> YuenTest:
    """One-sided Yuen test at level alpha of 'the location of d is at most ln(1 + indifference)';
    d are the per-seed log ratios new / baseline."""
    n = len(d)
    if n < 5:
        raise ValueError(f"a paired gate needs at least 5 common seeds, got {n}")
    g = trim_count(n, trim)
    h = n - 2 * g
    location = trimmed_mean(d, trim)
    sw = winsorised_sd(d, trim)
    se = math.sqrt((n - 1) * sw * sw / (h * (h - 1))) if h > 1 else 0.0
    critical = student_t_quantile(1.0 - alpha, h - 1)
    excess = location - math.log1p(indifference)
    if se == 0.0:
        statistic = math.inf if excess > 0 else (0.0 if excess == 0 else -math.inf)
    else:
        statistic = excess / se
    return YuenTest(n, h, location, se, statistic, critical, statistic > critical)


def critical_value(alpha: float) -> float:
    """The normal critical value of a one-sided test at level alpha (the planning value)."""
    return normal_quantile(1.0 - alpha)


def seeds_needed(spread: float, margin: float, alpha: float, power: float, trim: float,
                 indifference: float = 0.0) -> int:
    """Seeds with which a regression of `margin` (a fraction, 0.05 = 5 %) fails with probability
    `power`, for per-seed log ratios of winsorised standard deviation `spread` under a neutral
    change."""
    if spread <= 0.0:
        return 5
    z = critical_value(alpha) + normal_quantile(power)
    shift = math.log1p(margin) - math.log1p(indifference)
    return max(5, math.ceil((z * spread / ((1.0 - 2.0 * trim) * shift)) ** 2))


def minimum_detectable_effect(spread: float, seeds: int, alpha: float, power: float,
                              trim: float, indifference: float = 0.0) -> float:
    """The regression (a fraction) that fails with probability `power` with `seeds` seeds."""
    if spread <= 0.0:
        return indifference
    z = critical_value(alpha) + normal_quantile(power)
    return math.expm1(z * spread / ((1.0 - 2.0 * trim) * math.sqrt(seeds))
                      + math.log1p(indifference))


def power_at(effect: float, spread: float, seeds: int, alpha: float, trim: float,
             indifference: float = 0.0) -> float:
    """The probability that a regression of `effect` (a fraction) fails the gate."""
    excess = math.log1p(effect) - math.log1p(indifference)
    if spread <= 0.0:
        return 1.0 if excess > 0 else 0.0
    se = spread / ((1.0 - 2.0 * trim) * math.sqrt(seeds))
    return normal_cdf(excess / se - critical_value(alpha))


def mean_and_se(values: list[float]) -> tuple[float, float]:
    """The mean and its standard error (sample sd / sqrt(n))."""
    n = len(values)
    mean = sum(values) / n
    if n < 2:
        return mean, 0.0
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    return mean, sd / math.sqrt(n)


def pooled_rmse_and_se(rmse: list[float], counts: list[float]) -> tuple[float, float]:
    """The RMSE pooled over every step of every run, sqrt(sum(n_i r_i^2) / sum(n_i)), and its
    standard error by the delta method over runs (runs as the independent units)."""
    total = sum(counts)
    squares = [c * r * r for r, c in zip(rmse, counts)]
    pooled = math.sqrt(sum(squares) / total)
    n = len(rmse)
    if n < 2 or pooled == 0.0:
        return pooled, 0.0
    # ratio estimator sum(c r^2) / sum(c): its variance over runs, then sqrt's derivative.
    ratio = pooled * pooled
    mean_c = total / n
    residuals = [(s - ratio * c) / mean_c for s, c in zip(squares, counts)]
    var = sum(e * e for e in residuals) / (n - 1) / n
    return pooled, math.sqrt(var) / (2.0 * pooled)
