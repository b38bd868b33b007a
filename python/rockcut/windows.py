"""Means of a cutting run's time series over windows of tool travel.

  rockcut windows OUT [OUT ...] [--every-mm 10] [--from-mm 0] [--csv FILE] [--plot PNG]
                  [--plot-travel PNG] [--frames]

OUT is a run's output folder (`coupler run ... --out OUT`), or its run.h5, also of a run still
going. A paper-scale cut takes hours, and one stopped early (Ctrl-C) or cut short
(`--set time.end_time_s=...`) may not reach the steady part from which summary.json takes its means. The window means show how far the force has
settled. For each window [a, a + every) of `tool_travel_m`, from --from-mm to the last sample, this
prints one row:

  travel [mm]              the window; the last one ends at the last sample (a remainder under
                           1 % of a window joins the window before it)
  samples                  time-series samples in it
  Fh, Fv [kN/m]            mean horizontal force resisting the cut (-tool_force_x) and vertical
                           force on the tool (up > 0): the signs of summary.json
  P1, P2, P3 [MPa]         coupled runs: mean p - p_hydro of each pressure node, over the samples
                           in which the node held a particle centre (as summary.json); '-' if none
  tensile, shear, shear %  bond breaks by mode at the window's last sample
  chips, chip mm^2         chips and their mean area at the window's last sample
  cavitated                coupled runs: particles at the cavitation limit at the last sample
  window breaks            bonds broken within the window (run.h5's /breaks, by the tool travel at
                           the time of each break)
  ahead [mm], below tip %  where they broke: the median distance of the breaks ahead of the tool
                           tip in the cutting direction at the time of each break (negative:
                           behind it) and the share of them below the tip's height. A crushed zone
                           that grows ahead of and under the tool shows as both growing. The
                           coupler writes /breaks with each frame, so in a run still going the
                           windows past its newest frame show '-' here.

Under each table one line fits the horizontal force of the steady part (tool travel from
summary.json's steady_after_m, or while the run has no summary.json the scene's
dem.tool.steady_after_m, two cutting depths by default): its mean and its least-squares slope
against travel in kN/m per mm, how far a cut still climbs where summary.json takes its mean.

The means are those of summary.json taken over a window instead of the steady part: with
--from-mm at `steady_after_m` and --every-mm past the end, the one window gives summary.json's
force_*_mean_n_per_m and pressure_*_mean_pa (tests/python/windows_test.py).

  --every-mm W   window width in mm of tool travel (default 10)
  --from-mm A    first window's start in mm (default 0: the tool at the block)
  --csv FILE     also write the rows as CSV (SI units, one column per value; `run` names the
                 run, `water_depth_m` and `seed` are its scene's depth and specimen seed)
  --plot PNG     draw the window means of the runs against their hydrostatic pressure
                 (summary.json's hydrostatic_pressure_pa; a run without summary.json, still
                 going, is left out with a note), one line per window of full width: Fh, Fv,
                 the shear fraction, the mean chip area, P1-P3 and the cavitated particles.
                 Several runs at one depth (other seeds) are drawn as their mean, a bar from
                 their lowest to their highest value and each run as a faint dot, as
                 rockcut sweep draws its seeds. A window shorter than --every-mm (a run's
                 last) is not drawn: for one point per run over the steady part, give its
                 start and length (a paper-scale cut: --from-mm 40 --every-mm 59).
  --plot-travel PNG
                 draw the window means of each run against tool travel, one line per run
                 (labelled with its depth and seed), in the same panels as --plot: whole cuts
                 at several depths side by side, how far each has settled, and where its chips
                 came off (--every-mm 1 for a fine trace). Also for a run still going.

  --frames       also table what lies on the tool in each frame of run.h5 (frames need the
                 `position`, `radius` and `damage` fields): the discs whose centre lies above the
                 block's initial top surface (the cut material, count and area), and of them the
                 ones from 40 mm behind the tip to 10 mm ahead of it (the pile the tool pushes),
                 and the loose discs there (damage 1: every bond broken) above the tip's height.
                 A cut whose crushed grains pile up on the tool shows a growing loose count.

Several OUTs give one table each, in the order given: runs of one scene at several depths stopped
at the same travel (paper-scale cuts take hours each) are compared window by window, the way
docs/results.md compares its paper-scale runs.

Exit status: 0 on success, 2 on bad arguments or a file without a cutting time series.
"""
import argparse
import csv
import json
import math
import os
import re
import sys
from typing import NamedTuple

