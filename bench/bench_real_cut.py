#!/usr/bin/python3
"""A stretch in the middle of a real paper-scale cut: where each step's wall time goes.

  bench/bench_real_cut.py [--scene dry,saturated] [--depth 0,2000] [--at-mm 40]
                          [--stretch-mm 0.3] [--repeat 3] [--damping viscous|local]
                          [--scale paper|reduced]
                          [--variant NAME:PATH=VALUE[,PATH=VALUE...]] ...
                          [--threads 1,2,4,...] [--overlap-threads 8,16] [--cache DIR]
                          [--json FILE] [--coupler PATH]

The state at --at-mm of cut is made once per scene and depth (a `coupler run` to that travel,
which writes its end-of-run checkpoint) and kept under --cache (default
$XDG_CACHE_HOME/rockcut/bench_real_cut, outside the tree), keyed by the coupler's version and the
effective scene. Each measurement copies it and continues it with `coupler resume` for
--stretch-mm more. Variants change what a resume may change (the thread counts,
coupling.overlap), e.g. `--variant turns:coupling.overlap=off --variant overlap:coupling.overlap=on`;
the runs of one scene alternate between the variants, --repeat times, because this machine's speed
moves by tens of percent from one hour to the next. `--threads 1,2,4` adds the variants t1, t2,
t4 (T threads for each module, taking turns: what bench/scaling_model.py reads),
`--overlap-threads 8,16` the variants o8, o16 (T each, overlapping; saturated scenes only).
--json is written after every run, so a call stopped part-way keeps what it measured.

Per run it prints, from the resumed run's summary.json (the stretch only):
  ms/step        wall per DEM step
  p-steps/s      particle-steps per second
  dem, fluid     each module's busy time as a share of the wall, and its largest phases
                 (drift, bonds, contacts, finish; passes, force, ...: wire/phase_clock.hpp)
  svc            the modules' service work (messages, reports, guards), summed
  wait           the coupler's requests less the modules' busy time: transport and waiting
  own            the coupler's own work (output, observers, the scheme)
and, per scene and variant, the median over the repeats of the wall per step and of every phase,
the service and the rest (transport, waits, the coupler) per step [ms].
"""
import argparse
import hashlib
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

import scaling_model  # bench/: the per-step medians of every part

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = {
    ("paper", "viscous"): {"dry": "cases/cutting/dry_viscous.pbtxt",
                           "saturated": "cases/cutting/saturated_viscous.pbtxt"},
    ("paper", "local"): {"dry": "cases/cutting/dry.pbtxt",
                         "saturated": "cases/cutting/saturated.pbtxt"},
    # Seconds instead of hours: for trying the benchmark and for its test.
    ("reduced", "viscous"): {"saturated": "cases/cutting/saturated_reduced_long_viscous.pbtxt"},
    ("reduced", "local"): {"dry": "cases/cutting/dry_reduced_long.pbtxt",
                           "saturated": "cases/cutting/saturated_reduced_long.pbtxt"},
}
# Output off while measuring, rows rarely: output is not what is measured.
QUIET = ["output.frame_interval_s=0", "output.timeseries_every_steps=2000"]


def default_cache():
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "rockcut", "bench_real_cut")


def parse_variant(text):
    """'NAME:PATH=VALUE[,PATH=VALUE...]' -> (NAME, [PATH=VALUE, ...])."""
    name, sep, sets = text.partition(":")
    if not sep or not name or not all("=" in s for s in sets.split(",")):
        raise argparse.ArgumentTypeError(
            "variant %r: expected NAME:PATH=VALUE[,PATH=VALUE...]" % text)
    return name, sets.split(",")


def thread_list(text):
    """'1,2,4' -> [1, 2, 4]: thread counts of at least 1."""
    try:
        counts = [int(t) for t in text.split(",")]
    except ValueError:
        counts = []
    if not counts or min(counts) < 1:
        raise argparse.ArgumentTypeError("%r: expected thread counts like 1,2,4" % text)
    return counts


def write_json(path, results):
    """Every run so far, replaced whole (a reader never sees half a file)."""
    tmp = path + ".part"
    with open(tmp, "w") as f:
        json.dump(results, f, indent=1)
    os.replace(tmp, path)


def call(argv, cwd=None):
    p = subprocess.run(argv, capture_output=True, text=True, cwd=cwd)
    if p.returncode != 0:
        sys.exit("bench_real_cut: %s failed (%d):\n%s" % (" ".join(argv), p.returncode,
                                                          p.stderr[-3000:]))
    return p.stdout


