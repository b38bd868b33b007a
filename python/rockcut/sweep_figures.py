"""The figures of a sweep (rockcut sweep and rockcut collect) (paper figures 8-12, break fractions, chips) from a sweep folder.

A sweep folder holds one run folder per value, DIR/<name>=<value> (run_dir), or with seeds one per
value and seed, DIR/<name>=<value>/seed=<S>, with the run's summary.json and run.h5, and the
collected DIR/sweep.csv. `draw(Sweep(DIR, name, rows))` draws every figure whose data the rows have
and notes the ones it skips. With several runs per value (seeds) a figure draws their mean, a bar
over their range (min to max) and each run as a faint dot.
"""
import glob
import os
import sys

import numpy as np
from matplotlib.patches import Polygon
from matplotlib.ticker import MaxNLocator, NullLocator

from . import plot
from .figures import chisel_at, discs, dpi_for, frame_extent, plot_series, plt, set_x_scale
from .run_data import tool_block
from .stats import shear_fraction as breaks_shear_fraction


def note(message):
    sys.stdout.flush()  # keep the notes in order with the progress lines
    print(f"note: {message}", file=sys.stderr)


def as_number(value):
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def run_dir(out, name, value, seed=None):
    d = os.path.join(out, f"{name}={value}")
    return d if seed is None else os.path.join(d, f"seed={seed}")


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
            note(f"{figure}: no run's summary has {', '.join(missing)}; "
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


def value_axis(s, ax, x_is_pressure):
    """Scale and ticks of the x axis; on pressure axes the water depths are marked along the top."""
    x = s.pressure_axis()[0] if x_is_pressure else s.x
    logarithmic = set_x_scale(ax, x)
    if (not s.numeric or logarithmic) and not x_is_pressure:
        # Ticks at the values themselves: names, or plain numbers instead of powers of ten.
        ax.set_xticks(s.x)
        ax.set_xticklabels(s.values)
        ax.xaxis.set_minor_locator(NullLocator())
    if x_is_pressure:
        top = ax.secondary_xaxis("top")
        top.set_xticks(x)
        top.set_xticklabels(s.values, fontsize=8)
        top.xaxis.set_minor_locator(NullLocator())
        top.set_xlabel(axis_label(s.name), fontsize=9)
    ax.grid(True, which="major", alpha=0.3)


def plot_key(ax, s, x, key, scale, fmt, colour, label=None):
    """The mean of `key` over each value's runs as points and lines; with several runs per value
    also a bar from their min to their max and each run as a faint dot."""
    mean = s.column(key)
    plot_series(ax, x, mean * scale, fmt, color=colour, label=label)
    band = s.spread(key)
    if band is None:
        return
    lo, hi = band
    ok = np.isfinite(x) & np.isfinite(mean)
    ax.errorbar(x[ok], mean[ok] * scale,
                yerr=[(mean[ok] - lo[ok]) * scale, (hi[ok] - mean[ok]) * scale],
                fmt="none", ecolor=colour, elinewidth=1, capsize=3)
    px, py = s.points(key, x)
    plot_series(ax, px, py * scale, ".", color=colour, alpha=0.3)


def save(fig, s, filename):
    fig.tight_layout()
    fig.savefig(s.path(filename))
    plt.close(fig)
    print(f"wrote {s.path(filename)}", flush=True)


def remove_stale(s, pattern):
    """A figure that is not drawn this time must not be left from an earlier sweep in DIR."""
    for f in glob.glob(s.path(pattern)):
        os.remove(f)


def runs_note(s):
    """Appended to the titles of figures drawn from several runs per value."""
    if not s.seeded:
        return ""
    n = max(len(g) for g in s.groups)
    return f"\nmean of {n} specimen seeds; bars: their range, dots: each seed"


def line_figure(s, filename, title, series, ylabel, scale, against_pressure, models=()):
    """One panel of lines: series = [(key, legend label, colour)], values multiplied by `scale`.
    `models` = [(key, legend label, colour)]: analytical values per value, drawn dashed with crosses
    beside the runs (the same for every seed: summary.json's, never recomputed here)."""
    remove_stale(s, filename)
    cols = s.columns([k for k, _, _ in series], filename)
    if not cols:
        return
    if against_pressure:
        x, xlabel, is_pressure = s.pressure_axis()
    else:
        x, xlabel, is_pressure = s.x, axis_label(s.name), False
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=100)
    for key, label, colour in series:
        if key in cols:
            plot_key(ax, s, x, key, scale, "o-", colour, label)
    for key, label, colour in models:
        column = s.column(key)
        if column is not None:
            plot_series(ax, x, column * scale, "x--", color=colour, label=label)
    ax.axhline(0, color="k", lw=0.5)
    value_axis(s, ax, is_pressure)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title + runs_note(s), fontsize=10)
    ax.legend(fontsize=8)
    save(fig, s, filename)


