#!/usr/bin/python3
"""Paired differences over specimen seeds in a scripts/sweep CSV (docs/accuracy.md, "The coupling
interval over sixteen seeds").

  scripts/paired_differences SWEEP_CSV [--key force_horizontal_mean_n_per_m] [--scale 1e-3]

SWEEP_CSV is a sweep's sweep.csv, run with --seeds: its first column is the varied parameter.
Every value is run on the same specimens, so its difference from the first (smallest) value is
taken seed by seed; the mean of those differences and its standard error resolve a change that
the seeds' own spread hides. Prints a markdown table, one row per value: runs, mean wall time,
mean of KEY (times --scale), the mean paired difference from the first value ± its standard
error (and relative to the first value's mean), and the mean shear fraction of the broken bonds.
Seeds missing from either value, and failed runs, are left out of a difference.
"""
import argparse
import collections
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from accuracy import mean, sem  # noqa: E402


def table(rows, key, scale=1.0):
    """[(value, runs, wall, mean, diff, diff_sem, diff_rel, shear)] from sweep.csv rows."""
    param = next(iter(rows[0])) if rows else None
    by_value = collections.defaultdict(dict)
    for r in rows:
        if r.get("exit_code", "0") == "0" and r.get(key) not in (None, ""):
            by_value[float(r[param])][r["seed"]] = r
    if not by_value:
        return []
    values = sorted(by_value)
    ref = by_value[values[0]]
    ref_mean = mean([float(r[key]) * scale for r in ref.values()])
    out = []
    for v in values:
        runs = by_value[v]
        x = [float(r[key]) * scale for r in runs.values()]
        diffs = [(float(runs[s][key]) - float(ref[s][key])) * scale for s in runs if s in ref]
        shear = [float(r["breaks_shear"]) / (float(r["breaks_shear"]) + float(r["breaks_tensile"]))
                 for r in runs.values()]
        d = mean(diffs)
        out.append((v, len(runs), mean([float(r["wall_time_s"]) for r in runs.values()]), mean(x),
                    d, sem(diffs), d / ref_mean if ref_mean else float("nan"), mean(shear)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("--key", default="force_horizontal_mean_n_per_m")
    ap.add_argument("--scale", type=float, default=1e-3)
    a = ap.parse_args()
    try:
        with open(a.csv) as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit("scripts/paired_differences: %s" % e)
    if not rows or a.key not in rows[0] or "seed" not in rows[0]:
        sys.exit("scripts/paired_differences: %s has no seed column or no %s column" % (a.csv, a.key))
    param = next(iter(rows[0]))
    print("| %s | runs | wall [s] | %s | difference from the first | shear fraction |" % (param, a.key))
    print("|---:|---:|---:|---:|---:|---:|")
    for i, (v, n, wall, m, d, e, rel, sh) in enumerate(table(rows, a.key, a.scale)):
        diff = "" if i == 0 else "%+.1f ± %.1f (%+.0f %%)" % (d, e, 100 * rel)
        print("| %g | %d | %.1f | %.1f | %s | %.2f |" % (v, n, wall, m, diff, sh))


if __name__ == "__main__":
    main()
