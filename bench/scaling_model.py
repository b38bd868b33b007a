#!/usr/bin/python3
"""What a cut's step would cost on more cores: a model fitted to 1- and 2-thread stretches.

  bench/scaling_model.py RESULTS.json [--one t1] [--two t2] [--cores 2,4,16,64]
                         [--check t4:4,t8:8,t16:16]

RESULTS.json is what `bench/bench_real_cut.py --json` writes, with one variant on one thread per
module and one on two, e.g.
  --variant t1:dem.threads=1,fluid.threads=1,coupling.overlap=off \
  --variant t2:dem.threads=2,fluid.threads=2,coupling.overlap=off
(the modules taking turns on all cores, as they would on C cores with C threads each).

Per scene and depth, per module phase p (medians over the repeats, per step):
  T_p(t) = s_p + q_p / t,   q_p = 2 (T_p(1) - T_p(2)),   s_p = T_p(1) - q_p
(Amdahl's law from two points; a phase that got slower on two threads has q_p < 0, and is taken
as serial with s_p = T_p(2), its two-thread cost, which then holds its synchronisation; one more
than twice as fast on two, from the caches of two cores, has s_p < 0 and is taken as parallel
with q_p = 2 T_p(2)). The modules' service work and the transport are taken as serial (copies of
the arrays, one thread). A barrier's time is the wait for the slowest thread's share: the shares
shrink as 1/t while their spread grows as log2(t), so B(t) = B(2) (2/t) log2(t). The step on C
cores is the DEM's plus the fluid's (they take turns on all C cores) plus the serial rest. The
model ignores memory bandwidth, which caps the pair loops well before 64 cores: its speed-ups
are upper bounds.

--check NAME:T,... compares the model with variants measured on T threads (a machine with the
cores): per variant the predicted and the measured wall per step.

--interval N predicts the step at another coupling interval N than the runs' own (each row's
coupling_interval, 1 where a row lacks it): what the fluid does once per exchange (its passes,
force, advance and staleness test), the service and the rest (transport, waits, the coupler) are
per fluid step and scale as N_measured / N; the DEM's phases are per DEM step, and the fluid's
geometry and boundary refreshes are per distance travelled (geometry_refresh_distance), so
neither changes with N.
"""
import argparse
import json
import math
import statistics
import sys


def fit(t1, t2):
    """(serial, parallel) per step from the 1- and 2-thread costs of a phase."""
    q = 2.0 * (t1 - t2)
    if q <= 0:
        return t2, 0.0
    if q > t1:  # superlinear from one to two threads: no serial part
        return 0.0, 2.0 * t2
    return t1 - q, q


def predict(serial, parallel, threads):
    return serial + parallel / threads


def per_step(rows):
    """Median per-step seconds of every phase, the service and the rest, over `rows`."""
    out = {}
    keys = set()
    for r in rows:
        for who, phases in r["phases"].items():
            keys.update((who, p) for p in phases)
    for who, p in sorted(keys):
        out["%s.%s" % (who, p)] = statistics.median(r["phases"][who][p] / r["steps"] for r in rows)
    out["service"] = statistics.median(r["service_s"] / r["steps"] for r in rows)
    # Transport, waits and the coupler's own work: what the modules' busy time leaves.
    out["rest"] = statistics.median(
        (r["wall_s"] - sum(r.get(w + "_busy_s", 0.0) for w in ("dem", "fluid"))) / r["steps"]
        for r in rows)
    return out


# Per-step costs that do not scale with the coupling interval: the fluid's refreshes follow the
# distance the particles travel, not the exchanges.
PER_DISTANCE = ("fluid.geometry", "fluid.boundary")


def at_interval(costs, measured_interval, interval):
    """Per-step costs measured at `measured_interval` DEM steps per fluid step, moved to
    `interval`: the DEM's phases and the fluid's refreshes stay, the rest scales as
    measured_interval / interval."""
    scale = measured_interval / interval
    return {key: value if key.startswith("dem.") or key in PER_DISTANCE else value * scale
            for key, value in costs.items()}


def measured_interval(rows):
    intervals = {r.get("coupling_interval", 1) for r in rows}
    if len(intervals) != 1:
        sys.exit("scaling_model: runs at different coupling intervals %s in one fit"
                 % sorted(intervals))
    return intervals.pop()


