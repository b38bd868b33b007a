"""Several water-depth sweeps side by side: where shear breaks take over, and the forces.

  rockcut compare DIR[=LABEL] DIR[=LABEL] ... [--plot PNG] [--csv CSV]

Each DIR is a folder of rockcut sweep (DIR/water_depth_m=<v>[/seed=<S>]/summary.json), e.g. the same
scene swept with different bond strengths (`rockcut sweep ... --out DIR --set path=value`). LABEL
names it in the table and the figure (default: the folder's name). For each sweep it prints, per
water depth, the mean over the seeds (and their range) of
  the horizontal tool force [kN/m], the shear fraction of the broken bonds, the mean chip area,
and two depths of the change of failure mode (paper section 5: tensile breaks dominate in shallow
water, shear breaks in deep water, the transition at about 300 m):
  majority   where the mean shear fraction first rises through 0.5: shear breaks become the
             majority of the broken bonds;
  half-way   where it first rises through the middle of its change over the sweep, half-way from
             its value at the shallowest depth to that at the deepest: where the change from the
             shallow to the deep regime is half done, whatever the fraction's level.
Between the two depths that bracket a crossing the fraction is interpolated linearly in log
p_hydro, the axis of the figures. A sweep with no crossing (the fraction above the level at its
shallowest depth, or below it at every depth) is said so.

  --plot PNG   two panels against p_hydro: the shear fraction (mean, range bars, each seed as a
               dot) and the horizontal force, one colour per sweep
  --csv CSV    one row per sweep and depth: label, water_depth_m, hydrostatic_pressure_pa, runs,
               the means and ranges above, and the sweep's two transition depths and pressures

Exit status 0 when drawn, 2 on bad input (nothing written).
"""
import argparse
import csv
import os
import sys

import numpy as np

from .campaign import collect, seeds_in, sorted_values, values_in
from .figures import plt, set_x_scale
from .sweep_figures import plot_key
from .sweep_table import Sweep, shear_fraction


DEPTH = "water_depth_m"
MAJORITY = 0.5  # shear breaks are the majority above this shear fraction


def crossing(depth, pressure, fraction, level):
    """(depth, p_hydro, how) where the mean shear fraction first rises through `level`; depth and
    p_hydro are None when there is no crossing, and `how` says why. Between the two bracketing
    depths the fraction is taken as linear in log p_hydro, the axis of the paper's figures and of
    --plot (so the crossing lies on the drawn line); the depth follows from p_hydro, which is
    linear in depth."""
    ok = np.isfinite(fraction)
    d, p, f = depth[ok], pressure[ok], fraction[ok]
    if len(f) == 0:
        return None, None, "no run with breaks"
    if f[0] > level:
        return None, None, f"above {level:.2f} already at {d[0]:g} m ({f[0]:.2f})"
    for i in range(1, len(f)):
        if f[i - 1] <= level < f[i]:
            w = (level - f[i - 1]) / (f[i] - f[i - 1])
            p_x = p[i - 1] * (p[i] / p[i - 1]) ** w
            d_x = d[i - 1] + (p_x - p[i - 1]) / (p[i] - p[i - 1]) * (d[i] - d[i - 1])
            return d_x, p_x, f"between {d[i - 1]:g} and {d[i]:g} m"
    return None, None, f"below {level:.2f} at every depth (at most {f.max():.2f})"


def half_way_level(fraction):
    """The middle of the shear fraction's change from the shallowest to the deepest depth, or None
    when it does not rise."""
    f = fraction[np.isfinite(fraction)]
    if len(f) < 2 or f[-1] <= f[0]:
        return None
    return 0.5 * (f[0] + f[-1])


class Compared:
    """One sweep: its label, its Sweep and the columns the table and figure use."""

    def __init__(self, label, out):
        self.label, self.out = label, out
        name, values = values_in(out)
        if name != DEPTH:
            raise ValueError(f"{out} varies {name}, not {DEPTH}")
        rows = collect(out, name, sorted_values(values), seeds_in(out, name, values))
        done = [r for r in rows if "force_horizontal_mean_n_per_m" in r]  # runs with a summary
        if not done:
            raise ValueError(f"{out} holds no run with a summary.json")
        self.left_out = [f"{r[name]} m" + (f" seed {r['seed']}" if "seed" in r else "")
                         for r in rows if r not in done]
        rows = done
        self.sweep = s = Sweep(out, name, rows)
        self.depth = s.x
        self.runs = [len(g) for g in s.groups]
        self.pressure = s.column("hydrostatic_pressure_pa")
        self.force = s.stats("force_horizontal_mean_n_per_m")
        self.fraction = s.stats(shear_fraction)
        self.chip_area = s.stats("chip_area_mean_m2")
        f = self.fraction[0]
        self.majority = crossing(self.depth, self.pressure, f, MAJORITY)
        self.half_level = half_way_level(f)
        self.half_way = (crossing(self.depth, self.pressure, f, self.half_level)
                         if self.half_level is not None
                         else (None, None, "the shear fraction does not rise with depth"))


def parse_sweep(text):
    """'DIR=LABEL' or 'DIR' -> (DIR, LABEL). A folder name may hold '=' itself (out/ts=2.6e4): the
    whole text is a folder first, else the label follows the last '='."""
    if os.path.isdir(text) or "=" not in text:
        out, label = text, ""
    else:
        out, _, label = text.rpartition("=")
    return out, label or os.path.basename(os.path.normpath(out))


