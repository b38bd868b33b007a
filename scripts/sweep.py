#!/usr/bin/python3
"""Parameter sweep of a scene, and the paper's figures 8-12 from it.

  scripts/sweep CASE --vary water_depth_m=0,10,40,100,250,1000,2000 [--jobs N] [--out DIR]
                [--set path=value ...] [--coupler PATH] [--plot-only]

Runs `coupler run CASE --out DIR/<name>=<value> [--set path=value ...] --set <name>=<value>` once
per value, --jobs at a time, each run's output in DIR/<name>=<value>/log.txt, and prints one line
per finished run. Then writes
  DIR/sweep.csv                one row per value: the varied parameter, hydrostatic_pressure_pa,
                               then every scalar key of the runs' summary.json (sorted) and the
                               run's exit_code
  DIR/fig08_forces.png         mean horizontal and vertical tool force against the hydrostatic
                               pressure (paper figure 8)
  DIR/fig09_pressure_p1.png    mean pore pressure at P1 (figure 9)
  DIR/fig10_pressure_p2_p3.png mean pore pressures at P2 and P3 (figure 10)
  DIR/fig11_damage_<v>.png     damage of the last frame of the smallest value (figure 11: 0 m)
  DIR/fig12_damage_<v>.png     ... and of the largest value (figure 12: 2000 m)
  DIR/breaks_fraction.png      tensile and shear share of the broken bonds
  DIR/chips.png                number of chips and their mean area
When the varied parameter is not water_depth_m, figures 8-10 are drawn against the varied value.
A figure whose summary keys no run has (e.g. the pressures of a dry scene) is skipped with a note.

  --out DIR      default out/sweep_<case stem>
  --jobs N       runs at a time; default the CPUs divided by the scene's dem.threads
  --coupler PATH default build/bin/coupler of this repository
  --plot-only    run nothing: collect sweep.csv and draw from DIR (CASE and --vary may then be left
                 out when --out is given: the values are found from DIR's <name>=<value> folders)

Exit status: 0 if every run succeeded (coupler exit code 0), 1 if any failed (the sweep goes on and
draws what it has), 2 on bad arguments, 130 if interrupted. With --plot-only: 0 once drawn (failed
runs are listed in a note), 1 if DIR holds no run results.
"""
import argparse
import csv
import glob
import json
import math
import os
import re
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

# plot_cutting reads run.h5 and draws discs; it also sets the Agg backend and HDF5 file locking.
import plot_cutting  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402
from matplotlib.ticker import MaxNLocator, NullLocator  # noqa: E402

# The scene's defaults (proto/rockcut/scene.proto), used when a summary lacks
# hydrostatic_pressure_pa: p_hydro = p_atm + rho_w g water_depth_m.
P_ATM_PA = 101325.0
RHO_WATER_KG_M3 = 1025.0
GRAVITY_M_S2 = 9.81


def note(message):
    sys.stdout.flush()  # keep the notes in order with the progress lines
    print(f"note: {message}", file=sys.stderr)


# ---------------------------------------------------------------------------------------------
# Arguments


def parse_vary(text):
    """'name=v1,v2,...' -> (name, [v1, v2, ...]) with the values kept as typed (they name the
    run folders)."""
    name, sep, values = text.partition("=")
    values = [v.strip() for v in values.split(",") if v.strip()]
    if not sep or not name or not values:
        raise argparse.ArgumentTypeError(f"expected name=v1,v2,... , got '{text}'")
    if len(set(values)) != len(values):
        raise argparse.ArgumentTypeError(f"repeated value in '{text}'")
    return name.strip(), values


