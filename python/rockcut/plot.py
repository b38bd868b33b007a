"""rockcut plot OUT [OUT ...] [--png FILE]: the figures of runs, chosen by what each run holds.

A cutting run (a tool's time series) gets
  OUT/force.png   the tool forces against tool travel: the force resisting the cut (-F_x) and the
                  vertical force on the tool (F_y, positive up), the steady part shaded and its
                  means drawn as lines (coupler/observers/cutting_summary.hpp defines the steady part);
                  a run whose scene has a `rock` block also gets each analytical model's horizontal
                  force as a dotted line, read from summary.json's analytical_* keys
                  (docs/cutting_models.md), never computed here;
  OUT/damage.png  the discs of the last complete frame as circles of their radius, coloured by
                  damage D = 1 - bonds / initial bonds (paper figures 11-12), with the chisel;
  OUT/breaks.png  where bonds broke, coloured by mode (tensile, shear).
  Works on a run that is still going or stopped early: it reads what run.h5 holds so far.
A calibration run (UCS or Brazilian: /timeseries/axial_strain) gets OUT/stress_strain.png, the
load against the axial strain, and a fracture test OUT/force_elongation.png, the pull against the
elongation; with --png FILE every calibration run given is drawn into one figure FILE instead (for
comparing micro-parameter sets or platen speeds).

Exit status: 0 if every OUT was plotted, 1 otherwise, 2 without arguments.
"""
import argparse
import os
import sys
import time

import h5py
import numpy as np

from .figures import chisel_at, discs, dpi_for, frame_extent, plt, running_mean
from .plot_calibration import plot_calibration
from .run_data import (h5_path, read_frame, read_summary, read_timeseries, stored_scene,
                       tool_block)
from matplotlib.patches import Polygon



class RunData:
    """What the cutting figures need from run.h5, read into memory at once."""

    def __init__(self):
        self.scene = ""     # the effective scene text (root attribute `scene`)
        self.ts = {}        # time-series name -> values, all cut to the same length
        self.first = None   # (position, radius) of the first frame
        self.last = None    # (position, radius, damage, time_s) of the last readable frame
        self.breaks = None  # (x, y, mode), or None without /breaks


def load(h5):
    """Reads run.h5. A run still writing it may leave the newest objects unreadable, so each part
    is read on its own, and frames from the newest back until one reads whole."""
    d = RunData()
    with h5py.File(h5, "r") as f:
        d.scene = stored_scene(f)
        d.ts = read_timeseries(f)
        names = sorted(f["frames"].keys()) if "frames" in f else []
        for name in names:
            try:
                d.first = read_frame(f["frames"][name], ("position", "radius"))
                break
            except (KeyError, OSError, ValueError):
                continue
        for name in reversed(names):
            try:
                g = f["frames"][name]
                pos, radius, damage = read_frame(g, ("position", "radius", "damage"))
                d.last = (pos, radius, damage, float(g.attrs.get("time_s", np.nan)))
                break
            except (KeyError, OSError, ValueError):
                continue
        try:
            b = f["breaks"]
            n = min(len(b["x_m"]), len(b["y_m"]), len(b["mode"]))
            d.breaks = (b["x_m"][:n], b["y_m"][:n], b["mode"][:n])
        except (KeyError, OSError, ValueError):
            d.breaks = None  # no /breaks: no bond has broken (yet)
    return d


def run_name(out):
    return os.path.basename(os.path.normpath(out))


# The analytical models of summary.json (coupler/observers/analytical_cutting.hpp): key stem, label,
# colour. Evans and Nishimatsu give peak forces, Merchant/Miedema and the hyperbaric bound forces
# of continuous shearing.
ANALYTICAL_MODELS = (
    ("evans", "Evans, tensile chip (peak)", "tab:green"),
    ("nishimatsu", "Nishimatsu, shear plane (peak)", "tab:purple"),
    ("merchant", "Merchant/Miedema flow type", "tab:red"),
    ("hyperbaric", "hyperbaric bound (cavitation)", "tab:brown"),
)


