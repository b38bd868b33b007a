"""What the figures share: the Agg backend (files, no display), discs drawn to scale, the chisel at
a frame's time, the extent of a block, axis scales."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported: `from .figures import plt`)
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402

from .run_data import tool_polygon  # noqa: E402


def dpi_for(radius):
    """Enough pixels to tell the discs apart on a paper-scale block, small files otherwise."""
    return 100 if len(radius) < 5000 else 250


def discs(ax, pos, radius, **kw):
    """The discs as circles of their radius in data units (an EllipseCollection)."""
    coll = EllipseCollection(2 * radius, 2 * radius, np.zeros_like(radius), units="xy",
                             offsets=pos, offset_transform=ax.transData, **kw)
    ax.add_collection(coll)
    return coll


def block_extent(pos, radius, poly=None):
    """(lo, hi) corners of the bulk of the discs and the chisel: the few fragments thrown far away
    would shrink the block to a strip."""
    lo = np.percentile(pos - radius[:, None], 1.0, axis=0)
    hi = np.percentile(pos + radius[:, None], 99.0, axis=0)
    if poly is not None:
        lo = np.minimum(lo, poly.min(axis=0))
        hi = np.maximum(hi, poly.max(axis=0))
    return lo, hi


def frame_extent(ax, pos, radius, poly=None):
    lo, hi = block_extent(pos, radius, poly)
    pad = 0.02 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")


def chisel_at(tool, first, timeseries, t):
    """The chisel's polygon at time `t` where dem_module puts it: tip `cutting_depth_m` below the
    specimen's initial top, at its initial left edge plus the tool travel at that time (from the
    time series). `first` is (position, radius) of the first frame. None without what it needs."""
    if (first is None or "tool_travel_m" not in timeseries or "time_s" not in timeseries
            or not len(timeseries["time_s"]) or math.isnan(t)):
        return None
    p0, r0 = first
    left, top = (p0[:, 0] - r0).min(), (p0[:, 1] + r0).max()
    travel = np.interp(t, timeseries["time_s"], timeseries["tool_travel_m"])
    return tool_polygon(tool, left + travel, top - tool["cutting_depth_m"])


def running_mean(y, n):
    if n <= 1 or len(y) < n:
        return y
    c = np.cumsum(np.insert(y, 0, 0.0))
    out = np.empty_like(y)
    out[n - 1:] = (c[n:] - c[:-n]) / n
    out[:n - 1] = c[1:n] / np.arange(1, n)
    return out


def set_x_scale(ax, x):
    """Log x when the values span a decade or more; symlog when 0 is among them (water depth 0 m),
    linear up to the smallest non-zero value so that 0 gets a place. Returns True if not linear."""
    pos = x[np.isfinite(x) & (x > 0)]
    if len(pos) < 2 or pos.max() / pos.min() < 10 or (x < 0).any():
        return False
    if (x == 0).any():
        ax.set_xscale("symlog", linthresh=pos.min(), linscale=0.5)
    else:
        ax.set_xscale("log")
    return True


def plot_series(ax, x, y, *args, **kw):
    """Points and lines through the values that are finite: a failed run (NaN) leaves its point
    out without breaking the line."""
    ok = np.isfinite(x) & np.isfinite(y)
    ax.plot(x[ok], y[ok], *args, **kw)


def panel_grid(count, **subplots):
    """A figure with `count` panels, four to a row, and the axes of the ones in use."""
    cols = 4 if count > 4 else count
    nrows = (count + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(4.0 * cols, 3.2 * nrows), dpi=100,
                             squeeze=False, **subplots)
    for ax in list(axes.flat)[count:]:
        ax.set_visible(False)
    return fig, axes