def parse_args(argv):
    p = argparse.ArgumentParser(prog="scripts/sweep", description=__doc__.split("\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="\n".join(__doc__.split("\n")[1:]))
    p.add_argument("case", nargs="?", help="scene file (protobuf text format)")
    p.add_argument("--vary", type=parse_vary, help="name=v1,v2,... : the scene field to vary")
    p.add_argument("--jobs", type=int, help="runs at a time")
    p.add_argument("--out", help="sweep directory (default out/sweep_<case stem>)")
    p.add_argument("--set", action="append", default=[], metavar="PATH=VALUE",
                   help="scene override passed to every run (repeatable)")
    p.add_argument("--coupler", default=os.path.join(ROOT, "build", "bin", "coupler"))
    p.add_argument("--plot-only", action="store_true", help="run nothing, collect and draw")
    args = p.parse_args(argv)
    if not args.plot_only and (args.case is None or args.vary is None):
        p.error("CASE and --vary are required (unless --plot-only)")
    if args.out is None:
        if args.case is None:
            p.error("give CASE or --out")
        stem = os.path.splitext(os.path.basename(args.case))[0]
        args.out = os.path.join("out", f"sweep_{stem}")
    if args.jobs is not None and args.jobs < 1:
        p.error("--jobs must be at least 1")
    return args


def values_in(out):
    """(name, values) from the <name>=<value> folders of a sweep directory (for --plot-only)."""
    found = {}
    for d in sorted(os.listdir(out)) if os.path.isdir(out) else []:
        if "=" in d and os.path.isdir(os.path.join(out, d)):
            name, _, value = d.partition("=")
            found.setdefault(name, []).append(value)
    if len(found) != 1:
        raise SystemExit(f"sweep: cannot tell the varied parameter from {out} "
                         f"(found {sorted(found) or 'no <name>=<value> folders'}): give --vary")
    return next(iter(found.items()))


def as_number(value):
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def sorted_values(values):
    """Numeric values in increasing order; other values (e.g. model names) as given."""
    if all(as_number(v) is not None for v in values):
        return sorted(values, key=float)
    return list(values)


def cpu_count():
    try:
        return len(os.sched_getaffinity(0))  # the CPUs this process may use (containers, taskset)
    except AttributeError:
        return os.cpu_count() or 1


def dem_threads(case, sets):
    """dem.threads as the run will see it: a --set override, else the scene's `dem { threads: N }`,
    else the default 1. A plain-text look, good enough for choosing --jobs."""
    for s in reversed(sets):
        key, _, value = s.partition("=")
        if key.strip() == "dem.threads" and value.strip().isdigit():
            return int(value)
    try:
        with open(case) as f:
            text = re.sub(r"#[^\n]*", "", f.read())  # drop comments
    except OSError:
        return 1
    m = re.search(r"^\s*dem\s*:?\s*\{", text, re.M)
    if not m:
        return 1
    # The dem block up to its closing brace, then its nested blocks (specimen, tool, ...) removed
    # so that only dem's own fields remain.
    depth, end = 1, m.end()
    while depth and end < len(text):
        depth += {"{": 1, "}": -1}.get(text[end], 0)
        end += 1
    body = text[m.end():end - 1]
    while True:
        flat = re.sub(r"\{[^{}]*\}", "", body)
        if flat == body:
            break
        body = flat
    t = re.search(r"\bthreads\s*:\s*(\d+)", body)
    return int(t.group(1)) if t else 1


# ---------------------------------------------------------------------------------------------
# Running


def run_dir(out, name, value):
    return os.path.join(out, f"{name}={value}")


def start_run(args, name, value):
    d = run_dir(args.out, name, value)
    os.makedirs(d, exist_ok=True)
    # Files of an earlier sweep in the same folder must not pass for this run's results.
    for stale in ("summary.json", "sweep_run.json", "run.h5", "run.xdmf"):
        if os.path.exists(os.path.join(d, stale)):
            os.remove(os.path.join(d, stale))
    cmd = [args.coupler, "run", args.case, "--out", d]
    for s in args.set:
        cmd += ["--set", s]
    cmd += ["--set", f"{name}={value}"]  # last, so that it wins over a --set of the same field
    log = open(os.path.join(d, "log.txt"), "w")
    log.write("$ " + " ".join(cmd) + "\n")
    log.flush()
    # start_new_session: a Ctrl-C at the terminal reaches only this script, which then stops the
    # runs itself (below) instead of each run receiving it at a random point.
    proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                            start_new_session=True)
    return proc, log, time.monotonic(), cmd


def finish_run(args, name, value, proc, log, t0, cmd):
    """Records the run's exit code beside its output (for --plot-only) and prints its line."""
    log.close()
    wall = time.monotonic() - t0
    d = run_dir(args.out, name, value)
    with open(os.path.join(d, "sweep_run.json"), "w") as f:
        json.dump({"command": cmd, "exit_code": proc.returncode, "sweep_wall_s": wall}, f, indent=1)
    summary = read_summary(d)
    status = summary.get("status") if summary else "no summary.json"
    ok = proc.returncode == 0
    print(f"{name}={value}: {'ok' if ok else 'FAILED'}, status {status}, {wall:.1f} s wall, "
          f"exit code {proc.returncode}" + ("" if ok else f"  (see {d}/log.txt)"), flush=True)
    return ok


def run_sweep(args, name, values):
    """Runs every value, --jobs at a time. Returns True if all exited with 0."""
    jobs = args.jobs or max(1, cpu_count() // dem_threads(args.case, args.set))
    print(f"sweep: {len(values)} runs of {args.case} ({name} = {', '.join(values)}), {jobs} at a "
          f"time, into {args.out}", flush=True)
    pending = list(values)
    running = {}  # value -> (proc, log, t0, cmd)
    all_ok = True

    def stop(signum, frame):  # `kill` of the sweep stops its runs as Ctrl-C does
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    try:
        while pending or running:
            while pending and len(running) < jobs:
                value = pending.pop(0)
                running[value] = start_run(args, name, value)
            time.sleep(0.2)
            for value in [v for v, r in running.items() if r[0].poll() is not None]:
                all_ok = finish_run(args, name, value, *running.pop(value)) and all_ok
    except KeyboardInterrupt:
        # Ask the runs to stop (the coupler closes its output on SIGTERM), then insist.
        print(f"sweep: interrupted; stopping {len(running)} run(s)", file=sys.stderr)
        for proc, *_ in running.values():
            proc.send_signal(signal.SIGTERM)
        for proc, log, *_ in running.values():
            try:
                proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
            log.close()
        raise SystemExit(130)
    return all_ok


# ---------------------------------------------------------------------------------------------
# Collecting


def read_summary(d):
    try:
        with open(os.path.join(d, "summary.json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def collect(out, name, values):
    """One row (dict) per value, in the order of `values`."""
    rows = []
    for value in values:
        d = run_dir(out, name, value)
        summary = read_summary(d) or {}
        row = {k: v for k, v in summary.items()
               if v is None or isinstance(v, (bool, int, float, str))}  # scalars only
        try:
            with open(os.path.join(d, "sweep_run.json")) as f:
                row["exit_code"] = json.load(f).get("exit_code")
        except (OSError, ValueError):
            pass  # run outside this script, or before it recorded exit codes
        if not summary:
            row["status"] = "not run" if "exit_code" not in row else "failed: no summary.json"
        # The summary's own value wins; else p_atm + rho g h for a water-depth sweep.
        depth = as_number(value) if name == "water_depth_m" else None
        if "hydrostatic_pressure_pa" not in row and depth is not None:
            row["hydrostatic_pressure_pa"] = P_ATM_PA + RHO_WATER_KG_M3 * GRAVITY_M_S2 * depth
        row[name] = value
        rows.append(row)
    return rows


def write_csv(path, name, rows):
    keys = sorted(set().union(*(r.keys() for r in rows)) - {name, "hydrostatic_pressure_pa"})
    columns = [name, "hydrostatic_pressure_pa"] + keys
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, restval="")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in columns})


# ---------------------------------------------------------------------------------------------
# Figures


UNITS = (("_m_s", "m/s"), ("_m2", "m²"), ("_pa", "Pa"), ("_deg", "°"), ("_s", "s"), ("_m", "m"))


def axis_label(name):
    """'tool.velocity_m_s' -> 'tool.velocity [m/s]' (the unit from the field's suffix)."""
    for suffix, unit in UNITS:
        if name.endswith(suffix):
            return f"{name[:-len(suffix)]} [{unit}]"
    return name


def value_unit(name):
    for suffix, unit in UNITS:
        if name.endswith(suffix):
            return " " + unit
    return ""


class Sweep:
    """The collected rows, sorted by the varied value, with helpers to pull out columns."""

    def __init__(self, out, name, rows):
        self.out, self.name = out, name
        self.numeric = all(as_number(r[name]) is not None for r in rows)
        self.rows = sorted(rows, key=lambda r: float(r[name])) if self.numeric else rows
        self.values = [r[name] for r in self.rows]
        # Non-numeric values (e.g. fluid.model=explicit,implicit) are drawn at 0, 1, 2, ...
        self.x = (np.array([float(v) for v in self.values]) if self.numeric
                  else np.arange(len(self.values), dtype=float))

    def column(self, key):
        """The key's values as floats (NaN where missing), or None if no run has it."""
        col = np.array([as_number(r.get(key)) for r in self.rows], dtype=float)  # None -> NaN
        if np.isnan(col).all():
            return None
        return col

    def columns(self, keys, figure):
        """{key: column} of the keys some run has; notes the others."""
        found = {k: self.column(k) for k in keys}
        missing = [k for k, c in found.items() if c is None]
        if missing:
            note(f"{figure}: no run's summary has {', '.join(missing)}; "
                 + ("left out of it" if len(missing) < len(keys) else "not drawn"))
        return {k: c for k, c in found.items() if c is not None}

    def pressure_axis(self):
        """x for figures 8-10: the hydrostatic pressure in MPa when water depth is varied (as in the
        paper), else the varied value. Returns (x, label, is_pressure)."""
        p = self.column("hydrostatic_pressure_pa")
        if self.name == "water_depth_m" and p is not None and not np.isnan(p).any():
            return p / 1e6, "hydrostatic pressure [MPa]", True
        return self.x, axis_label(self.name), False

    def path(self, filename):
        return os.path.join(self.out, filename)


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


def plot_series(ax, x, y, *args, **kw):
    """Points and lines through the runs that have the value: a failed run (NaN) leaves its point
    out without breaking the line."""
    ok = np.isfinite(x) & np.isfinite(y)
    ax.plot(x[ok], y[ok], *args, **kw)


def save(fig, s, filename):
    fig.tight_layout()
    fig.savefig(s.path(filename))
    plt.close(fig)
    print(f"wrote {s.path(filename)}", flush=True)


def remove_stale(s, pattern):
    """A figure that is not drawn this time must not be left from an earlier sweep in DIR."""
    for f in glob.glob(s.path(pattern)):
        os.remove(f)


def line_figure(s, filename, title, series, ylabel, scale, against_pressure, reference=False):
    """One panel of lines: series = [(key, legend label, colour)], values multiplied by `scale`.
    reference: also draw y = hydrostatic pressure (for the pore pressures, in the same unit)."""
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
            plot_series(ax, x, cols[key] * scale, "o-", color=colour, label=label)
    if reference and is_pressure:
        ax.plot(x, x, ":", color="0.4", label="hydrostatic pressure")
    ax.axhline(0, color="k", lw=0.5)
    value_axis(s, ax, is_pressure)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8)
    save(fig, s, filename)