def fmt_range(stats, i, scale, digits):
    mean, lo, hi = (a[i] * scale for a in stats)
    if not np.isfinite(mean):
        return "-"
    if lo == hi:
        return f"{mean:.{digits}f}"
    return f"{mean:.{digits}f} ({lo:.{digits}f}-{hi:.{digits}f})"


def print_tables(sweeps):
    for c in sweeps:
        print(f"{c.label}  ({c.out})")
        if c.left_out:
            print(f"  left out, no summary.json (failed or not run): {', '.join(c.left_out)}")
        print(f"  {'depth [m]':>9} {'p_hydro [MPa]':>13} {'runs':>4}  {'Fh [kN/m]':<20} "
              f"{'shear fraction':<20} chip area [mm²]")
        for i in range(len(c.depth)):
            area = fmt_range(c.chip_area, i, 1e6, 1) if c.chip_area else "-"
            print(f"  {c.depth[i]:>9g} {c.pressure[i] / 1e6:>13.2f} {c.runs[i]:>4}  "
                  f"{fmt_range(c.force, i, 1e-3, 0):<20} {fmt_range(c.fraction, i, 1, 2):<20} "
                  f"{area}")
        for what, (d, p, how), level in (("shear breaks the majority", c.majority, MAJORITY),
                                         ("half-way", c.half_way, c.half_level)):
            name = what if level is None else f"{what} (shear fraction {level:.2f})"
            if d is None:
                print(f"  {name}: no crossing ({how})")
            else:
                print(f"  {name}: from {d:.0f} m, p_hydro {p / 1e6:.2f} MPa ({how}, "
                      f"linear in log p_hydro)")
        print()


def write_csv(path, sweeps):
    columns = ["label", DEPTH, "hydrostatic_pressure_pa", "runs",
               "force_horizontal_mean_n_per_m", "force_horizontal_min_n_per_m",
               "force_horizontal_max_n_per_m", "shear_fraction", "shear_fraction_min",
               "shear_fraction_max", "chip_area_mean_m2", "majority_depth_m",
               "majority_pressure_pa", "half_way_fraction", "half_way_depth_m",
               "half_way_pressure_pa"]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for c in sweeps:
            d, p, _ = c.majority
            hd, hp, _ = c.half_way
            blank = lambda v: "" if v is None else v  # noqa: E731
            for i in range(len(c.depth)):
                area = c.chip_area[0][i] if c.chip_area else np.nan
                w.writerow([c.label, f"{c.depth[i]:g}", c.pressure[i], c.runs[i],
                            c.force[0][i], c.force[1][i], c.force[2][i],
                            c.fraction[0][i], c.fraction[1][i], c.fraction[2][i], area,
                            blank(d), blank(p), blank(c.half_level), blank(hd), blank(hp)])
    print(f"wrote {path}")


def plot(path, sweeps):
    fig, (ax_f, ax_h) = plt.subplots(2, 1, figsize=(7.5, 8), dpi=100, sharex=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    all_p = np.concatenate([c.pressure for c in sweeps]) / 1e6
    for k, c in enumerate(sweeps):
        colour = colours[k % len(colours)]
        x = c.pressure / 1e6
        plot_key(ax_f, c.sweep, x, shear_fraction, 1.0, "o-", colour, c.label)
        plot_key(ax_h, c.sweep, x, "force_horizontal_mean_n_per_m", 1e-3, "o-", colour, c.label)
        for (_, p, _), level, marker in ((c.majority, MAJORITY, "x"),
                                         (c.half_way, c.half_level, "D")):
            if p is not None:
                ax_f.plot([p / 1e6], [level], marker, color=colour, ms=9, mew=2, mfc="none")
    ax_f.axhline(MAJORITY, color="k", lw=0.6, ls="--")
    ax_f.set_ylim(0, 1)
    ax_f.set_ylabel("shear fraction of the broken bonds [-]")
    ax_f.set_title("Shear fraction against p_hydro; x: shear breaks become the majority,\n"
                   "diamond: half-way from the shallowest to the deepest value\n"
                   "mean over the seeds; bars: their range, dots: each seed", fontsize=9)
    ax_f.legend(fontsize=8)
    ax_h.set_ylabel("mean horizontal tool force [kN/m]")
    ax_h.set_xlabel("hydrostatic pressure [MPa]")
    ax_h.set_ylim(bottom=0)
    for ax in (ax_f, ax_h):
        set_x_scale(ax, all_p)
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    print(f"wrote {path}")


def main(argv):
    p = argparse.ArgumentParser(prog="rockcut compare", description=__doc__.split("\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="\n".join(__doc__.split("\n")[1:]))
    p.add_argument("sweeps", nargs="+", metavar="DIR[=LABEL]")
    p.add_argument("--plot", metavar="PNG")
    p.add_argument("--csv", metavar="CSV")
    args = p.parse_args(argv)
    sweeps = []
    for text in args.sweeps:
        out, label = parse_sweep(text)
        if not os.path.isdir(out):
            print(f"rockcut compare: {out}: no such folder", file=sys.stderr)
            return 2
        try:
            sweeps.append(Compared(label, out))
        except (ValueError, SystemExit) as e:
            print(f"rockcut compare: {e}", file=sys.stderr)
            return 2
    labels = [c.label for c in sweeps]
    if len(set(labels)) != len(labels):
        print(f"rockcut compare: two sweeps share a label ({', '.join(labels)}): give DIR=LABEL",
              file=sys.stderr)
        return 2
    print_tables(sweeps)
    if args.csv:
        write_csv(args.csv, sweeps)
    if args.plot:
        plot(args.plot, sweeps)
    return 0