def effective_scene(coupler, scene, sets):
    """The scene as the coupler runs it, named by its path in the tree (`scene`, relative to the
    checkout): the cache's key then holds in any checkout, and the states travel with it."""
    argv = [os.path.abspath(coupler), "validate", scene, "--print"]
    for s in sets:
        argv += ["--set", s]
    return call(argv, cwd=ROOT)


def field(text, block, name):
    """A scalar of the effective scene's text: the first `name:` inside `block {`."""
    m = re.search(r"\b%s\s*\{(.*?)\n\}" % block, text, re.S)
    m = re.search(r"\b%s:\s*([-+0-9.eE]+)" % name, m.group(1) if m else "")
    return float(m.group(1)) if m else None


def cut_time_s(text, travel_m):
    """The time at which the tool tip has cut `travel_m` into the block."""
    velocity = field(text, "tool", "velocity_m_s") or 1.0
    gap = field(text, "tool", "start_gap_m")
    return ((0.001 if gap is None else gap) + travel_m) / velocity


def cached_state(coupler, scene, depth, at_mm, cache):
    """The run directory holding the end-of-run checkpoint at `at_mm` of cut; made if missing."""
    sets = ["water_depth_m=%g" % depth] + QUIET
    text = effective_scene(coupler, scene, sets)
    end = cut_time_s(text, at_mm * 1e-3)
    version = call([coupler, "--version"]).strip()
    key = hashlib.sha256(("%s\n%s\n%.12g" % (version, text, end)).encode()).hexdigest()[:16]
    out = os.path.join(cache, "%s_%gm_%gmm_%s" % (os.path.basename(scene)[:-len(".pbtxt")], depth, at_mm, key))
    if not os.path.exists(os.path.join(out, "summary.json")):
        print("making the state at %g mm of %s at %g m (once; kept in %s)" %
              (at_mm, scene, depth, out), flush=True)
        shutil.rmtree(out, ignore_errors=True)
        argv = [coupler, "run", os.path.join(ROOT, scene), "--out", out,
                "--set", "time.end_time_s=%.12g" % end]
        for s in sets:
            argv += ["--set", s]
        call(argv)
    return out, text


def stretch(coupler, state, text, at_mm, stretch_mm, sets):
    """Continues a copy of `state` for stretch_mm; the stretch's figures from its summary.json."""
    with open(os.path.join(state, "summary.json")) as f:
        before = json.load(f)
    # A resume starts from the newest checkpoint, which may lie before the run's end (a dry run's
    # last Advance is not cut at its checkpoint): its step is in its name.
    before["steps"] = max(int(re.match(r"checkpoint_(\d+)\.h5$", name).group(1))
                          for name in os.listdir(os.path.join(state, "checkpoints"))
                          if re.match(r"checkpoint_(\d+)\.h5$", name))
    with tempfile.TemporaryDirectory(prefix="rockcut-bench-cut-") as tmp:
        run = os.path.join(tmp, "run")
        shutil.copytree(state, run)
        end = cut_time_s(text, (at_mm + stretch_mm) * 1e-3)
        argv = [coupler, "resume", run, "--no-checkpoints", "--set", "time.end_time_s=%.12g" % end]
        for s in sets:
            argv += ["--set", s]
        call(argv)
        with open(os.path.join(run, "summary.json")) as f:
            after = json.load(f)
    return figures(before, after)


def figures(before, after):
    """The stretch's wall, steps and the split of its wall time (see the module's doc)."""
    # The resumed loop's wall: its requests to the modules and its own work (summary.json's
    # wall_time_s also counts the first run's, up to its checkpoint).
    wall = after["coupler_own_s"] + sum(after.get(w + "_request_s", 0.0) for w in ("dem", "fluid"))
    steps = after["steps"] - before["steps"]
    row = {"wall_s": wall, "steps": steps, "ms_per_step": 1e3 * wall / steps,
           "particle_steps_per_s": after["particles"] * steps / wall,
           "own_s": after["coupler_own_s"], "phases": {},
           "coupling_interval": after.get("coupling_interval", 1)}
    busy = wait = service = 0.0
    for who in ("dem", "fluid"):
        if who + "_busy_s" not in after:
            continue
        busy_s = after[who + "_busy_s"]
        row[who + "_busy_s"] = busy_s
        busy += busy_s
        wait += after[who + "_request_s"]
        service += after.get(who + "_service_s", 0.0)
        prefix = who + "_phase_"
        row["phases"][who] = {k[len(prefix):-2]: v for k, v in after.items()
                              if k.startswith(prefix)}
    # Requests less busy time; the DEM's work after its replies overlaps the fluid's requests.
    row["wait_s"] = wait - busy + after.get("dem_after_reply_s", 0.0)
    row["service_s"] = service
    return row