from .figures import panel_grid
from .run_data import read_frame, read_timeseries, stored_scene as scene_of_file, tool_block

NODES = ("p1", "p2", "p3")


def fail(message):
    print(f"windows: {message}", file=sys.stderr)
    raise SystemExit(2)


def read_series(path):
    """The time series of run.h5 as float arrays of one length (run_data.read_timeseries,
    which also reads a file the run is still writing)."""
    import h5py  # run_data has set HDF5_USE_FILE_LOCKING before h5py opens a file
    if os.path.isdir(path):
        path = os.path.join(path, "run.h5")
    if not os.path.isfile(path):
        fail(f"{path}: no such file (give a run's --out folder or its run.h5)")
    try:
        with h5py.File(path, "r") as f:
            series = read_timeseries(f)
    except OSError as e:
        fail(f"{path}: cannot read: {e}")
    if not series:
        fail(f"{path}: no time series (output.timeseries_every_steps 0?)")
    for key in ("tool_travel_m", "tool_force_x_n_per_m", "tool_force_y_n_per_m"):
        if key not in series:
            fail(f"{path}: time series has no '{key}': not a cutting run (a scene with dem.tool)")
    if len(series["tool_travel_m"]) == 0:
        fail(f"{path}: the time series is empty")
    return path, series


def read_breaks(path):
    """run.h5's /breaks (one row per broken bond: time_s, x_m, y_m) as float arrays, and
    `covered_to_s`, the time up to which they are complete; or None for a file without them (a run
    with no bonds). The coupler appends the breaks since the last frame with each frame (also the
    first and the last, whatever the frame interval), so they are complete up to the newest
    frame. Rows a running writer is still adding are cut to the shortest column."""
    import h5py
    import numpy as np
    with h5py.File(path, "r") as f:
        if "breaks" not in f:
            return None
        g = f["breaks"]
        try:
            cols = {k: np.asarray(g[k][()], dtype=float) for k in ("time_s", "x_m", "y_m")}
        except (KeyError, OSError, ValueError):
            return None
        frames = f["frames"] if "frames" in f else {}
        times = [float(frames[k].attrs.get("time_s", math.nan)) for k in frames]
    n = min(len(v) for v in cols.values())
    breaks = {k: v[:n] for k, v in cols.items()}
    breaks["covered_to_s"] = max((t for t in times if math.isfinite(t)), default=-math.inf)
    return breaks


TOOL_KEYS = ("time_s", "tool_tip_x_m", "tool_tip_y_m")  # what placing things at the tool needs


def relative_to_tool(series, time, x, y):
    """(tool travel [m], distance ahead of the tip in the cutting direction [m], height above the
    tip [m]) of points (x, y) [m] at `time` [s] (a scalar or one per point). The tool is taken at
    that time, linear between samples: it moves at a constant velocity, so that is exact between
    samples after its start. The cut runs towards +x when the tip's x grows over the run."""
    import numpy as np
    t, tip_x, tip_y = (series[k] for k in TOOL_KEYS)
    direction = 1.0 if tip_x[-1] >= tip_x[0] else -1.0
    return (np.interp(time, t, series["tool_travel_m"]),
            direction * (x - np.interp(time, t, tip_x)), y - np.interp(time, t, tip_y))


def break_places(series, breaks):
    """relative_to_tool() of each break at its time; None without breaks or the tool's tip."""
    if breaks is None or any(k not in series for k in TOOL_KEYS):
        return None
    return relative_to_tool(series, breaks["time_s"], breaks["x_m"], breaks["y_m"])


PILE_BEHIND_M, PILE_AHEAD_M = 0.04, 0.01  # the --frames window around the tip [m]


