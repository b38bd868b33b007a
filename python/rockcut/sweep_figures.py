"""The figures of a sweep (rockcut sweep and rockcut collect) (paper figures 8-12, break fractions, chips) from a sweep folder.

A sweep folder (campaign.py) holds one run folder per value, DIR/<name>=<value>, or with seeds one
per value and seed, DIR/<name>=<value>/seed=<S>, with the run's summary.json and run.h5, and the
collected DIR/sweep.csv. `draw(Sweep(DIR, name, rows))` (sweep_table.Sweep) draws every figure
whose data the rows have and notes the ones it skips. With several runs per value (seeds) a figure
draws their mean, a bar over their range (min to max) and each run as a faint dot.
"""
import glob
import os

import numpy as np
from matplotlib.patches import Polygon
from matplotlib.ticker import MaxNLocator, NullLocator

from . import plot
from .figures import chisel_at, discs, dpi_for, frame_extent, plot_series, plt, set_x_scale
from .run_data import tool_block
# The table the figures draw from; Sweep and shear_fraction are also reached from here.
from .sweep_table import Sweep, axis_label, note, shear_fraction, value_unit  # noqa: F401


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
    # The peak beside the means: a dynamic cut (dashpots) is read by its peak, which the models'
    # chip forces (Evans, Nishimatsu) are peaks of too.
    line_figure(s, "fig08_forces.png", "Tool forces over the steady part of the cut (fig. 8)",
                [("force_horizontal_mean_n_per_m", "horizontal mean (resisting the cut)", "tab:blue"),
                 ("force_horizontal_peak_n_per_m", "horizontal peak", "tab:purple"),
                 ("force_vertical_mean_n_per_m", "vertical mean (up > 0)", "tab:orange")],
                "force on the tool [kN per m of width]", 1e-3, against_pressure=True,
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