def analytical_lines(summary):
    """[(key stem, label, colour, horizontal force [kN/m])] of the models summary.json holds."""
    lines = []
    for stem, label, colour in ANALYTICAL_MODELS:
        value = summary.get(f"analytical_{stem}_force_horizontal_n_per_m")
        if isinstance(value, (int, float)) and np.isfinite(value):
            lines.append((stem, label, colour, value / 1e3))
    return lines


def plot_force(out, ts, tool, summary):
    if not {"tool_travel_m", "tool_force_x_n_per_m", "tool_force_y_n_per_m"} <= ts.keys():
        print(f"{out}: no tool force time series; force.png not written", file=sys.stderr)
        return
    travel_mm = ts["tool_travel_m"] * 1e3
    fh = -ts["tool_force_x_n_per_m"] / 1e3  # kN/m, the force resisting the cut
    fv = ts["tool_force_y_n_per_m"] / 1e3   # kN/m, positive up
    # The steady part as coupler/observers/cutting_summary.cpp takes it: travel >= steady_after_m.
    steady = ts["tool_travel_m"] >= tool["steady_after_m"]
    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=100)
    # Raw samples faintly, a 1 mm running mean on top.
    step_mm = float(np.median(np.diff(travel_mm))) if len(travel_mm) > 1 else 0.0
    n = max(1, int(round(1.0 / step_mm))) if step_mm > 0 else 1
    ax.plot(travel_mm, fh, color="tab:blue", lw=0.4, alpha=0.3)
    ax.plot(travel_mm, fv, color="tab:orange", lw=0.4, alpha=0.3)
    ax.plot(travel_mm, running_mean(fh, n), color="tab:blue", lw=1.2,
            label="horizontal $-F_x$ (1 mm running mean)")
    ax.plot(travel_mm, running_mean(fv, n), color="tab:orange", lw=1.2,
            label="vertical $F_y$, up > 0 (1 mm running mean)")
    if steady.any():
        x0, x1 = travel_mm[steady][0], travel_mm[steady][-1]
        ax.axvspan(x0, x1, color="0.85", zorder=0, label="steady part")
        mh, mv = fh[steady].mean(), fv[steady].mean()
        w = tool["width_m"]
        ax.hlines(mh, x0, x1, color="navy", lw=2, ls="--",
                  label=f"mean {mh:.3g} kN/m ({mh * w * 1e3:.3g} N on {w * 1e3:g} mm)")
        ax.hlines(mv, x0, x1, color="darkred", lw=2, ls="--",
                  label=f"mean {mv:.3g} kN/m ({mv * w * 1e3:.3g} N on {w * 1e3:g} mm)")
    # The hyperbaric bound of a dry run is the Merchant force (no pore water): drawn once.
    drawn = set()
    for stem, label, colour, kn in analytical_lines(summary):
        if stem == "hyperbaric" and round(kn, 9) in drawn:
            continue
        drawn.add(round(kn, 9))
        ax.axhline(kn, color=colour, lw=1.2, ls=":", label=f"{label}: {kn:.3g} kN/m")
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("tool travel into the specimen [mm]")
    ax.set_ylabel("force on the tool [kN per m of width]")
    status = summary.get("status", "running or stopped early: no summary.json")
    ax.set_title(f"{run_name(out)}: tool forces ({status})", fontsize=10)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "force.png"))
    plt.close(fig)


