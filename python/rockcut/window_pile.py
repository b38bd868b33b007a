"""rockcut windows --frames: what lies on the tool in each frame of run.h5 (windows.py documents the
columns): the cut material above the block's initial top surface, the pile the tool pushes and the
loose discs in it.
"""
import math

from .run_data import read_frame
from .window_means import TOOL_KEYS, fail, relative_to_tool


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