def describe(row):
    wall = row["wall_s"]
    parts = []
    for who, phases in row["phases"].items():
        top = sorted(phases.items(), key=lambda kv: -kv[1])[:3]
        parts.append("%s %.0f %% (%s)" % (who, 100 * row[who + "_busy_s"] / wall,
                                          ", ".join("%s %.0f" % (k, 100 * v / wall)
                                                    for k, v in top)))
    return "%8.3f %10.3g  %s; svc %.0f %%, wait %.0f %%, own %.1f %%" % (
        row["ms_per_step"], row["particle_steps_per_s"], "; ".join(parts),
        100 * row["service_s"] / wall, 100 * row["wait_s"] / wall, 100 * row["own_s"] / wall)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default="dry,saturated")
    ap.add_argument("--depth", default="0,2000", help="water depths [m], comma-separated")
    ap.add_argument("--scale", choices=["paper", "reduced"], default="paper")
    ap.add_argument("--damping", choices=["viscous", "local"], default="viscous")
    ap.add_argument("--at-mm", type=float, default=40.0)
    ap.add_argument("--stretch-mm", type=float, default=0.3)
    ap.add_argument("--repeat", type=int, default=3, help="0: make the cached states only")
    ap.add_argument("--variant", type=parse_variant, action="append", default=[])
    ap.add_argument("--threads", type=thread_list, default=[],
                    help="1,2,4,...: variants tT, T threads per module taking turns")
    ap.add_argument("--overlap-threads", type=thread_list, default=[],
                    help="8,16,...: variants oT, T threads per module overlapping")
    ap.add_argument("--cache", default=default_cache())
    ap.add_argument("--json", help="write every run's figures here")
    ap.add_argument("--coupler", default=os.path.join(ROOT, "build", "bin", "coupler"))
    args = ap.parse_args()
    variants = args.variant + [
        ("t%d" % t, ["dem.threads=%d" % t, "fluid.threads=%d" % t, "coupling.overlap=off"])
        for t in args.threads] + [
        ("o%d" % t, ["dem.threads=%d" % t, "fluid.threads=%d" % t, "coupling.overlap=on"])
        for t in args.overlap_threads]
    variants = variants or [("scene", [])]
    overlapping = {"o%d" % t for t in args.overlap_threads}
    results = []
    print("%-9s %6s %-8s %8s %10s  split of the wall" % ("scene", "depth", "variant", "ms/step",
                                                       "p-steps/s"))
    for name in args.scene.split(","):
        scene = SCENES[(args.scale, args.damping)].get(name)
        if scene is None:
            sys.exit("bench_real_cut: no %s %s scene at %s scale (%s)" % (
                args.damping, name, args.scale, ", ".join(SCENES[(args.scale, args.damping)])))
        depths = [0.0] if name == "dry" else [float(d) for d in args.depth.split(",")]
        for depth in depths:
            state, text = cached_state(args.coupler, scene, depth, args.at_mm, args.cache)
            # A dry scene has no fluid and nothing to overlap: its oT would repeat its tT.
            runs = [(v, sets) for v, sets in variants if name != "dry" or v not in overlapping]
            rows = {v: [] for v, _ in runs}
            for _ in range(args.repeat):
                for v, sets in runs:
                    if name == "dry":
                        sets = [s for s in sets if not s.startswith(("fluid.", "coupling."))]
                    row = stretch(args.coupler, state, text, args.at_mm, args.stretch_mm, sets)
                    rows[v].append(row)
                    results.append(dict(row, scene=scene, depth_m=depth, variant=v))
                    print("%-9s %6g %-8s %s" % (name, depth, v, describe(row)), flush=True)
                    if args.json:
                        write_json(args.json, results)
            for v, rs in rows.items():
                if not rs:  # --repeat 0: the states only
                    continue
                print("%-9s %6g %-8s median %.3f ms/step over %d" % (
                    name, depth, v, statistics.median(r["ms_per_step"] for r in rs), len(rs)))
                # Every phase, the service and the rest: medians per step [ms].
                parts = scaling_model.per_step(rs)
                print("%-9s %6g %-8s   %s" % (name, depth, v, ", ".join(
                    "%s %.3f" % (k, 1e3 * t) for k, t in parts.items())))
    if args.json:
        write_json(args.json, results)


if __name__ == "__main__":
    main()
