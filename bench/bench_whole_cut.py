#!/usr/bin/python3
"""Whole cuts as a user runs them, one right after the other, then bench_dem: the ratios that say
whether a coupled run is as fast as its dry run and a dry run as fast as the DEM alone.

  bench/bench_whole_cut.py [--scene dry,saturated] [--depth 0] [--scale paper|reduced]
                           [--damping viscous|local] [--windows-mm 0,10,25,40]
                           [--set PATH=VALUE] ... [--no-bench-dem] [--json FILE]
                           [--keep DIR [--resume]] [--coupler PATH] [--bench-dem PATH]

Each run is `coupler run SCENE` with the scene's own output (frames, time series, checkpoints), as
a user starts it; --set adds overrides to every run (e.g. time.end_time_s for a shorter cut). The
runs go one after the other in the order given (dry first by default), because this machine's
speed moves by tens of percent from one hour to the next and only runs side by side compare.
Right after the last run, bench_dem measures the DEM alone on its 57k block at the dry scene's
thread count and damping model (BM_BondedBlockCutting/T under local damping,
BM_BondedBlockCuttingViscous/T under dashpots).

It prints per run:
  wall, steps, particle-steps/s   from the run's summary.json
  ms/step per window              the wall per DEM step between travels of the tool (--windows-mm,
                                  read off the run's progress lines, every 10 s of wall), and the
                                  whole run's over the first window's: the criterion "whole cuts
                                  as fast per step as their early stretches"
and then the saturated runs' wall over the dry run's and the dry run's rate over bench_dem's.
A paper-scale dry cut takes about an hour on two cores and a saturated one three to four. Such
a call can be taken in parts: Ctrl-C stops the run in progress after a checkpoint (the coupler's
own stop), and the same command with --keep DIR --resume continues it where it stopped and runs
the rest; a run's wall is then the sum of its segments', each placed after the wall at which the
segments before reached its checkpoint.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import bench_real_cut  # bench/: the scenes and the effective scene's fields

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROGRESS = re.compile(r"^t = ([-+0-9.eE]+) / [-+0-9.eE]+ s\s+step (\d+) / \d+\s+wall ([0-9.]+) s",
                      re.M)
RESUMED_AT = re.compile(r"^resume\s+from .*? \(step (\d+),", re.M)
SEGMENT = "=== bench_whole_cut: a segment of the run\n"


def progress_points(log_text):
    """(time [s], step, wall [s]) of every progress line of a run's log, with (0, 0, 0) first."""
    points = [(0.0, 0, 0.0)]
    for m in PROGRESS.finditer(log_text):
        points.append((float(m.group(1)), int(m.group(2)), float(m.group(3))))
    return points


def joined_points(log_text):
    """progress_points of a run made of segments (SEGMENT lines between them, each after the
    first resumed from a checkpoint): each segment's wall restarts at 0 and its first steps redo
    those after the checkpoint, so it is placed at the wall the segments before reached the
    checkpoint's step, and their lines past that step are dropped."""
    points = []
    for text in log_text.split(SEGMENT):
        if not text.strip():
            continue
        own = progress_points(text)
        m = RESUMED_AT.search(text)
        if points and m:
            step = int(m.group(1))
            offset = wall_at(points, step, math.inf)
            if offset is None:  # past the earlier lines: the last one's wall
                offset = points[-1][2]
            points = [p for p in points if p[1] < step]
            points += [(t, s, w + offset) for t, s, w in own[1:] if s > step]
            continue
        points = own
    return points


def wall_at(points, step, max_gap):
    """The wall [s] at `step`, linear between the progress lines around it; None past the last
    line or where those lines lie more than `max_gap` steps apart (too coarse to place it)."""
    for (_, s0, w0), (_, s1, w1) in zip(points, points[1:]):
        if s0 <= step <= s1 and s1 > s0:
            return w0 + (w1 - w0) * (step - s0) / (s1 - s0) if s1 - s0 <= max_gap else None
    return None


