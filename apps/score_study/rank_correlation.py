#!/usr/bin/env python3
"""Spearman rank correlation between each score and the position RMSE, per seed, from the CSV
phdslam_score_study prints; and whether the true association scores best.

    python3 apps/score_study/rank_correlation.py STUDY.csv [STUDY.csv ...]
"""
import csv
import sys
from collections import defaultdict

SCORES = ("score_flat", "score_poisson_birth")


def ranks(values):
    order = sorted(range(len(values)), key=lambda i: values[i])
    out = [0.0] * len(values)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
            j += 1
        for k in range(i, j + 1):
            out[order[k]] = (i + j) / 2.0
        i = j + 1
    return out


def spearman(x, y):
    rx, ry = ranks(x), ranks(y)
    n = len(x)
    mx, my = sum(rx) / n, sum(ry) / n
    sxy = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    sxx = sum((a - mx) ** 2 for a in rx)
    syy = sum((b - my) ** 2 for b in ry)
    return sxy / (sxx * syy) ** 0.5 if sxx > 0 and syy > 0 else float("nan")


def main(paths):
    for path in paths:
        groups = defaultdict(list)
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                groups[row["seed"]].append(row)
        print(f"{path}: {len(groups)} seeds")
        print("| seed | solutions | " + " | ".join(f"Spearman {s}" for s in SCORES) +
              " | " + " | ".join(f"truth best ({s})" for s in SCORES) + " |")
        means = defaultdict(list)
        best = defaultdict(int)
        for seed, rows in groups.items():
            rmse = [float(r["pos_rmse_m"]) for r in rows]
            cells = []
            flags = []
            for s in SCORES:
                score = [float(r[s]) for r in rows]
                rho = spearman(score, rmse)
                means[s].append(rho)
                cells.append(f"{rho:.3f}")
                truth = min(float(r[s]) for r in rows if r["variant"] == "truth")
                others = min(float(r[s]) for r in rows if r["variant"] != "truth")
                ok = truth <= others  # a corruption that changed nothing ties
                best[s] += ok
                flags.append("yes" if ok else "no")
            print(f"| {seed} | {len(rows)} | " + " | ".join(cells) + " | " + " | ".join(flags) + " |")
        print("| mean | | " + " | ".join(f"{sum(v) / len(v):.3f}" for v in means.values()) +
              " | " + " | ".join(f"{best[s]}/{len(groups)}" for s in SCORES) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