def model(one, two):
    """{part: (serial, parallel, imbalance coefficient)} from per-step costs at 1 and 2 threads."""
    parts = {}
    for key in two:
        a, b = one.get(key, 0.0), two[key]
        if key.endswith(".barrier"):
            parts[key] = (0.0, 0.0, b)       # b (2/t) log2(t): nothing on one thread
        elif key in ("service", "rest"):
            parts[key] = (max(b, 0.0), 0.0, 0.0)
        else:
            s, q = fit(a, b)
            parts[key] = (s, q, 0.0)
    return parts


def step_cost(parts, threads):
    return sum(s + q / threads + g * 2.0 * math.log2(threads) / threads
               for s, q, g in parts.values())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("results")
    ap.add_argument("--one", default="t1")
    ap.add_argument("--two", default="t2")
    ap.add_argument("--cores", default="2,4,16,64")
    ap.add_argument("--check", default="",
                    help="NAME:T,... variants measured on T threads, to hold the model against")
    ap.add_argument("--interval", type=int,
                    help="predict at this coupling interval N (default: the runs' own)")
    args = ap.parse_args()
    if args.interval is not None and args.interval < 1:
        sys.exit("scaling_model: --interval %d: expected N >= 1" % args.interval)
    try:
        check = [(n, int(t)) for n, t in (c.split(":") for c in args.check.split(",") if c)]
    except ValueError:
        sys.exit("scaling_model: --check %r: expected NAME:THREADS[,NAME:THREADS...]" % args.check)
    with open(args.results) as f:
        results = json.load(f)
    cores = [int(c) for c in args.cores.split(",")]
    groups = {}
    for r in results:
        groups.setdefault((r["scene"], r["depth_m"]), {}).setdefault(r["variant"], []).append(r)
    if not groups:
        sys.exit("scaling_model: no runs in %s" % args.results)
    for (scene, depth), variants in sorted(groups.items()):
        if args.one not in variants or args.two not in variants:
            print("%s at %g m: no %s and %s runs" % (scene, depth, args.one, args.two))
            continue
        one, two = per_step(variants[args.one]), per_step(variants[args.two])
        runs_interval = measured_interval(variants[args.one] + variants[args.two])
        interval = args.interval or runs_interval
        if interval != runs_interval:
            one = at_interval(one, runs_interval, interval)
            two = at_interval(two, runs_interval, interval)
            print("%s at %g m: measured at N = %d, predicted at N = %d (the measured columns "
                  "are N = %d's)" % (scene, depth, runs_interval, interval, runs_interval))
        parts = model(one, two)
        base = step_cost(parts, 1)
        print("%s at %g m: %.3f ms/step on 1 thread (measured %.3f), %.3f on 2 (measured %.3f)" % (
            scene, depth, 1e3 * base,
            1e3 * statistics.median(r["wall_s"] / r["steps"] for r in variants[args.one]),
            1e3 * step_cost(parts, 2),
            1e3 * statistics.median(r["wall_s"] / r["steps"] for r in variants[args.two])))
        serial = sum(s for s, _, _ in parts.values())
        print("  serial part %.3f ms/step (service %.3f, rest %.3f); parallel %.3f ms/step" % (
            1e3 * serial, 1e3 * parts["service"][0], 1e3 * parts["rest"][0],
            1e3 * sum(q for _, q, _ in parts.values())))
        for c in cores:
            t = step_cost(parts, c)
            print("  %3d cores: %.3f ms/step, %.1f times one thread" % (c, 1e3 * t, base / t))
        for name, threads in check:
            if name not in variants:
                print("  %s: not measured" % name)
                continue
            at = measured_interval(variants[name])
            if at != interval:
                print("  %s: measured at N = %d, not at %d" % (name, at, interval))
                continue
            measured = statistics.median(r["wall_s"] / r["steps"] for r in variants[name])
            t = step_cost(parts, threads)
            print("  %s on %d threads: model %.3f ms/step, measured %.3f (model/measured %.2f)" % (
                name, threads, 1e3 * t, 1e3 * measured, t / measured))


if __name__ == "__main__":
    main()
