"""The window means of rockcut windows (windows.py documents the columns): reading a cutting run's
time series and bond breaks from run.h5 (also of a run still writing it), the means over windows of
tool travel, the steady part's trend, and the tables printed.
"""
import json
import math
import os
import re
import sys
from typing import NamedTuple

from .run_data import read_timeseries, stored_scene as scene_of_file, tool_block


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
                # A dynamic cut's force is read at its peak; the mean is mostly the zeros
                # between chips, which the contact share says (both as summary.json's).
                "fh_peak_n_per_m": float((-series["tool_force_x_n_per_m"][picked]).max()),
                "contact_fraction": float(((series["tool_force_x_n_per_m"][picked] != 0) |
                                           (series["tool_force_y_n_per_m"][picked] != 0)).mean()),
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
    head = ["travel [mm]", "samples", "Fh [kN/m]", "Fv [kN/m]", "Fh peak [kN/m]", "contact %"]
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
                 fmt(r["fh_n_per_m"], 1e-3, 1), fmt(r["fv_n_per_m"], 1e-3, 1),
                 fmt(r["fh_peak_n_per_m"], 1e-3, 1), fmt(r["contact_fraction"], 100, 0)]
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


def shear_fraction(w):
    tensile, shear = w.get("breaks_tensile"), w.get("breaks_shear")
    if tensile is None or shear is None or tensile + shear <= 0:
        return math.nan
    return shear / (tensile + shear)


class Run(NamedTuple):
    label: str     # the path given
    depth: float   # water_depth_m [m]
    seed: int      # dem.specimen.seed
    p_hydro: float  # [Pa], NaN without summary.json
    rows: list     # windows()