def fig_forces(s):
    line_figure(s, "fig08_forces.png", "Mean tool forces over the steady part of the cut (fig. 8)",
                [("force_horizontal_mean_n_per_m", "horizontal (resisting the cut)", "tab:blue"),
                 ("force_vertical_mean_n_per_m", "vertical (up > 0)", "tab:orange")],
                "mean force on the tool [kN per m of width]", 1e-3, against_pressure=True)


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
    total = cols["breaks_tensile"] + cols["breaks_shear"]
    with np.errstate(invalid="ignore", divide="ignore"):  # no breaks at all: no fraction (NaN)
        tensile = np.where(total > 0, cols["breaks_tensile"] / total, np.nan)
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=100)
    plot_series(ax, s.x, tensile, "o-", color="tab:blue", label="tensile")
    plot_series(ax, s.x, 1 - tensile, "s-", color="tab:red", label="shear")
    for xi, n in zip(s.x, total):
        if np.isfinite(n):
            ax.annotate(f"{int(n)}", (xi, 1.0), textcoords="offset points", xytext=(0, 3),
                        ha="center", fontsize=7, color="0.4")
    value_axis(s, ax, False)
    ax.set_ylim(0, 1.08)
    ax.set_xlabel(axis_label(s.name))
    ax.set_ylabel("fraction of the broken bonds [-]")
    ax.set_title("Bond breaks by mode (number of breaks above the points)", fontsize=10)
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
        plot_series(ax, s.x, cols[key] * scale, "o-", color=colour)
        ax.set_ylabel(ylabel)
        ax.set_ylim(bottom=0)
        if key == "chips":
            ax.yaxis.set_major_locator(MaxNLocator(integer=True))
        value_axis(s, ax, False)
    axes[-1, 0].set_xlabel(axis_label(s.name))
    axes[0, 0].set_title("Chips cut off at the end of the run", fontsize=10)
    save(fig, s, filename)