def fig_forces(s):
    line_figure(s, "fig08_forces.png", "Mean tool forces over the steady part of the cut (fig. 8)",
                [("force_horizontal_mean_n_per_m", "horizontal (resisting the cut)", "tab:blue"),
                 ("force_vertical_mean_n_per_m", "vertical (up > 0)", "tab:orange")],
                "mean force on the tool [kN per m of width]", 1e-3, against_pressure=True,
                models=analytical_series())


def analytical_series():
    """The analytical models' horizontal forces (summary.json's analytical_* keys of a scene with
    a rock block, docs/cutting_models.md) as line_figure models."""
    return [(f"analytical_{stem}_force_horizontal_n_per_m", label, colour)
            for stem, label, colour in plot.ANALYTICAL_MODELS]


def fig_pressure_p1(s):
    line_figure(s, "fig09_pressure_p1.png", "Mean pore pressure at P1 (fig. 9)",
                [("pressure_p1_mean_pa", "P1", "tab:blue")],
                "mean excess pore pressure p - p_hydro [MPa]", 1e-6, against_pressure=True)


def fig_pressure_p2_p3(s):
    line_figure(s, "fig10_pressure_p2_p3.png", "Mean pore pressures at P2 and P3 (fig. 10)",
                [("pressure_p2_mean_pa", "P2", "tab:green"),
                 ("pressure_p3_mean_pa", "P3", "tab:red")],
                "mean excess pore pressure p - p_hydro [MPa]", 1e-6, against_pressure=True)


def shear_fraction(row):
    """Shear breaks over all breaks of one run (NaN for a run without breaks or a summary)."""
    return breaks_shear_fraction(as_number(row.get("breaks_tensile")), as_number(row.get("breaks_shear")))


def fig_breaks_fraction(s):
    filename = "breaks_fraction.png"
    remove_stale(s, filename)
    cols = s.columns(["breaks_tensile", "breaks_shear"], filename)
    if len(cols) < 2:
        return
    total = cols["breaks_tensile"] + cols["breaks_shear"]  # mean over the runs of a value
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=100)
    plot_key(ax, s, s.x, lambda r: 1.0 - shear_fraction(r), 1.0, "o-", "tab:blue", "tensile")
    plot_key(ax, s, s.x, shear_fraction, 1.0, "s-", "tab:red", "shear")
    for xi, n in zip(s.x, total):
        if np.isfinite(n):
            ax.annotate(f"{int(n)}", (xi, 1.0), textcoords="offset points", xytext=(0, 3),
                        ha="center", fontsize=7, color="0.4")
    value_axis(s, ax, False)
    ax.set_ylim(0, 1.08)
    ax.set_xlabel(axis_label(s.name))
    ax.set_ylabel("fraction of the broken bonds [-]")
    ax.set_title("Bond breaks by mode (number of breaks above the points)" + runs_note(s),
                 fontsize=10)
    # Outside the axes: inside it would hide the counts along the top.
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
    save(fig, s, filename)