def windows(points, steps, wall_s, dt_s, gap_m, velocity_m_s, edges_mm):
    """ms per step between the tool's travels `edges_mm` (the last window ends with the run):
    a list of (from_mm, to_mm, ms_per_step), only the windows whose ends the progress lines
    place to a fifth of the window (a short run's lines, 10 s of wall apart, place none)."""
    # The run's own end: its last step at its total wall.
    points = points + [(steps * dt_s, steps, wall_s)]
    bounds = []
    for mm in edges_mm:
        step = int(round((gap_m + 1e-3 * mm) / velocity_m_s / dt_s))
        if step < steps:
            bounds.append((mm, step))
    bounds.append((None, steps))
    rows = []
    for (a_mm, a), (b_mm, b) in zip(bounds, bounds[1:]):
        gap = 0.2 * (b - a)
        wa, wb = wall_at(points, a, gap), wall_at(points, b, gap)
        if wa is None or wb is None or b <= a:
            continue
        rows.append((a_mm, b_mm, 1e3 * (wb - wa) / (b - a)))
    return rows


def read_summary(out):
    try:
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)
    except FileNotFoundError:
        return None


def whole_run(coupler, scene, sets, out, resume, end_time_s):
    """Runs the scene into `out` (with `resume`, continues what a stopped call left there; a run
    that completed to `end_time_s` is taken as it is), its output appended to out + ".log" one
    segment after the other. Returns its summary and that log."""
    log_path = out + ".log"
    summary = read_summary(out) if resume else None
    done = (summary is not None and summary.get("status") == "completed" and
            summary["time_s"] >= end_time_s - 0.5 * summary["dt_s"])
    if not done:
        argv = [coupler, "run", os.path.join(ROOT, scene), "--out", out,
                "--resume" if resume else "--overwrite"]
        for s in sets:
            argv += ["--set", s]
        with open(log_path, "a" if resume else "w") as log:
            log.write(SEGMENT)
            log.flush()
            p = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT)
            try:
                code = p.wait()
            except KeyboardInterrupt:  # Ctrl-C reached the coupler too: it checkpoints and stops
                p.wait()
                sys.exit("bench_whole_cut: stopped; the same command with --resume continues "
                         "from the runs' checkpoints in %s" % os.path.dirname(out))
        if code != 0:
            with open(log_path) as f:
                tail = f.read()[-3000:]
            sys.exit("bench_whole_cut: %s failed (%d):\n%s" % (" ".join(argv), code, tail))
        summary = read_summary(out)
    with open(log_path) as f:
        return summary, f.read()