def pile_rows(path, series):
    """--frames: one dict per frame of run.h5, in SI units, as documented above."""
    import h5py
    import numpy as np
    rows = []
    if any(k not in series for k in TOOL_KEYS):
        fail(f"{path}: --frames needs the time series' {', '.join(TOOL_KEYS)}")
    fields = ("position", "radius", "damage")
    with h5py.File(path, "r") as f:
        names = sorted(f["frames"].keys()) if "frames" in f else []
        if not names:
            fail(f"{path}: --frames: the run wrote no frames (output.frame_interval_s 0?)")
        if any(k not in f["frames"][names[0]] for k in fields):
            fail(f"{path}: --frames needs the frame fields {', '.join(fields)} "
                 f"(output.frame_fields); the first frame has {', '.join(f['frames'][names[0]])}")
        pos0, r0, _ = read_frame(f["frames"][names[0]], fields)
        top = float((pos0[:, 1] + r0).max())  # the block's initial top surface [m]
        for name in names:
            g = f["frames"][name]
            try:
                pos, r, damage = read_frame(g, fields)
            except (KeyError, OSError, ValueError):
                continue  # the newest frame of a run still writing it
            time = float(g.attrs.get("time_s", math.nan))
            if not math.isfinite(time):
                continue
            travel, ahead, above_tip = relative_to_tool(series, time, pos[:, 0], pos[:, 1])
            by_tool = (ahead >= -PILE_BEHIND_M) & (ahead <= PILE_AHEAD_M)
            above = pos[:, 1] > top
            near = above & by_tool
            loose = by_tool & (damage >= 1.0 - 1e-9) & (above_tip > 0)
            area = np.pi * r * r
            rows.append({"time_s": time, "tool_travel_m": float(travel),
                         "above_surface": int(above.sum()),
                         "above_surface_area_m2": float(area[above].sum()),
                         "at_tool": int(near.sum()), "at_tool_area_m2": float(area[near].sum()),
                         "loose_at_tool": int(loose.sum())})
    return rows


def print_pile(rows):
    print("| frame t [ms] | travel [mm] | above surface | area [mm^2] | at the tool | area [mm^2] "
          "| loose at the tool |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r['time_s'] * 1e3:.1f} | {r['tool_travel_m'] * 1e3:.1f} | {r['above_surface']} "
              f"| {r['above_surface_area_m2'] * 1e6:.1f} | {r['at_tool']} "
              f"| {r['at_tool_area_m2'] * 1e6:.1f} | {r['loose_at_tool']} |")


def run_facts(path):
    """(water depth [m] and specimen seed from the scene stored in run.h5, hydrostatic pressure
    [Pa] from the run's summary.json or NaN while the run has none). The stored scene is the one
    the run used, with its --set overrides; a field it leaves out has its default."""
    depth, seed = 0.0, 1  # the scene fields' defaults (docs/scene_reference.md)
    scene = stored_scene(path)
    m = re.search(r"^water_depth_m:\s*([-+0-9.eE]+)", scene, re.M)
    if m:
        depth = float(m.group(1))
    m = re.search(r"^\s*seed:\s*([0-9]+)", scene, re.M)  # dem.specimen.seed, the scene's only seed
    if m:
        seed = int(m.group(1))
    return depth, seed, summary_value(path, "hydrostatic_pressure_pa", math.nan)


def stored_scene(path):
    """The scene text stored in run.h5 at `path` (run_data.stored_scene)."""
    import h5py
    with h5py.File(path, "r") as f:
        return scene_of_file(f)


def summary_value(path, key, otherwise):
    """summary.json's `key` beside run.h5 at `path` as a float, or `otherwise` while the run has
    none (or it lacks the key)."""
    summary = os.path.join(os.path.dirname(path), "summary.json")
    try:
        with open(summary) as f:
            return float(json.load(f).get(key, otherwise))
    except (OSError, ValueError):
        return otherwise


def steady_start(path):
    """The steady part's start [m of tool travel]: summary.json's steady_after_m, or while the
    run has none the stored scene's dem.tool.steady_after_m (two cutting depths when 0)."""
    scene_start = tool_block(stored_scene(path))["steady_after_m"]
    return summary_value(path, "steady_after_m", scene_start)


def steady_trend(series, start_m):
    """(samples, mean Fh [N/m], least-squares slope of Fh against tool travel [N/m per m]) over
    the samples from start_m of travel on, the steady part of summary.json; slope NaN with fewer
    than 3 samples or no spread in travel."""
    import numpy as np
    picked = series["tool_travel_m"] >= start_m
    travel, fh = series["tool_travel_m"][picked], -series["tool_force_x_n_per_m"][picked]
    slope = math.nan
    if travel.size >= 3 and np.ptp(travel) > 0:
        dx = travel - travel.mean()
        slope = float((dx * (fh - fh.mean())).sum() / (dx * dx).sum())
    return int(picked.sum()), mean(fh), slope