def fig_damage(s, value, filename, figure_no):
    """Discs of the run's last complete frame coloured by damage, with the chisel, in mm."""
    h5 = os.path.join(run_dir(s.out, s.name, value), "run.h5")
    if not os.path.isfile(h5):
        note(f"{filename}: no {h5}; not drawn")
        return
    d = plot_cutting.load(h5)
    if d.last is None:
        note(f"{filename}: {h5} has no frame with damage; not drawn")
        return
    pos, radius, damage, t = d.last
    pos, radius = pos * 1e3, radius * 1e3  # mm
    tool = plot_cutting.tool_block(d.scene)
    # The chisel where dem_module puts it at the frame's time (as plot_cutting.plot_damage does).
    poly = None
    ts = d.ts
    if (d.first is not None and "tool_travel_m" in ts and "time_s" in ts and len(ts["time_s"])
            and not math.isnan(t)):
        p0, r0 = d.first
        left, top = (p0[:, 0] - r0).min(), (p0[:, 1] + r0).max()
        travel = np.interp(t, ts["time_s"], ts["tool_travel_m"])
        poly = plot_cutting.tool_polygon(tool, left + travel, top - tool["cutting_depth_m"]) * 1e3
    fig, ax = plt.subplots(figsize=(8, 5), dpi=plot_cutting.dpi_for(radius))
    coll = plot_cutting.discs(ax, pos, radius, array=np.clip(damage, 0, 1), cmap="jet",
                              linewidths=0)
    coll.set_clim(0, 1)
    if poly is not None:
        ax.add_patch(Polygon(poly, closed=True, fc="0.5", ec="k", lw=0.8, zorder=3))
    plot_cutting.frame_extent(ax, pos, radius, poly)  # also sets the equal aspect
    fig.colorbar(coll, ax=ax, shrink=0.8, label="damage D = 1 - bonds / initial bonds [-]")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(f"Damage at {s.name} = {value}{value_unit(s.name)}, t = {t:.4g} s "
                 f"(fig. {figure_no})", fontsize=10)
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
    have = [v for v in s.values
            if os.path.isfile(os.path.join(run_dir(s.out, s.name, v), "run.h5"))]
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


# ---------------------------------------------------------------------------------------------


def main(argv):
    args = parse_args(argv)
    name, values = args.vary if args.vary else values_in(args.out)
    ok = True
    if not args.plot_only:
        if not os.access(args.coupler, os.X_OK):
            print(f"sweep: no coupler at {args.coupler} (build it, or give --coupler)",
                  file=sys.stderr)
            return 2
        ok = run_sweep(args, name, values)
    rows = collect(args.out, name, sorted_values(values))
    if not any("exit_code" in r or r.get("status") not in (None, "not run") for r in rows):
        print(f"sweep: no run results in {args.out}", file=sys.stderr)
        return 1
    os.makedirs(args.out, exist_ok=True)
    failed = [f"{r[name]} (exit code {r['exit_code']})" for r in rows
              if r.get("exit_code") not in (0, None)]
    if args.plot_only and failed:
        note(f"runs that failed: {', '.join(failed)}")
    write_csv(os.path.join(args.out, "sweep.csv"), name, rows)
    print(f"wrote {os.path.join(args.out, 'sweep.csv')}")
    draw(Sweep(args.out, name, rows))
    if not ok:
        print("sweep: some runs failed (see above)", file=sys.stderr)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
