#!/usr/bin/env python3
"""Sets two step traces side by side (the authors' release under Octave, written by
octave/phdslam_authors_run.m, and phdslam's replay on the same draws, written by
phdslam_authors_replay) and reports, per quantity, the largest difference and the first step where
it exceeds the tolerance, and the first divergence overall.

    compare_traces.py AUTHORS_TRACE PHDSLAM_TRACE [--rtol 1e-6] [--atol 1e-9]
                      [--negligible-weight 1e-12] [--json OUT]

Two numbers agree when |a - b| <= atol + rtol * max(|a|, |b|); counts, resampling flags and
sources must be equal. Proposal log-weights are compared normalised (the authors' are
unnormalised). The mean and covariance of a proposal component whose normalised weight is below
--negligible-weight on both sides are reported apart ("..., negligible weight") and never count
as a divergence: such a component moves the proposal mixture by at most its weight times the
difference, and is drawn with that probability. Its weight is still compared.
Exit 0 when everything agrees, 1 when something diverges, 2 on bad input.
"""
import argparse
import csv
import json
import math
import os
import sys


class TraceError(ValueError):
    """A trace file that cannot be compared: the message names the file, line and column."""


class Row(dict):
    """One CSV row with the file and line it came from, for the messages."""

    def __init__(self, cells, path, line):
        super().__init__(cells)
        self.path = path
        self.line = line

    def where(self, key):
        return f"{self.path} line {self.line} column '{key}'"


