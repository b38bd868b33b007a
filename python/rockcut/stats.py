"""Statistics over runs: means, standard errors, paired differences over specimen seeds."""
import collections
import math


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


def paired_table(rows, key, scale=1.0):
    """Paired differences over seeds from sweep.csv rows (dicts of strings; the first column is the
    varied parameter): [(value, runs, mean wall time, mean of key, mean difference from the first
    value taken seed by seed, its standard error, relative to the first value's mean, mean shear
    fraction)]. Failed runs and seeds without a partner are left out of a difference."""
    param = next(iter(rows[0])) if rows else None
    kept = [r for r in rows if r.get("exit_code", "0") == "0" and r.get(key) not in (None, "")]
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
        return []
    values = sorted(by_value) if numeric else list(by_value)
    ref = by_value[values[0]]
    ref_mean = mean(float(r[key]) * scale for r in ref.values())
    out = []
    for v in values:
        runs = by_value[v]
        x = [float(r[key]) * scale for r in runs.values()]
        diffs = [(float(runs[s][key]) - float(ref[s][key])) * scale for s in runs if s in ref]
        shear = [shear_fraction(float(r["breaks_tensile"]), float(r["breaks_shear"]))
                 for r in runs.values()]
        d = mean(diffs)
        out.append((v, len(runs), mean(float(r["wall_time_s"]) for r in runs.values()), mean(x),
                    d, sem(diffs), d / ref_mean if ref_mean else math.nan, mean(shear)))
    return out
