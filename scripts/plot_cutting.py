#!/usr/bin/python3
"""Plots of a cutting run: scripts/plot_cutting OUT [OUT2 ...]

For each run directory OUT (holding run.h5, and summary.json once the run has ended) writes
  OUT/force.png   the tool forces against tool travel: the force resisting the cut (-F_x) and the
                  vertical force on the tool (F_y, positive up), the steady part shaded and its
                  means drawn as lines (coupler/run/cutting_summary.hpp defines the steady part);
  OUT/damage.png  the discs of the last complete frame as circles of their radius, coloured by
                  damage D = 1 - bonds / initial bonds (paper figures 11-12), with the chisel;
  OUT/breaks.png  where bonds broke, coloured by mode (tensile, shear).
Works on a run that is still going or stopped early: it reads what run.h5 holds so far.
Exit status: 0 if every OUT was plotted, 1 otherwise, 2 without arguments.
"""
import json
import math
import os
import sys
import time

os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")  # the run may still be writing run.h5

import h5py  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene_text as scene_text_module  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402


# ---------------------------------------------------------------------------------------------
# Reading


def tool_block(scene_text):
    """The scalar fields of the scene's `tool { ... }` block (defaults as in scene.proto)."""
    tool = {"cutting_angle_deg": 60.0, "clearance_angle_deg": 5.0, "cutting_depth_m": 0.02,
            "width_m": 0.02, "face_length_m": 0.0, "steady_after_m": 0.0}
    tool.update(scene_text_module.scalar_fields(scene_text, "tool"))
    if tool["face_length_m"] <= 0:
        tool["face_length_m"] = 3.0 * tool["cutting_depth_m"]
    if tool["steady_after_m"] <= 0:
        tool["steady_after_m"] = 2.0 * tool["cutting_depth_m"]
    return tool


class RunData:
    """What the plots need from run.h5, read into memory at once."""

    def __init__(self):
        self.scene = ""     # the effective scene text (root attribute `scene`)
        self.ts = {}        # time-series name -> values, all cut to the same length
        self.first = None   # (position, radius) of the first frame
        self.last = None    # (position, radius, damage, time_s) of the last readable frame
        self.breaks = None  # (x, y, mode), or None without /breaks


def read_timeseries(f):
    if "timeseries" not in f:
        return {}
    g = f["timeseries"]
    series = {}
    for name in g.keys():
        try:
            series[name] = np.asarray(g[name][()], dtype=float)
        except (KeyError, OSError, ValueError):
            pass  # being extended by the writer: leave it out
    n = min((len(v) for v in series.values()), default=0)  # a partial file may be ragged
    return {k: v[:n] for k, v in series.items()}


def read_frame(g, fields):
    values = tuple(np.asarray(g[k][()]) for k in fields)
    if len(values[0]) == 0 or any(len(v) != len(values[0]) for v in values):
        raise ValueError("incomplete frame")
    return values


def stored_scene(f):
    """The scene text stored in an open run.h5 (its root attribute `scene`), "" if none: the
    scene the run used, with its --set overrides."""
    scene = f.attrs.get("scene", "")
    return scene.decode() if isinstance(scene, bytes) else str(scene)


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


# ---------------------------------------------------------------------------------------------
# Plots


def running_mean(y, n):
    if n <= 1 or len(y) < n:
        return y
    c = np.cumsum(np.insert(y, 0, 0.0))
    out = np.empty_like(y)
    out[n - 1:] = (c[n:] - c[:-n]) / n
    out[:n - 1] = c[1:n] / np.arange(1, n)
    return out


def run_name(out):
    return os.path.basename(os.path.normpath(out))


def plot_force(out, ts, tool, summary):
    if not {"tool_travel_m", "tool_force_x_n_per_m", "tool_force_y_n_per_m"} <= ts.keys():
        print(f"{out}: no tool force time series; force.png not written", file=sys.stderr)
        return
    travel_mm = ts["tool_travel_m"] * 1e3
    fh = -ts["tool_force_x_n_per_m"] / 1e3  # kN/m, the force resisting the cut
    fv = ts["tool_force_y_n_per_m"] / 1e3   # kN/m, positive up
    # The steady part as coupler/run/cutting_summary.cpp takes it: travel >= steady_after_m.
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
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("tool travel into the specimen [mm]")
    ax.set_ylabel("force on the tool [kN per m of width]")
    status = summary.get("status", "running or stopped early: no summary.json")
    ax.set_title(f"{run_name(out)}: tool forces ({status})", fontsize=10)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "force.png"))
    plt.close(fig)


def tool_polygon(tool, tip_x, tip_y):
    """The chisel as dem_module builds it: tip, top of the cutting face, end of the clearance face."""
    a = math.radians(tool["cutting_angle_deg"])
    b = math.radians(tool["clearance_angle_deg"])
    L = tool["face_length_m"]
    return np.array([[tip_x, tip_y],
                     [tip_x - L * math.cos(a), tip_y + L * math.sin(a)],
                     [tip_x - L * math.cos(b), tip_y + L * math.sin(b)]])


def dpi_for(radius):
    """Enough pixels to tell the discs apart on a paper-scale block, small files otherwise."""
    return 100 if len(radius) < 5000 else 250


def discs(ax, pos, radius, **kw):
    coll = EllipseCollection(2 * radius, 2 * radius, np.zeros_like(radius), units="xy",
                             offsets=pos, offset_transform=ax.transData, **kw)
    ax.add_collection(coll)
    return coll


def frame_extent(ax, pos, radius, poly=None):
    # The bulk of the discs: the few fragments thrown far away would shrink the block to a strip.
    lo = np.percentile(pos - radius[:, None], 1.0, axis=0)
    hi = np.percentile(pos + radius[:, None], 99.0, axis=0)
    if poly is not None:
        lo = np.minimum(lo, poly.min(axis=0))
        hi = np.maximum(hi, poly.max(axis=0))
    pad = 0.02 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")


def plot_damage(out, d, tool):
    if d.last is None:
        print(f"{out}: no frame with damage; damage.png not written", file=sys.stderr)
        return
    pos, radius, damage, t = d.last
    damage = np.clip(damage, 0.0, 1.0)
    ts = d.ts
    # The chisel: tip `cutting_depth_m` below the specimen's initial top, at the specimen's initial
    # left edge plus the tool travel at the frame's time (as dem_module places it).
    poly = None
    if (d.first is not None and "tool_travel_m" in ts and "time_s" in ts and len(ts["time_s"])
            and not math.isnan(t)):
        p0, r0 = d.first
        left = (p0[:, 0] - r0).min()
        top = (p0[:, 1] + r0).max()
        travel = np.interp(t, ts["time_s"], ts["tool_travel_m"])
        poly = tool_polygon(tool, left + travel, top - tool["cutting_depth_m"])
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


def plot_run(out):
    h5 = os.path.join(out, "run.h5")
    if not os.path.isfile(h5):
        print(f"{out}: no run.h5", file=sys.stderr)
        return False
    summary = {}
    try:
        with open(os.path.join(out, "summary.json")) as s:
            summary = json.load(s)
    except (OSError, ValueError):
        pass
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


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    ok = True
    for out in argv[1:]:
        try:
            ok = plot_run(out) and ok
        except Exception as e:  # keep going with the other runs
            print(f"{out}: {type(e).__name__}: {e}", file=sys.stderr)
            ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
