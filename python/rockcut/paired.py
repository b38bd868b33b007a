"""Paired differences over specimen seeds in a rockcut sweep CSV (docs/record/accuracy.md,
"The coupling interval over sixteen seeds").

  rockcut paired SWEEP_CSV [SWEEP_CSV ...] [--key force_horizontal_mean_n_per_m] [--scale 1e-3] [--reference V]
  rockcut paired SWEEP_CSV [SWEEP_CSV ...] --against OTHER_CSV [OTHER_CSV ...] [--key ...]
  ... [--signs]

SWEEP_CSV is a sweep's sweep.csv, run with --seeds: its first column is the varied parameter.
Several are read as one sweep: the same sweep run in batches of seeds (`--seeds 1,...,8`, then
`--seeds 9,...,16`), which must vary the same parameter on the same scene; a value and seed run in two of them is
refused, naming both. OTHER_CSV, likewise.
Every value is run on the same specimens, so its difference from the reference value (the first,
smallest, unless --reference names another: the scene's own setting, say) is taken seed by seed;
the mean of those differences and its standard error resolve a change that the seeds' own spread
hides. Prints a markdown table, one row per value: runs, mean wall time, mean of KEY (times
--scale), the mean paired difference from the reference ± its standard error (and relative to the
reference's mean), and the mean shear fraction of the broken bonds. Seeds missing from either
value, and failed runs, are left out of a difference.

With --against, two sweeps of the same values and seeds (the same sweep run again with one
option changed, `--set fluid.open_water_drag=true` say) are paired run by run: one row per value,
the pairs, KEY in each, the mean difference SWEEP_CSV - OTHER_CSV ± its standard error (and
relative to OTHER_CSV's mean), and the shear fractions.

With --signs, two more columns say whether a mean difference is the seeds' or a few seeds': the
median of the paired differences, and in how many pairs the value lies below and above its
partner ("17 / 15 of 32"). A mean moved by a tail of a few seeds shows a median near zero and
about as many pairs either way.
"""
import argparse
import csv
import os
import sys

from .stats import against_signs, against_table, paired_signs, paired_table



def table(rows, key, scale=1.0, reference=None):
    """[(value, runs, wall, mean, diff, diff_sem, diff_rel, shear)] from sweep.csv rows
    (stats.paired_table)."""
    return paired_table(rows, key, scale, reference)


def read_rows(path, key):
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit("rockcut paired: %s" % e)
    if not rows or key not in rows[0] or "seed" not in rows[0]:
        sys.exit("rockcut paired: %s has no seed column or no %s column" % (path, key))
    return rows


def read_sweeps(paths, key):
    """The rows of several sweep.csv files of one varied parameter, as one sweep; exits with one
    line if they vary different parameters or two of them hold the same value and seed."""
    rows, param, scene, where = [], None, None, {}
    for path in paths:
        these = read_rows(path, key)
        name = next(iter(these[0]))
        # A sweep run from another checkout names its scene by another path: the file's name says.
        this_scene = os.path.basename(these[0].get("scene", ""))
        if param is None:
            param, scene = name, this_scene
        elif name != param:
            sys.exit("rockcut paired: %s varies %s, %s varies %s: not one sweep"
                     % (paths[0], param, path, name))
        elif this_scene != scene:
            sys.exit("rockcut paired: %s ran %s, %s ran %s: not one sweep"
                     % (paths[0], scene or "no scene", path, this_scene or "no scene"))
        for r in these:
            run = (r[param], r["seed"])
            if run in where:
                sys.exit("rockcut paired: %s = %s, seed %s is in %s and in %s: give each run once"
                         % (param, run[0], run[1], where[run], path))
            where[run] = path
        rows += these
    return rows


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut paired", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", nargs="+", help="a sweep's sweep.csv; several: one sweep run in batches of seeds")
    ap.add_argument("--key", default="force_horizontal_mean_n_per_m")
    ap.add_argument("--scale", type=float, default=1e-3)
    ap.add_argument("--against", metavar="OTHER_CSV", nargs="+",
                    help="pair each run with the run of the same value and seed in this sweep")
    ap.add_argument("--reference", metavar="VALUE",
                    help="the value the others are differenced from (default: the first)")
    ap.add_argument("--signs", action="store_true",
                    help="add the median paired difference and how many pairs lie below / above")
    a = ap.parse_args(argv)
    if a.against and a.reference is not None:
        sys.exit("rockcut paired: --reference pairs values of one sweep; --against pairs two "
                 "sweeps run by run: give one of them")
    rows = read_sweeps(a.csv, a.key)
    sweep = " ".join(a.csv)
    param = next(iter(rows[0]))
    if a.against:
        other = read_sweeps(a.against, a.key)
        others = " ".join(a.against)
        if next(iter(other[0])) != param:
            sys.exit("rockcut paired: %s varies %s, %s varies %s: nothing to pair"
                     % (sweep, param, others, next(iter(other[0]))))
        t = against_table(rows, other, a.key, a.scale)
        if not t:
            sys.exit("rockcut paired: no run of %s has a partner of the same value and seed in %s"
                     % (sweep, others))
        signs = against_signs(rows, other, a.key, a.scale) if a.signs else None
        print("| %s | pairs | %s | against | difference | shear fraction, against |%s"
              % (param, a.key, SIGN_HEADER if a.signs else ""))
        print("|---:|---:|---:|---:|---:|---:|" + ("---:|---:|" if a.signs else ""))
        for i, (v, n, m_a, m_b, d, e, rel, sh_a, sh_b) in enumerate(t):
            print("| %s | %d | %.1f | %.1f | %+.1f ± %.1f (%+.0f %%) | %.2f, %.2f |%s"
                  % (v, n, m_a, m_b, d, e, 100 * rel, sh_a, sh_b,
                     sign_cells(signs[i]) if a.signs else ""))
        return
    try:
        t = table(rows, a.key, a.scale, a.reference)
    except ValueError as e:
        sys.exit("rockcut paired: --reference: %s" % e)
    ref_name = "the first" if a.reference is None else "%s = %s" % (param, a.reference)
    print("| %s | runs | wall [s] | %s | difference from %s | shear fraction |%s"
          % (param, a.key, ref_name, SIGN_HEADER if a.signs else ""))
    print("|---:|---:|---:|---:|---:|---:|" + ("---:|---:|" if a.signs else ""))
    if not t:
        sys.exit("rockcut paired: %s has no completed run" % sweep)
    signs = paired_signs(rows, a.key, a.scale, a.reference) if a.signs else None
    ref_value = t[0][0]
    if a.reference is not None:
        ref_value = float(a.reference) if isinstance(ref_value, float) else a.reference
    for i, (v, n, wall, m, d, e, rel, sh) in enumerate(t):
        diff = "" if v == ref_value else "%+.1f ± %.1f (%+.0f %%)" % (d, e, 100 * rel)
        value = "%g" % v if isinstance(v, float) else v
        extra = ""
        if a.signs:
            extra = " | |" if v == ref_value else sign_cells(signs[i])
        print("| %s | %d | %.1f | %.1f | %s | %.2f |%s" % (value, n, wall, m, diff, sh, extra))


SIGN_HEADER = " median difference | below / above |"


def sign_cells(signs):
    """The --signs columns of one row: (value, pairs, median, below, above)."""
    _, n, med, below, above = signs
    return " %+.1f | %d / %d of %d |" % (med, below, above, n)