def read_rows(path):
    """The rows of a trace CSV; TraceError for a byte-order mark, bytes that are not ASCII, a row
    with more or fewer cells than the header, or no header."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise TraceError(f"{path}: cannot read ({e.strerror or e})") from None
    if data.startswith(b"\xef\xbb\xbf"):
        raise TraceError(f"{path}: starts with a byte-order mark; write it without one")
    try:
        text = data.decode("ascii")
    except UnicodeDecodeError as e:
        line = data[:e.start].count(b"\n") + 1
        raise TraceError(f"{path} line {line}: a byte that is not ASCII (0x{data[e.start]:02x})") \
            from None
    reader = csv.reader(text.splitlines())
    try:
        header = next(reader)
    except StopIteration:
        raise TraceError(f"{path}: empty (no header line)") from None
    rows = []
    for cells in reader:
        if len(cells) != len(header):
            raise TraceError(f"{path} line {reader.line_num}: {len(cells)} cells, the header has "
                             f"{len(header)} (a line cut short?)")
        rows.append(Row(zip(header, cells), path, reader.line_num))
    return rows


def field(row, key):
    if key not in row:
        raise TraceError(f"{row.path}: no column '{key}'")
    return row[key]


def num(row, key):
    text = field(row, key)
    try:
        return float(text)
    except ValueError:
        raise TraceError(f"{row.where(key)}: not a number: {text!r}") from None


def integer(row, key):
    text = field(row, key)
    try:
        return int(text)
    except ValueError:
        raise TraceError(f"{row.where(key)}: not an integer: {text!r}") from None


class Quantity:
    """The largest difference of one quantity and the first step beyond tolerance."""

    def __init__(self, name):
        self.name = name
        self.max_diff = 0.0
        self.max_step = None
        self.first_step = None
        self.first_detail = ""
        self.compared = 0

    def add(self, step, diff, ok, detail):
        self.compared += 1
        if diff > self.max_diff or (math.isnan(diff) and not math.isnan(self.max_diff)):
            self.max_diff = diff
            self.max_step = step
        if not ok and (self.first_step is None or step < self.first_step):
            self.first_step = step
            self.first_detail = detail

    def as_dict(self):
        return {"quantity": self.name, "compared": self.compared, "max_diff": self.max_diff,
                "max_diff_step": self.max_step, "first_divergence_step": self.first_step,
                "first_divergence": self.first_detail}


class Comparison:
    def __init__(self, rtol, atol, negligible_weight=0.0):
        self.rtol = rtol
        self.atol = atol
        self.negligible_weight = negligible_weight
        self.quantities = {}

    def q(self, name):
        if name not in self.quantities:
            self.quantities[name] = Quantity(name)
        return self.quantities[name]

    def number(self, name, step, a, b, where, gated=True):
        diff = abs(a - b)
        ok = not gated or diff <= self.atol + self.rtol * max(abs(a), abs(b))
        self.q(name).add(step, diff, ok, f"{where}: authors {a!r}, phdslam {b!r} (|diff| {diff:.3g})")

    def exact(self, name, step, a, b, where):
        ok = a == b
        self.q(name).add(step, 0.0 if ok else 1.0, ok, f"{where}: authors {a!r}, phdslam {b!r}")


def keyed(rows, keys):
    return {tuple(integer(r, k) for k in keys): r for r in rows}


def compare_particles(cmp, a_rows, b_rows):
    a = keyed(a_rows, ["step", "particle"])
    b = keyed(b_rows, ["step", "particle"])
    for key in sorted(set(a) | set(b)):
        step, i = key
        where = f"step {step}, particle {i}"
        if key not in a or key not in b:
            cmp.exact("particle present", step, key in a, key in b, where)
            continue
        ra, rb = a[key], b[key]
        for c in ("prior_x", "prior_y", "prior_theta"):
            cmp.number("prior mean", step, num(ra, c), num(rb, c), f"{where} {c}")
        for c in ("prior_pxx", "prior_pxy", "prior_pxt", "prior_pyy", "prior_pyt", "prior_ptt"):
            cmp.number("prior covariance", step, num(ra, c), num(rb, c), f"{where} {c}")
        cmp.exact("proposal components", step, integer(ra, "components"), integer(rb, "components"), where)
        for c in ("x", "y", "theta"):
            cmp.number("sampled pose", step, num(ra, c), num(rb, c), f"{where} {c}")
        cmp.number("log weight after sampling", step, num(ra, "log_weight_sampled"),
                   num(rb, "log_weight_sampled"), where)


def normalised(rows):
    """Proposal rows keyed by (step, particle, component) with normalised log-weights."""
    groups = {}
    for r in rows:
        groups.setdefault((integer(r, "step"), integer(r, "particle")), []).append(r)
    out = {}
    for (step, i), group in groups.items():
        w = [num(r, "log_weight") for r in group]
        top = max(w)
        total = top + math.log(sum(math.exp(x - top) for x in w))
        for r, x in zip(group, w):
            out[(step, i, integer(r, "component"))] = (x - total, r)
    return out


def compare_proposals(cmp, a_rows, b_rows):
    a = normalised(a_rows)
    b = normalised(b_rows)
    components = {}
    for k in a:
        components[k[:2]] = components.get(k[:2], 0) + 1
    for key in sorted(set(a) & set(b)):
        step, i, j = key
        where = f"step {step}, particle {i}, component {j}"
        (wa, ra), (wb, rb) = a[key], b[key]
        if components[key[:2]] > 1:
            cmp.number("proposal weight", step, math.exp(wa), math.exp(wb), where)
        negligible = (cmp.negligible_weight > 0
                      and max(wa, wb) < math.log(cmp.negligible_weight))
        suffix = ", negligible weight" if negligible else ""
        for c in ("x", "y", "theta"):
            cmp.number("proposal mean" + suffix, step, num(ra, c), num(rb, c), f"{where} {c}",
                       gated=not negligible)
        for c in ("pxx", "pxy", "pxt", "pyy", "pyt", "ptt"):
            cmp.number("proposal covariance" + suffix, step, num(ra, c), num(rb, c),
                       f"{where} {c}", gated=not negligible)


def compare_states(cmp, a_rows, b_rows):
    a = keyed(a_rows, ["step", "particle"])
    b = keyed(b_rows, ["step", "particle"])
    for key in sorted(set(a) & set(b)):
        step, i = key
        where = f"step {step}, particle {i}"
        ra, rb = a[key], b[key]
        cmp.number("log weight", step, num(ra, "log_weight"), num(rb, "log_weight"), where)
        for c in ("active", "passive", "births"):
            cmp.exact(f"map {c} count", step, integer(ra, c), integer(rb, c), where)


def compare_maps(cmp, a_rows, b_rows):
    a = keyed(a_rows, ["step", "particle", "list", "component"])
    b = keyed(b_rows, ["step", "particle", "list", "component"])
    for key in sorted(set(a) & set(b)):
        step = key[0]
        where = f"step {step}, particle {key[1]}, {'passive' if key[2] else 'active'} {key[3]}"
        ra, rb = a[key], b[key]
        cmp.number("map weight", step, num(ra, "log_weight"), num(rb, "log_weight"), where)
        for c in ("x", "y"):
            cmp.number("map mean", step, num(ra, c), num(rb, c), f"{where} {c}")
        for c in ("pxx", "pxy", "pyy"):
            cmp.number("map covariance", step, num(ra, c), num(rb, c), f"{where} {c}")


def compare_estimates(cmp, a_rows, b_rows):
    a = keyed(a_rows, ["step"])
    b = keyed(b_rows, ["step"])
    for key in sorted(set(a) | set(b)):
        step = key[0]
        where = f"step {step}"
        if key not in a or key not in b:
            cmp.exact("step present", step, key in a, key in b, where)
            continue
        ra, rb = a[key], b[key]
        for c in ("x", "y", "theta"):
            cmp.number("estimate", step, num(ra, c), num(rb, c), f"{where} {c}")
        cmp.exact("estimate map size", step, integer(ra, "map_size"), integer(rb, "map_size"),
                  where)
        cmp.number("ESS", step, num(ra, "ess"), num(rb, "ess"), where)
        cmp.exact("resampled", step, integer(ra, "resampled"), integer(rb, "resampled"), where)
        cmp.exact("resampling sources", step, field(ra, "sources").strip(),
                  field(rb, "sources").strip(), where)


def compare(a_dir, b_dir, rtol, atol, negligible_weight=0.0):
    cmp = Comparison(rtol, atol, negligible_weight)
    files = [("particles.csv", compare_particles), ("proposals.csv", compare_proposals),
             ("states.csv", compare_states), ("maps.csv", compare_maps),
             ("estimate.csv", compare_estimates)]
    for name, fn in files:
        fn(cmp, read_rows(os.path.join(a_dir, name)), read_rows(os.path.join(b_dir, name)))
    quantities = [q.as_dict() for q in cmp.quantities.values()]
    diverged = [q for q in quantities if q["first_divergence_step"] is not None]
    first = min(diverged, key=lambda q: q["first_divergence_step"]) if diverged else None
    return {"rtol": rtol, "atol": atol, "negligible_weight": negligible_weight,
            "quantities": quantities, "first_divergence": first}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("authors")
    ap.add_argument("phdslam")
    ap.add_argument("--rtol", type=float, default=1e-6)
    ap.add_argument("--atol", type=float, default=1e-9)
    ap.add_argument("--negligible-weight", type=float, default=1e-12,
                    help="proposal components below this normalised weight on both sides are "
                         "reported but not gated (0: gate every component)")
    ap.add_argument("--json", help="write the comparison here as JSON")
    args = ap.parse_args()
    try:
        if not 0.0 <= args.negligible_weight < 1.0:
            raise ValueError(f"--negligible-weight must be in [0, 1), got {args.negligible_weight}")
        result = compare(args.authors, args.phdslam, args.rtol, args.atol, args.negligible_weight)
    except (OSError, ValueError) as e:
        print(f"compare_traces.py: {e}", file=sys.stderr)
        return 2
    for q in result["quantities"]:
        flag = "ok" if q["first_divergence_step"] is None else f"DIVERGES at step {q['first_divergence_step']}"
        if q["quantity"].endswith("negligible weight"):
            flag = "reported, not gated"
        print(f"{q['quantity']:44s} n={q['compared']:8d} max|diff|={q['max_diff']:.3g} "
              f"(step {q['max_diff_step']}) {flag}")
    first = result["first_divergence"]
    print("first divergence: " + ("none" if first is None else
                                  f"step {first['first_divergence_step']}, {first['quantity']}: "
                                  f"{first['first_divergence']}"))
    if args.json:
        try:
            with open(args.json, "w", encoding="utf-8") as f:
                json.dump(result, f, indent=1)
        except OSError as e:
            print(f"compare_traces.py: --json {args.json}: cannot write ({e.strerror or e})",
                  file=sys.stderr)
            return 2
    return 0 if first is None else 1


if __name__ == "__main__":
    sys.exit(main())
