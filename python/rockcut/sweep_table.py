"""The collected rows of a sweep (campaign.collect) as a table grouped by the varied value: the
mean over a value's runs (seeds), their range and the runs themselves, for the figures
(sweep_figures), sweep_mean.csv (Sweep.mean_rows) and rockcut compare.
"""
import os
import sys

import numpy as np

from .campaign import as_number, run_dir
from .stats import shear_fraction as breaks_shear_fraction


def note(message):
    sys.stdout.flush()  # keep the notes in order with the progress lines
    print(f"note: {message}", file=sys.stderr)


UNITS = (("_m_s", "m/s"), ("_m2", "m²"), ("_pa", "Pa"), ("_deg", "°"), ("_s", "s"), ("_m", "m"))


def axis_label(name):
    """'tool.velocity_m_s' -> 'tool.velocity [m/s]' (the unit from the field's suffix)."""
    for suffix, unit in UNITS:
        if name.endswith(suffix):
            return f"{name[:-len(suffix)]} [{unit}]"
    return name


def value_unit(name):
    for suffix, unit in UNITS:
        if name.endswith(suffix):
            return " " + unit
    return ""


class Sweep:
    """The collected rows (one per run), grouped by the varied value and sorted by it, with helpers
    to pull out columns: the mean over a value's runs, their range and the runs themselves."""

    def __init__(self, out, name, rows):
        self.out, self.name = out, name
        groups = {}
        for r in rows:
            groups.setdefault(r[name], []).append(r)
        self.numeric = all(as_number(v) is not None for v in groups)
        self.values = sorted(groups, key=float) if self.numeric else list(groups)
        self.groups = [groups[v] for v in self.values]  # the runs of each value
        self.seeded = any(len(g) > 1 for g in self.groups)
        # Non-numeric values (e.g. fluid.model=explicit,implicit) are drawn at 0, 1, 2, ...
        self.x = (np.array([float(v) for v in self.values]) if self.numeric
                  else np.arange(len(self.values), dtype=float))

    def per_run(self, key):
        """[array of the runs' values] per value; `key` is a summary key or a function of a row.
        Missing values are NaN."""
        get = key if callable(key) else (lambda r: as_number(r.get(key)))
        return [np.array([get(r) for r in g], dtype=float) for g in self.groups]

    def stats(self, key):
        """(mean, min, max) arrays over each value's runs that have the key (NaN where none has
        it), or None if no run has it."""
        runs = [v[np.isfinite(v)] for v in self.per_run(key)]
        if not any(len(v) for v in runs):
            return None
        return tuple(np.array([f(v) if len(v) else np.nan for v in runs])
                     for f in (np.mean, np.min, np.max))

    def column(self, key):
        """The mean over each value's runs that have the key, or None if no run has it."""
        st = self.stats(key)
        return None if st is None else st[0]

    def spread(self, key):
        """(min, max) arrays over each value's runs, or None with one run per value."""
        st = self.stats(key) if self.seeded else None
        return None if st is None else st[1:]

    def points(self, key, x):
        """(x, y) of every run, x being the value's position on the figure's axis."""
        runs = self.per_run(key)
        xs = np.concatenate([np.full(len(v), xi) for xi, v in zip(x, runs)])
        return xs, np.concatenate(runs)

    def mean_rows(self):
        """One row per value: the mean, min and max over its runs of every numeric key, and the
        number of runs that exited with 0 (for sweep_mean.csv)."""
        skip = {self.name, "seed", "exit_code"}
        keys = sorted({k for g in self.groups for r in g for k, v in r.items()
                       if k not in skip and isinstance(v, (int, float)) and not isinstance(v, bool)})
        stats = {k: self.stats(k) for k in keys}
        rows = []
        for i, (value, g) in enumerate(zip(self.values, self.groups)):
            row = {self.name: value, "runs": len(g),
                   "runs_ok": sum(1 for r in g if r.get("exit_code") == 0)}
            for k, (mean, lo, hi) in stats.items():
                if np.isfinite(mean[i]):
                    row[k], row[k + "_min"], row[k + "_max"] = (float(mean[i]), float(lo[i]),
                                                               float(hi[i]))
            rows.append(row)
        return rows

    def run_with(self, value, filename):
        """The folder of the value's first run (by seed) that has `filename`, or None."""
        for r in sorted(self.groups[self.values.index(value)], key=lambda r: r.get("seed", 0)):
            d = run_dir(self.out, self.name, value, r.get("seed"))
            if os.path.isfile(os.path.join(d, filename)):
                return d
        return None

    def columns(self, keys, figure):
        """{key: column} of the keys some run has; notes the others."""
        found = {k: self.column(k) for k in keys}
        missing = [k for k, c in found.items() if c is None]
        if missing:
            note(f"{figure}: no run's summary has a value of {', '.join(missing)}; "
                 + ("left out of it" if len(missing) < len(keys) else "not drawn"))
        return {k: c for k, c in found.items() if c is not None}

    def pressure_axis(self):
        """x for figures 8-10: the hydrostatic pressure in MPa when water depth is varied (as in the
        paper), else the varied value. Returns (x, label, is_pressure)."""
        p = self.column("hydrostatic_pressure_pa")
        if self.name == "water_depth_m" and p is not None and not np.isnan(p).any():
            return p / 1e6, "hydrostatic pressure [MPa]", True
        return self.x, axis_label(self.name), False

    def path(self, filename):
        return os.path.join(self.out, filename)


def shear_fraction(row):
    """Shear breaks over all breaks of one run (NaN for a run without breaks or a summary)."""
    return breaks_shear_fraction(as_number(row.get("breaks_tensile")), as_number(row.get("breaks_shear")))