def print_trend(trend, start_m, reached_m):
    samples, fh, slope = trend
    head = f"steady part from {start_m * 1e3:.1f} mm:"
    if samples == 0:
        print(f"{head} not reached (the run reached {reached_m * 1e3:.2f} mm)")
        return
    print(f"{head} {samples} samples, Fh mean {fmt(fh, 1e-3, 1)} kN/m, "
          f"slope {fmt(slope, 1e-6, 2)} kN/m per mm of travel (least squares)")


def mean(values):
    return float(values.mean()) if values.size else math.nan


def break_columns(places, start, end, complete):
    """The window's breaks columns from break_places(): those with a travel in [start, end), or
    from start on when end is None; NaN when the window is not complete (past the newest frame,
    whose breaks are not written yet)."""
    import numpy as np
    if not complete:
        return dict.fromkeys(("window_breaks", "break_ahead_median_m",
                              "break_below_tip_fraction"), math.nan)
    travel, ahead, above = places
    inside = (travel >= start) & (True if end is None else travel < end)
    return {"window_breaks": int(inside.sum()),
            "break_ahead_median_m": float(np.median(ahead[inside])) if inside.any() else math.nan,
            "break_below_tip_fraction": mean((above[inside] < 0).astype(float))}


def windows(series, every_m, from_m, breaks=None):
    """Rows of window means: dicts of SI values, as documented above. `breaks` (read_breaks)
    adds where the window's bonds broke."""
    travel = series["tool_travel_m"]
    places = break_places(series, breaks)
    last = float(travel.max())
    rows = []
    start = from_m
    while start <= last:
        end = start + every_m
        # The last window ends at the last sample; a remainder under 1 % of a window (a sample a
        # rounding past a window's end) joins the window before it.
        is_last = last < end + 0.01 * every_m
        picked = (travel >= start) & (True if is_last else travel < end)
        if picked.any():
            at_end = picked.nonzero()[0][-1]
            row = {
                "from_m": start, "to_m": last if is_last else end, "samples": int(picked.sum()),
                "fh_n_per_m": mean(-series["tool_force_x_n_per_m"][picked]),
                "fv_n_per_m": mean(series["tool_force_y_n_per_m"][picked]),
            }
            for node in NODES:
                p_key = f"fluid_probe_{node}_pa"
                n_key = f"fluid_probe_{node}_particles"
                if p_key in series and n_key in series:
                    row[f"{node}_pa"] = mean(series[p_key][picked & (series[n_key] >= 1)])
            for key in ("breaks_tensile", "breaks_shear", "chips", "chip_area_mean_m2",
                        "fluid_cavitated_particles"):
                if key in series:
                    row[key] = float(series[key][at_end])
            if places is not None:
                complete = series["time_s"][at_end] <= breaks["covered_to_s"]
                row.update(break_columns(places, start, None if is_last else end, complete))
            rows.append(row)
        if is_last:
            break
        start = end
    return rows


def fmt(value, scale, digits):
    return "-" if value is None or math.isnan(value) else f"{value * scale:.{digits}f}"


def print_table(rows):
    coupled = any("p1_pa" in r for r in rows)
    head = ["travel [mm]", "samples", "Fh [kN/m]", "Fv [kN/m]"]
    if coupled:
        head += ["P1 [MPa]", "P2 [MPa]", "P3 [MPa]"]
    head += ["tensile", "shear", "shear %", "chips", "chip [mm^2]"]
    if coupled:
        head += ["cavitated"]
    located = any("window_breaks" in r for r in rows)
    if located:
        head += ["window breaks", "ahead [mm]", "below tip %"]
    print("| " + " | ".join(head) + " |")
    print("|" + "|".join("---" if k == 0 else "---:" for k in range(len(head))) + "|")
    for r in rows:
        tensile, shear = r.get("breaks_tensile"), r.get("breaks_shear")
        fraction = shear_fraction(r)
        cells = [f"{r['from_m'] * 1e3:.1f}-{r['to_m'] * 1e3:.1f}", str(r["samples"]),
                 fmt(r["fh_n_per_m"], 1e-3, 1), fmt(r["fv_n_per_m"], 1e-3, 1)]
        if coupled:
            cells += [fmt(r.get(f"{n}_pa"), 1e-6, 2) for n in NODES]
        cells += [fmt(tensile, 1, 0), fmt(shear, 1, 0), fmt(fraction, 100, 0),
                  fmt(r.get("chips"), 1, 0), fmt(r.get("chip_area_mean_m2"), 1e6, 2)]
        if coupled:
            cells += [fmt(r.get("fluid_cavitated_particles"), 1, 0)]
        if located:
            cells += [fmt(r.get("window_breaks"), 1, 0), fmt(r.get("break_ahead_median_m"), 1e3, 1),
                      fmt(r.get("break_below_tip_fraction"), 100, 0)]
        print("| " + " | ".join(cells) + " |")


