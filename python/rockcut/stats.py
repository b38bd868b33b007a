"""Statistics over runs: means, standard errors, paired differences over specimen seeds."""
import collections
import math
import statistics


def mean(xs):
    xs = list(xs)
    return sum(xs) / len(xs) if xs else math.nan


def sem(xs):
    """Standard error of the mean: the sample standard deviation / sqrt(n); NaN below two values."""
    xs = list(xs)
    if len(xs) < 2:
        return math.nan
    m = mean(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1) / len(xs))


def mean_and_error(values):
    """(mean, standard error of the mean) of the values that are not NaN."""
    values = [v for v in values if not math.isnan(v)]
    if not values:
        return math.nan, math.nan
    return mean(values), sem(values)


def shear_fraction(tensile, shear):
    """Shear breaks over all breaks; NaN without breaks or counts."""
    if tensile is None or shear is None or tensile + shear <= 0:
        return math.nan
    return shear / (tensile + shear)


def completed_runs(rows, key):
    """The sweep.csv rows of runs that completed and have `key`."""
    return [r for r in rows if r.get("exit_code", "0") == "0" and r.get(key) not in (None, "")]


def run_shear_fraction(row):
    """A sweep.csv row's shear breaks over all its breaks."""
    return shear_fraction(float(row["breaks_tensile"]), float(row["breaks_shear"]))


def _seeds_by_value(rows, key, reference=None):
    """(values in table order, {value: {seed: row}}, the reference value) of a sweep's completed
    runs (paired_table says the order and the reference)."""
    param = next(iter(rows[0])) if rows else None
    kept = completed_runs(rows, key)
    # Numbers in ascending order; anything else (`--vary fluid.open_water_drag=false,true`) in the
    # sweep's own order. Either way the first value is the reference.
    try:
        value_of = [float(r[param]) for r in kept]
        numeric = True
    except ValueError:
        value_of = [r[param] for r in kept]
        numeric = False
    by_value = collections.defaultdict(dict)
    for v, r in zip(value_of, kept):
        by_value[v][r["seed"]] = r
    if not by_value:
        return [], by_value, None
    values = sorted(by_value) if numeric else list(by_value)
    ref_value = values[0]
    if reference is not None:
        ref_value = float(reference) if numeric else reference
        if ref_value not in by_value:
            raise ValueError("%s = %s is not a value of the sweep (its values: %s)"
                             % (param, reference, ", ".join("%g" % v if numeric else v
                                                            for v in values)))
    return values, by_value, ref_value


def paired_table(rows, key, scale=1.0, reference=None):
    """Paired differences over seeds from sweep.csv rows (dicts of strings; the first column is the
    varied parameter): [(value, runs, mean wall time, mean of key, mean difference from the
    reference value taken seed by seed, its standard error, relative to the reference's mean, mean
    shear fraction)]. The reference is the first value unless `reference` (a string, compared as a
    number where the values are numbers) names another; a reference that is not a value of the
    sweep raises ValueError. Failed runs and seeds without a partner are left out of a
    difference."""
    values, by_value, ref_value = _seeds_by_value(rows, key, reference)
    if not values:
        return []
    ref = by_value[ref_value]
    ref_mean = mean(float(r[key]) * scale for r in ref.values())
    out = []
    for v in values:
        runs = by_value[v]
        x = [float(r[key]) * scale for r in runs.values()]
        diffs = _seed_differences(runs, ref, key, scale)
        d = mean(diffs)
        out.append((v, len(runs), mean(float(r["wall_time_s"]) for r in runs.values()), mean(x),
                    d, sem(diffs), d / ref_mean if ref_mean else math.nan,
                    mean(run_shear_fraction(r) for r in runs.values())))
    return out


def _seed_differences(runs, ref, key, scale):
    """key in `runs` less key in `ref` (both {seed: row}), times scale, for the seeds of both."""
    return [(float(runs[s][key]) - float(ref[s][key])) * scale for s in runs if s in ref]


def _pair_differences(pairs, key, scale):
    """key in each (row, other row) pair's row less its other's, times scale."""
    return [(float(a[key]) - float(b[key])) * scale for a, b in pairs]


def sign_counts(diffs):
    """(median, how many below zero, how many above) of paired differences: what a mean moved by a
    few large pairs does not show."""
    return (statistics.median(diffs) if diffs else math.nan, sum(d < 0 for d in diffs),
            sum(d > 0 for d in diffs))


def paired_signs(rows, key, scale=1.0, reference=None):
    """The seed-by-seed differences from the reference value as paired_table takes them, summed up
    by their signs: [(value, pairs, median difference, pairs below, pairs above)], in
    paired_table's order (the reference's own row with no pairs)."""
    values, by_value, ref_value = _seeds_by_value(rows, key, reference)
    out = []
    for v in values:
        diffs = [] if v == ref_value else _seed_differences(by_value[v], by_value[ref_value], key,
                                                            scale)
        out.append((v, len(diffs)) + sign_counts(diffs))
    return out


def _run_pairs(rows, other_rows, key):
    """(values in table order, {value: [(row, other row)]}) for against_table."""
    def index(rs):
        param = next(iter(rs[0])) if rs else None
        return {(r[param], r["seed"]): r for r in completed_runs(rs, key)}

    here, there = index(rows), index(other_rows)
    pairs = collections.defaultdict(list)
    order = []
    for (v, s) in here:
        if (v, s) in there:
            if v not in pairs:
                order.append(v)
            pairs[v].append((here[(v, s)], there[(v, s)]))
    try:
        order.sort(key=float)
    except ValueError:
        pass
    return order, pairs


def against_table(rows, other_rows, key, scale=1.0):
    """Two sweeps of the same values and seeds, one with a change (an option set, another build),
    paired run by run: [(value, pairs, mean of key in rows, in other_rows, mean difference rows -
    other_rows over the pairs, its standard error, relative to other_rows' mean, shear fraction in
    rows, in other_rows)], one per value of the first column, in ascending order when numbers.
    A run pairs with the run of the same value and seed; failed runs and runs without a partner
    are left out."""
    order, pairs = _run_pairs(rows, other_rows, key)
    out = []
    for v in order:
        a = [float(p[0][key]) * scale for p in pairs[v]]
        b = [float(p[1][key]) * scale for p in pairs[v]]
        diffs = _pair_differences(pairs[v], key, scale)
        d, m_b = mean(diffs), mean(b)
        out.append((v, len(diffs), mean(a), m_b, d, sem(diffs), d / m_b if m_b else math.nan,
                    mean(run_shear_fraction(p[0]) for p in pairs[v]),
                    mean(run_shear_fraction(p[1]) for p in pairs[v])))
    return out


def against_signs(rows, other_rows, key, scale=1.0):
    """against_table's run-by-run differences summed up by their signs: [(value, pairs, median
    difference, pairs below, pairs above)]."""
    order, pairs = _run_pairs(rows, other_rows, key)
    return [(v, len(pairs[v])) + sign_counts(_pair_differences(pairs[v], key, scale))
            for v in order]