def fig_chips(s):
    filename = "chips.png"
    remove_stale(s, filename)
    cols = s.columns(["chips", "chip_area_mean_m2"], filename)
    if not cols:
        return
    panels = [("chips", "chips [count]", 1.0, "tab:blue"),
              ("chip_area_mean_m2", "mean chip area [mm²]", 1e6, "tab:orange")]
    panels = [p for p in panels if p[0] in cols]
    fig, axes = plt.subplots(len(panels), 1, figsize=(7, 2.6 * len(panels) + 1), dpi=100,
                             sharex=True, squeeze=False)
    for ax, (key, ylabel, scale, colour) in zip(axes[:, 0], panels):
        plot_key(ax, s, s.x, key, scale, "o-", colour)
        ax.set_ylabel(ylabel)
        ax.set_ylim(bottom=0)
        if key == "chips":
            ax.yaxis.set_major_locator(MaxNLocator(integer=True))
        value_axis(s, ax, False)
    axes[-1, 0].set_xlabel(axis_label(s.name))
    axes[0, 0].set_title("Chips cut off at the end of the run" + runs_note(s), fontsize=10)
    save(fig, s, filename)


def fig_damage(s, value, filename, figure_no):
    """Discs of the run's last complete frame coloured by damage, with the chisel, in mm (the
    value's first seed with a run.h5)."""
    run = s.run_with(value, "run.h5")
    if run is None:
        note(f"{filename}: no run.h5 for {s.name}={value}; not drawn")
        return
    h5 = os.path.join(run, "run.h5")
    seed = os.path.basename(run) if s.seeded else ""
    d = plot.load(h5)
    if d.last is None:
        note(f"{filename}: {h5} has no frame with damage; not drawn")
        return
    pos, radius, damage, t = d.last
    # The chisel where dem_module puts it at the frame's time (as rockcut plot draws it).
    poly = chisel_at(tool_block(d.scene), d.first, d.ts, t)
    pos, radius = pos * 1e3, radius * 1e3  # mm
    poly = None if poly is None else poly * 1e3
    fig, ax = plt.subplots(figsize=(8, 5), dpi=dpi_for(radius))
    coll = discs(ax, pos, radius, array=np.clip(damage, 0, 1), cmap="jet", linewidths=0)
    coll.set_clim(0, 1)
    if poly is not None:
        ax.add_patch(Polygon(poly, closed=True, fc="0.5", ec="k", lw=0.8, zorder=3))
    frame_extent(ax, pos, radius, poly)  # also sets the equal aspect
    fig.colorbar(coll, ax=ax, shrink=0.8, label="damage D = 1 - bonds / initial bonds [-]")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(f"Damage at {s.name} = {value}{value_unit(s.name)}, t = {t:.4g} s "
                 f"(fig. {figure_no})" + (f", {seed}" if seed else ""), fontsize=10)
    save(fig, s, filename)


def draw(s):
    fig_forces(s)
    fig_pressure_p1(s)
    fig_pressure_p2_p3(s)
    fig_breaks_fraction(s)
    fig_chips(s)
    # Figures 11 and 12: the smallest and the largest value (0 m and 2000 m in the paper), or the
    # nearest to them that left a run.h5 when a run failed.
    remove_stale(s, "fig11_damage_*.png")
    remove_stale(s, "fig12_damage_*.png")
    have = [v for v in s.values if s.run_with(v, "run.h5") is not None]
    if not have:
        note("fig11/fig12: no run left a run.h5; not drawn")
        return
    for value, wanted in ((have[0], s.values[0]), (have[-1], s.values[-1])):
        if value != wanted:
            note(f"{s.name}={wanted} has no run.h5: damage drawn for {s.name}={value} instead")
    ends = [(have[0], 11)] + ([(have[-1], 12)] if len(have) > 1 else [])
    for value, no in ends:
        try:
            fig_damage(s, value, f"fig{no}_damage_{value}.png", no)
        except (OSError, KeyError, ValueError) as e:  # e.g. a run.h5 cut short by a crash
            note(f"fig{no}_damage_{value}.png: {type(e).__name__}: {e}; not drawn")
