"""rockcut animate OUT [--color damage|pressure|velocity] [-o FILE] [--gif]: a film of a run.

  rockcut animate OUT [--color damage] [-o OUT/cut.mp4] [--gif] [--fps 10] [--width-px 800]

Draws every frame of OUT/run.h5 (discs to scale as circles of their radius, coloured by the field
chosen, the chisel where the time series puts its tip, the scene's walls where their velocity puts
them, a colour bar, the time and the tool travel in the title) and writes an MP4 (H.264, with Debian's ffmpeg; scripts/setup installs it) or, with
--gif or a FILE ending in .gif, a GIF (Pillow, no ffmpeg needed).

  --color damage    D = 1 - bonds / initial bonds, 0 to 1 (the frame field `damage`)
  --color pressure  the excess pore pressure p - p_hydro [MPa] (field `pressure`; p_hydro from
                    summary.json, else the first frame's median)
  --color velocity  the speed |v| [m/s] (field `velocity`)
The colour range is fixed over the film (pressure and velocity: the 1st to 99th percentile of all
frames), so colours compare between frames. The frames need `position`, `radius` and the field
(output.frame_fields of the scene); output.frame_interval_s sets how many there are.
Exit status: 0 when written, 2 on a run without what the film needs.
"""
import argparse
import os
import shutil
import sys

import numpy as np
from matplotlib import animation
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
from matplotlib.patches import Polygon

from .figures import block_extent, chisel_at, discs, plt
from .run_data import read_run, scene_walls, tool_block, tool_polygon


FIELDS = {"damage": "damage", "pressure": "pressure", "velocity": "velocity"}
LABELS = {"damage": "damage D = 1 - bonds / initial bonds [-]",
          "pressure": "p - p_hydro [MPa]", "velocity": "speed |v| [m/s]"}


def fail(message):
    print(f"rockcut animate: {message}", file=sys.stderr)
    raise SystemExit(2)


def values(color, frame, p_hydro):
    """The colour values of a frame (a run_data.Frame)."""
    if color == "damage":
        return np.clip(frame["damage"], 0.0, 1.0)
    if color == "pressure":
        return (frame["pressure"] - p_hydro) / 1e6
    return np.hypot(frame["velocity"][:, 0], frame["velocity"][:, 1])


def tool_at(run, tool, first, t):
    """The chisel's polygon at time t: at the tip the time series records (tool_tip_x_m, _y_m),
    else where the tool travel puts it (figures.chisel_at); None for a run without a tool."""
    ts = run.timeseries
    if "tool_travel_m" not in ts:
        return None
    if "tool_tip_x_m" in ts and "tool_tip_y_m" in ts and len(ts["time_s"]):
        return tool_polygon(tool, np.interp(t, ts["time_s"], ts["tool_tip_x_m"]),
                            np.interp(t, ts["time_s"], ts["tool_tip_y_m"]))
    return chisel_at(tool, first, ts, t)