def bench_dem_rate(bench_dem, threads, damping_model):
    """bench_dem's particle-steps/s at `threads` threads and the scene's damping model."""
    name = "BM_BondedBlockCuttingViscous" if damping_model == "viscous" else "BM_BondedBlockCutting"
    argv = [bench_dem, "--benchmark_filter=^%s/%d/" % (name, threads), "--benchmark_format=json"]
    p = subprocess.run(argv, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("bench_whole_cut: %s failed (%d):\n%s" % (" ".join(argv), p.returncode,
                                                           p.stderr[-3000:]))
    runs = json.loads(p.stdout)["benchmarks"]
    if not runs:
        sys.exit("bench_whole_cut: bench_dem has no %s/%d" % (name, threads))
    return name + "/%d" % threads, runs[0]["particle_steps_per_s"]


def text_field(text, block, name):
    """A string of the effective scene's text: the first `name: "..."` inside `block {`."""
    m = re.search(r"\b%s\s*\{(.*?)\n\s*\}" % block, text, re.S)
    m = re.search(r'\b%s:\s*"([^"]*)"' % name, m.group(1) if m else "")
    return m.group(1) if m else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default="dry,saturated")
    ap.add_argument("--depth", default="0", help="water depths of the saturated runs [m]")
    ap.add_argument("--scale", choices=["paper", "reduced"], default="paper")
    ap.add_argument("--damping", choices=["viscous", "local"], default="viscous")
    ap.add_argument("--windows-mm", default="0,10,25,40",
                    help="travels of the tool where the per-step windows start [mm]")
    ap.add_argument("--set", action="append", default=[], metavar="PATH=VALUE")
    ap.add_argument("--no-bench-dem", action="store_true")
    ap.add_argument("--json", help="write the figures here")
    ap.add_argument("--keep", help="keep the runs' directories here (default: removed)")
    ap.add_argument("--resume", action="store_true",
                    help="with --keep: continue the runs a stopped call (Ctrl-C) left in it")
    ap.add_argument("--coupler", default=os.path.join(ROOT, "build", "bin", "coupler"))
    ap.add_argument("--bench-dem", help="default: bench_dem beside --coupler")
    args = ap.parse_args()
    if args.resume and not args.keep:
        ap.error("--resume continues the runs in --keep DIR: give it")
    edges = [float(x) for x in args.windows_mm.split(",")]
    bench_dem = args.bench_dem or os.path.join(os.path.dirname(args.coupler), "bench_dem")
    work = args.keep or tempfile.mkdtemp(prefix="rockcut-bench-whole-")
    os.makedirs(work, exist_ok=True)
    results = {"runs": []}
    dry_threads = dry_damping = None
    try:
        for name in args.scene.split(","):
            scene = bench_real_cut.SCENES[(args.scale, args.damping)].get(name)
            if scene is None:
                sys.exit("bench_whole_cut: no %s %s scene at %s scale (%s)" % (
                    args.damping, name, args.scale,
                    ", ".join(bench_real_cut.SCENES[(args.scale, args.damping)])))
            depths = [None] if name == "dry" else [float(d) for d in args.depth.split(",")]
            for depth in depths:
                sets = ([] if depth is None else ["water_depth_m=%g" % depth]) + args.set
                text = bench_real_cut.effective_scene(args.coupler, scene, sets)
                out = os.path.join(work, name if depth is None else "%s_%gm" % (name, depth))
                summary, log = whole_run(args.coupler, scene, sets, out, args.resume,
                                         bench_real_cut.field(text, "time", "end_time_s"))
                gap = bench_real_cut.field(text, "tool", "start_gap_m")
                velocity = bench_real_cut.field(text, "tool", "velocity_m_s") or 1.0
                rows = windows(joined_points(log), summary["steps"], summary["wall_time_s"],
                               summary["dt_s"], 0.001 if gap is None else gap, velocity, edges)
                whole_ms = 1e3 * summary["wall_time_s"] / summary["steps"]
                run = {"scene": scene, "depth_m": depth, "wall_s": summary["wall_time_s"],
                       "steps": summary["steps"], "particles": summary["particles"],
                       "particle_steps_per_s": summary["particle_steps_per_s"],
                       "ms_per_step": whole_ms,
                       "windows": [{"from_mm": a, "to_mm": b, "ms_per_step": ms}
                                   for a, b, ms in rows]}
                if rows:
                    run["whole_over_first_window"] = whole_ms / rows[0][2]
                # What a cut's flying grains cost in list work (summary.json, since the start).
                for key in ("dem_neighbour_rebuilds", "fluid_geometry_updates",
                            "fluid_geometry_rows_recomputed"):
                    if key in summary:
                        run[key] = summary[key]
                results["runs"].append(run)
                if name == "dry":
                    dry_threads = int(bench_real_cut.field(text, "dem", "threads") or 1)
                    dry_damping = text_field(text, "damping", "model") or "local"
                print("%-9s %6s  wall %8.1f s  %9d steps  %.3g particle-steps/s  %.3f ms/step" % (
                    name, "-" if depth is None else "%gm" % depth, run["wall_s"], run["steps"],
                    run["particle_steps_per_s"], whole_ms), flush=True)
                for w in run["windows"]:
                    print("          %s-%s mm: %.3f ms/step" % (
                        "%g" % w["from_mm"], "end" if w["to_mm"] is None else "%g" % w["to_mm"],
                        w["ms_per_step"]))
                if rows:
                    print("          whole run / first window: %.2f" % run["whole_over_first_window"])
                if "dem_neighbour_rebuilds" in run:
                    print("          DEM lists rebuilt every %.0f steps" % (
                        run["steps"] / max(run["dem_neighbour_rebuilds"], 1)), end="")
                    if "fluid_geometry_updates" in run:
                        print(", fluid geometry refreshed every %.1f exchanges" % (
                            summary["exchanges"] / max(run["fluid_geometry_updates"], 1)), end="")
                    print()
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    dry = [r for r in results["runs"] if r["depth_m"] is None]
    if dry:
        for r in results["runs"]:
            if r["depth_m"] is not None:
                r["wall_over_dry"] = r["wall_s"] / dry[0]["wall_s"]
                print("saturated %gm / dry: wall %.2f, per step %.2f" % (
                    r["depth_m"], r["wall_over_dry"], r["ms_per_step"] / dry[0]["ms_per_step"]))
        if not args.no_bench_dem:
            bench, rate = bench_dem_rate(bench_dem, dry_threads, dry_damping)
            results["bench_dem"] = {"benchmark": bench, "particle_steps_per_s": rate}
            dry[0]["rate_over_bench_dem"] = dry[0]["particle_steps_per_s"] / rate
            print("bench_dem %s right after: %.3g particle-steps/s; the dry run's rate is %.2f of it"
                  % (bench, rate, dry[0]["rate_over_bench_dem"]))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