def plot_damage(out, d, tool):
    if d.last is None:
        print(f"{out}: no frame with damage; damage.png not written", file=sys.stderr)
        return
    pos, radius, damage, t = d.last
    damage = np.clip(damage, 0.0, 1.0)
    ts = d.ts
    poly = chisel_at(tool, d.first, ts, t)
    fig, ax = plt.subplots(figsize=(8, 5), dpi=dpi_for(radius))
    coll = discs(ax, pos, radius, array=damage, cmap="jet", linewidths=0)
    coll.set_clim(0, 1)
    if poly is not None:
        ax.add_patch(Polygon(poly, closed=True, fc="0.5", ec="k", lw=0.8, zorder=3))
    frame_extent(ax, pos, radius, poly)
    fig.colorbar(coll, ax=ax, shrink=0.8, label="damage D = 1 - bonds / initial bonds")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{run_name(out)}: damage at t = {t:.4g} s ({len(radius)} discs)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "damage.png"))
    plt.close(fig)


def plot_breaks(out, d):
    last = d.last[:2] if d.last is not None else None
    if d.breaks is not None:
        x, y, mode = d.breaks
    else:
        x, y, mode = np.zeros(0), np.zeros(0), np.zeros(0)
    n = len(mode)
    fig, ax = plt.subplots(figsize=(8, 5), dpi=dpi_for(last[1] if last is not None else ()))
    if last is not None:
        discs(ax, last[0], last[1], facecolors="0.88", edgecolors="0.75", linewidths=0.2)
        frame_extent(ax, *last)
    else:
        ax.set_aspect("equal")
    size = 4 if n > 2000 else 10
    for value, name, colour in ((0, "tensile", "tab:blue"), (1, "shear", "tab:red")):
        sel = mode == value
        ax.scatter(x[sel], y[sel], s=size, c=colour, lw=0, label=f"{name} ({int(sel.sum())})",
                   zorder=3)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{run_name(out)}: {n} bond breaks, where they broke, by mode "
                 "(on the last frame's discs)", fontsize=10)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "breaks.png"))
    plt.close(fig)


def plot_cutting(out):
    h5 = os.path.join(out, "run.h5")
    if not os.path.isfile(h5):
        print(f"{out}: no run.h5", file=sys.stderr)
        return False
    summary = read_summary(out) or {}
    # A run that is writing run.h5 may leave it briefly inconsistent: try again a few times.
    for attempt in range(5):
        try:
            d = load(h5)
            break
        except (OSError, KeyError, ValueError):
            if attempt == 4:
                raise
            time.sleep(1.0)
    tool = tool_block(d.scene)
    plot_force(out, d.ts, tool, summary)
    plot_damage(out, d, tool)
    plot_breaks(out, d)
    print(f"{out}: wrote " + ", ".join(
        p for p in ("force.png", "damage.png", "breaks.png") if os.path.exists(os.path.join(out, p))))
    return True


def kind_of(out):
    """"cutting", "calibration" or None (no run.h5, or neither kind of time series)."""
    h5 = h5_path(out)
    if not os.path.isfile(h5):
        return None
    with h5py.File(h5, "r") as f:
        names = set(f["timeseries"].keys()) if "timeseries" in f else set()
    if "axial_strain" in names:
        return "calibration"
    return "cutting" if "tool_travel_m" in names else None


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut plot", description=__doc__.split("\n")[0],
                                 epilog="\n".join(__doc__.split("\n")[1:]),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", nargs="+", help="a run's output folder")
    ap.add_argument("--png", help="calibration runs: draw them all into this one figure")
    a = ap.parse_args(argv)
    ok = True
    calibration = []
    for out in a.out:
        try:
            kind = kind_of(out)
            if kind == "calibration":
                calibration.append(out)
            elif kind == "cutting":
                ok = plot_cutting(out) and ok
            else:
                print(f"{out}: no run.h5 with a tool's or a loading test's time series",
                      file=sys.stderr)
                ok = False
        except Exception as e:  # keep going with the other runs
            print(f"{out}: {type(e).__name__}: {e}", file=sys.stderr)
            ok = False
    if calibration:
        try:
            plot_calibration(calibration, a.png)
        except (OSError, KeyError) as e:
            print(f"{type(e).__name__}: {e}", file=sys.stderr)
            ok = False
    return 0 if ok else 1
