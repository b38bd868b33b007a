"""The figures of rockcut windows: --plot (the window means of several runs against their
hydrostatic pressure) and --plot-travel (each run's window means against tool travel).
"""
import math
import os
import sys

from .figures import panel_grid
from .window_means import NODES, fail, shear_fraction


def is_full(w, every_m):
    return w["to_m"] - w["from_m"] >= 0.99 * every_m


def depth_points(runs, every_m, value):
    """{window start [m]: [(p_hydro [Pa], values of the runs at that pressure)]}, over the runs
    with a summary.json and the windows of full width; runs at one depth (other seeds) share a
    point. Values that are NaN (a node that held no particle) are left out."""
    groups = {}
    for run in runs:
        if not math.isfinite(run.p_hydro):
            continue
        for w in run.rows:
            if is_full(w, every_m):
                v = value(w)
                if math.isfinite(v):
                    start = round(w["from_m"], 9)
                    groups.setdefault(start, {}).setdefault(run.p_hydro, []).append(v)
    return {start: sorted(by_p.items()) for start, by_p in sorted(groups.items())}


def plot(runs, every_m, png):
    """One line per window start through the mean over each depth's runs; with several runs at a
    depth a bar from their lowest to their highest value and each run as a faint dot."""
    from .figures import plt
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    for run in runs:
        if not math.isfinite(run.p_hydro):
            print(f"note: {run.label}: no summary.json (still going?), left out of the plot",
                  file=sys.stderr)
    usable = sorted((r for r in runs if math.isfinite(r.p_hydro)), key=lambda r: r.p_hydro)
    if not usable:
        fail("--plot: no run has a summary.json with its hydrostatic pressure")
    coupled = any("p1_pa" in row for r in usable for row in r.rows)
    panels = window_panels(coupled)
    fig, axes = panel_grid(len(panels))
    for ax, (title, value) in zip(axes.flat, panels):
        for k, (start, points) in enumerate(depth_points(usable, every_m, value).items()):
            colour = f"C{k % 10}"
            xs = [p * 1e-6 for p, _ in points]
            means = [sum(v) / len(v) for _, v in points]
            ax.plot(xs, means, "o-", color=colour,
                    label=f"{start * 1e3:.0f}-{(start + every_m) * 1e3:.0f} mm")
            for x, m, (_, v) in zip(xs, means, points):
                if len(v) > 1:
                    ax.errorbar([x], [m], yerr=[[m - min(v)], [max(v) - m]], fmt="none",
                                ecolor=colour, elinewidth=1, capsize=3)
                    ax.plot([x] * len(v), v, ".", color=colour, alpha=0.3)
        ax.set_xscale("log")
        ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("hydrostatic pressure [MPa]")
        ax.set_title(title, fontsize=10)
        if title.startswith("P"):
            ax.axhline(0.0, color="0.6", lw=0.8)
    axes.flat[0].legend(title="tool travel", fontsize=8)
    seeds = {}
    for r in usable:
        seeds.setdefault(r.depth, []).append(r.seed)
    names = ", ".join(f"{d:g} m" + (f" (seeds {', '.join(map(str, s))})" if len(s) > 1 else "")
                      for d, s in seeds.items())
    several = any(len(s) > 1 for s in seeds.values())
    fig.suptitle(f"window means of {len(usable)} runs ({names})"
                 + ("\nbars: the range over a depth's runs, dots: each run" if several else ""),
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    plt.close(fig)


def window_panels(coupled):
    """(title, value of a window) of the panels that --plot and --plot-travel draw."""
    panels = [("Fh [kN/m]", lambda w: w["fh_n_per_m"] * 1e-3),
              ("Fv, up > 0 [kN/m]", lambda w: w["fv_n_per_m"] * 1e-3),
              ("shear breaks / all breaks", shear_fraction),
              ("mean chip area [mm$^2$]", lambda w: w.get("chip_area_mean_m2", math.nan) * 1e6)]
    if coupled:
        panels += [(f"{n.upper()}: p - p_hydro [MPa]",
                    lambda w, n=n: w.get(f"{n}_pa", math.nan) * 1e-6) for n in NODES]
        panels += [("cavitated particles", lambda w: w.get("fluid_cavitated_particles", math.nan))]
    return panels


def travel_lines(runs, panels):
    """{panel title: [(run label, travel [mm], values)]}: each window drawn as a step over its
    travel, so the x values are the windows' edges and every value appears twice."""
    lines = {}
    for run in runs:
        name = f"{os.path.basename(os.path.dirname(os.path.abspath(run.label)))}: {run.depth:g} m"
        if run.seed != 1:
            name += f", seed {run.seed}"
        for title, value in panels:
            xs, ys = [], []
            for w in run.rows:
                v = value(w)
                xs += [w["from_m"] * 1e3, w["to_m"] * 1e3]
                ys += [v, v]
            lines.setdefault(title, []).append((name, xs, ys))
    return lines


def plot_travel(runs, every_m, png):
    """One panel per quantity, one line per run against tool travel."""
    from .figures import plt
    coupled = any("p1_pa" in row for r in runs for row in r.rows)
    panels = window_panels(coupled)
    lines = travel_lines(runs, panels)
    fig, axes = panel_grid(len(panels), sharex=True)
    for ax, (title, _) in zip(axes.flat, panels):
        for k, (name, xs, ys) in enumerate(lines[title]):
            ax.plot(xs, ys, "-", color=f"C{k % 10}", lw=1.2, label=name)
        ax.set_xlabel("tool travel [mm]")
        ax.set_title(title, fontsize=10)
        if title.startswith("P") or title.startswith("Fv"):
            ax.axhline(0.0, color="0.6", lw=0.8)
    axes.flat[0].legend(fontsize=8)
    fig.suptitle(f"window means of {len(runs)} runs against tool travel "
                 f"({every_m * 1e3:g} mm windows)", fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    plt.close(fig)
    return lines