class Run(NamedTuple):
    label: str     # the path given
    depth: float   # water_depth_m [m]
    seed: int      # dem.specimen.seed
    p_hydro: float  # [Pa], NaN without summary.json
    rows: list     # windows()


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


def shear_fraction(w):
    tensile, shear = w.get("breaks_tensile"), w.get("breaks_shear")
    if tensile is None or shear is None or tensile + shear <= 0:
        return math.nan
    return shear / (tensile + shear)


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut windows", description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="+", help="a run's output folder, or its run.h5")
    ap.add_argument("--every-mm", type=float, default=10.0)
    ap.add_argument("--from-mm", type=float, default=0.0)
    ap.add_argument("--csv", help="also write the rows to this CSV file (SI units)")
    ap.add_argument("--plot", help="draw the runs' window means against p_hydro into this PNG")
    ap.add_argument("--plot-travel", help="draw each run's window means against tool travel "
                    "into this PNG")
    ap.add_argument("--frames", action="store_true",
                    help="also table what lies on the tool in each frame")
    args = ap.parse_args(argv)
    if not (args.every_mm > 0) or not math.isfinite(args.every_mm):
        fail(f"--every-mm {args.every_mm}: must be a window width > 0 mm")
    if not math.isfinite(args.from_mm):
        fail(f"--from-mm {args.from_mm}: must be a number of mm")
    for option, target in (("--csv", args.csv), ("--plot", args.plot),
                           ("--plot-travel", args.plot_travel)):
        folder = os.path.dirname(os.path.abspath(target)) if target else None
        if folder and not os.path.isdir(folder):
            fail(f"{option} {target}: no folder {folder} to write it in")
    runs = []
    for out in args.out:
        path, series = read_series(out)
        rows = windows(series, args.every_mm * 1e-3, args.from_mm * 1e-3, read_breaks(path))
        reached_mm = float(series["tool_travel_m"].max()) * 1e3
        if not rows:
            fail(f"{path}: no sample at or beyond {args.from_mm} mm of travel "
                 f"(the run reached {reached_mm:.2f} mm)")
        depth, seed, p_hydro = run_facts(path)
        runs.append(Run(path, depth, seed, p_hydro, rows))
        if len(runs) > 1:
            print()
        print(f"{path}: {len(series['tool_travel_m'])} samples, tool travel up to "
              f"{reached_mm:.2f} mm, water depth {depth:g} m, seed {seed}")
        print_table(rows)
        steady_m = steady_start(path)
        print_trend(steady_trend(series, steady_m), steady_m, reached_mm * 1e-3)
        if args.frames:
            print()
            print_pile(pile_rows(path, series))
    if args.plot and not depth_points(runs, args.every_mm * 1e-3, lambda w: w["fh_n_per_m"]):
        reached = ", ".join(f"{r.rows[-1]['to_m'] * 1e3:.2f}" for r in runs)
        fail(f"--plot {args.plot}: no window of full width ({args.every_mm:g} mm from "
             f"{args.from_mm:g} mm) in a run with a summary.json to draw (the runs reached "
             f"{reached} mm; a shorter last window is not drawn): give a smaller --every-mm, "
             f"e.g. the steady part's length for one point per run")
    if args.csv:
        first = ["run", "water_depth_m", "seed"]
        table = [{"run": r.label, "water_depth_m": r.depth, "seed": r.seed, **row}
                 for r in runs for row in r.rows]
        keys = first + sorted({k for r in table for k in r} - set(first))
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=keys)
            writer.writeheader()
            writer.writerows(table)
    if args.plot:
        plot(runs, args.every_mm * 1e-3, args.plot)
        print(f"plot: {args.plot}")
    if args.plot_travel:
        plot_travel(runs, args.every_mm * 1e-3, args.plot_travel)
        print(f"plot: {args.plot_travel}")
    return 0