def render(out, color="damage", target=None, gif=False, fps=10, width_px=800):
    """Writes the film of run `out`; returns (target, frames written)."""
    run = read_run(out)
    fields = ("position", "radius", FIELDS[color])
    if len(run.frames) < 2:
        fail(f"{out}: {len(run.frames)} frame(s) in run.h5: a film needs two or more "
             "(output.frame_interval_s)")
    missing = [f for f in fields if f not in run.frames.fields]
    if missing:
        fail(f"{out}: the frames lack {', '.join(missing)} (they hold "
             f"{', '.join(run.frames.fields)}; add it to output.frame_fields)")
    gif = gif or (target or "").endswith(".gif")
    target = target or os.path.join(run.path, "cut.gif" if gif else "cut.mp4")
    if not gif and shutil.which("ffmpeg") is None:
        fail("no ffmpeg on PATH: scripts/setup installs Debian's ffmpeg (or use --gif)")

    frames = []
    for i in range(len(run.frames)):
        try:
            frames.append(run.frames.read(i, fields))
        except (KeyError, OSError, ValueError):
            pass  # the newest frame of a run still writing it
    first = (frames[0]["position"], frames[0]["radius"])
    p_hydro = float(run.summary.get("hydrostatic_pressure_pa", np.median(frames[0].get("pressure", [0.0]))))
    if color == "damage":
        norm = Normalize(0.0, 1.0)
    else:
        every = np.concatenate([values(color, f, p_hydro) for f in frames])
        lo, hi = np.percentile(every[np.isfinite(every)], [1.0, 99.0])
        norm = Normalize(lo, hi if hi > lo else lo + 1e-12)
    tool = tool_block(run.scene)
    polys = [tool_at(run, tool, first, f.time_s) for f in frames]
    walls = scene_walls(run.scene)
    # One view for the whole film: the block at the start and the tool along its path.
    lo, hi = block_extent(*first)
    for poly in (p for p in polys if p is not None):
        lo, hi = np.minimum(lo, poly.min(axis=0)), np.maximum(hi, poly.max(axis=0))
    pad = 0.03 * (hi - lo).max()
    lo, hi = lo - pad, hi + pad

    aspect = (hi[1] - lo[1]) / (hi[0] - lo[0])
    dpi = 100
    width = 2 * (width_px // 2)  # H.264 with yuv420p wants even sizes
    height = 2 * int(round(0.5 * width * min(max(aspect, 0.3), 1.5) + 60))
    fig = plt.figure(figsize=(width / dpi, height / dpi), dpi=dpi)
    ax = fig.add_axes([0.12, 0.1, 0.70, 0.76])
    cax = fig.add_axes([0.85, 0.1, 0.025, 0.78])
    fig.colorbar(ScalarMappable(norm=norm, cmap="jet"), cax=cax, label=LABELS[color])
    ax.set_xlim(lo[0] * 1e3, hi[0] * 1e3)
    ax.set_ylim(lo[1] * 1e3, hi[1] * 1e3)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    title = run.summary.get("title") or os.path.basename(os.path.normpath(run.path))
    ts = run.timeseries
    drawn = []

    def draw(k):
        for artist in drawn:
            artist.remove()
        drawn.clear()
        f = frames[k]
        coll = discs(ax, f["position"] * 1e3, f["radius"] * 1e3, array=values(color, f, p_hydro),
                     cmap="jet", norm=norm, linewidths=0)
        drawn.append(coll)
        for w in walls:
            xy = (w["vertices"] + w["velocity_m_s"] * f.time_s) * 1e3
            if w["closed"]:
                xy = np.vstack([xy, xy[:1]])
            drawn.extend(ax.plot(xy[:, 0], xy[:, 1], color="k", lw=1.5, zorder=2))
        if polys[k] is not None:
            drawn.append(ax.add_patch(Polygon(polys[k] * 1e3, closed=True, fc="0.5", ec="k", lw=0.8,
                                              zorder=3)))
        travel = (f" tool travel {np.interp(f.time_s, ts['time_s'], ts['tool_travel_m']) * 1e3:.1f} mm"
                  if "tool_travel_m" in ts and len(ts["time_s"]) else "")
        ax.set_title(f"{title}\nt = {f.time_s * 1e3:.2f} ms{',' if travel else ''}{travel}",
                     fontsize=10)
        return drawn

    film = animation.FuncAnimation(fig, draw, frames=len(frames), blit=False)
    if gif:
        writer = animation.PillowWriter(fps=fps)
    else:
        writer = animation.FFMpegWriter(fps=fps, codec="libx264",
                                        extra_args=["-pix_fmt", "yuv420p"])
    film.save(target, writer=writer, dpi=dpi)
    plt.close(fig)
    return target, len(frames)


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut animate", description=__doc__.split("\n")[0],
                                 epilog="\n".join(__doc__.split("\n")[1:]),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", metavar="OUT", help="a run's output folder")
    ap.add_argument("--color", choices=sorted(FIELDS), default="damage")
    ap.add_argument("-o", "--output", help="the film to write (default OUT/cut.mp4, or cut.gif)")
    ap.add_argument("--gif", action="store_true", help="write a GIF instead of an MP4")
    ap.add_argument("--fps", type=float, default=10.0, help="frames per second (default 10)")
    ap.add_argument("--width-px", type=int, default=800, help="width of the film (default 800)")
    a = ap.parse_args(argv)
    if not os.path.isfile(os.path.join(a.out, "run.h5")):
        fail(f"{a.out}: no run.h5 (give a run's --out folder)")
    if a.fps <= 0 or a.width_px < 100:
        fail("--fps must be > 0 and --width-px at least 100")
    target, n = render(a.out, a.color, a.output, a.gif, a.fps, a.width_px)
    print(f"wrote {target} ({n} frames)")
    return 0
