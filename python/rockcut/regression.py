"""Regression cases: reduced scenes whose summary.json values are kept as references.

  rockcut regression check NAME [--coupler PATH]   run the case and compare with its reference
                                                  (what ctest runs: regression.NAME)
  rockcut regression update [NAME ...] [--seeds 1,2,3,4] [--threads 1,2] [--jobs 2]
                                                  run each case over specimen seeds and thread
                                                  counts and store the centre and the width of
                                                  each key's range as reference and tolerance
  rockcut regression spread ...                   the same (its former name)

A case is tests/regression/NAME.json:
  scene            the scene file, relative to the repository
  set              --set overrides that make it short (e.g. a shorter cut)
  keys             the summary.json keys compared
  values           the reference values: the centre of each key's range over the runs
  tolerance_abs    per key: |value - reference| allowed, the width of that range
  spread           how they were measured (runs, min, max per key)
The check runs the scene as given (its seed and threads) and passes when every key lies within
the measured range widened by half its width on each side.

Why these tolerances: a given seed and thread count reproduce a run bit for bit, but any change of
round-off (another thread count, a reordered sum) grows chaotically through the bond breaks into
a different crack path, as another specimen seed does. So a code change that is exact in
arithmetic still moves every value by the natural scatter of the cut, and the test can only
detect changes beyond it. The runs over seeds 1-4 and 1 and 2 threads (8) sample that scatter.
For a value spread normally with deviation s, the range of 8 runs is about 2.85 s, so the window
is about +-2.85 s around the centre: an equivalent run falls outside it with probability about
0.4 % per key, 3 % for a case of 8 keys, while a shift of the mean by more than about 3 s fails.
(The earlier window, the range around the one run of the scene as given, failed an equivalent
run with probability about 8 % per key: half of all exact-arithmetic changes tripped a case.)
The floor of 1 % of the reference (and 1 for counts) keeps a key that happened not to vary in
the measured runs from failing on round-off.

The cases run over the inproc transport: every transport gives the same bits (the tests
CoupledRun.TransportsGiveBitIdenticalResults and SharedMemory.PaperScaleCut...), and on these
scenes inproc takes about two thirds of the wall of ipc, whose every message wakes a ZeroMQ I/O
thread on each side (docs/performance.md, "Transports").
"""
import argparse
import concurrent.futures
import json
import os
import sys
import tempfile

from . import runs
from .run_data import read_summary

CASES = os.path.join(runs.REPO, "tests", "regression")
TRANSPORT = "inproc"  # the same bits as ipc, quicker on reduced scenes (above)


def case_path(name):
    return os.path.join(CASES, name + ".json")


def load_case(name):
    with open(case_path(name)) as f:
        return json.load(f)


def save_case(name, case):
    with open(case_path(name), "w") as f:
        json.dump(case, f, indent=2, sort_keys=False)
        f.write("\n")


def all_names():
    return sorted(f[:-5] for f in os.listdir(CASES) if f.endswith(".json"))


def run_case(case, coupler, extra_sets=()):
    """Runs the case's scene with its overrides; returns the summary as a dict."""
    with tempfile.TemporaryDirectory(prefix="rockcut-regression-") as out:
        sets = list(case.get("set", [])) + list(extra_sets)
        proc = runs.run(os.path.join(runs.REPO, case["scene"]), out, sets, coupler, TRANSPORT)
        if proc.returncode != 0:
            raise RuntimeError("%s exited with %d:\n%s" % (
                " ".join(runs.command(case["scene"], out, sets, coupler, TRANSPORT)),
                proc.returncode,
                proc.stderr[-2000:]))
        return read_summary(out)


def check(name, coupler):
    case = load_case(name)
    summary = run_case(case, coupler)
    failures = []
    print("regression %s: %s %s" % (name, case["scene"], " ".join("--set " + s for s in case["set"])))
    for key in case["keys"]:
        ref = case["values"][key]
        tol = case["tolerance_abs"][key]
        value = summary.get(key)
        ok = value is not None and abs(value - ref) <= tol
        print("  %-32s %14.6g  reference %14.6g  +- %-12.4g %s" %
              (key, value if value is not None else float("nan"), ref, tol, "ok" if ok else "MOVED"))
        if not ok:
            failures.append(key)
    if failures:
        print("regression %s: %d value(s) moved beyond the seed/thread spread: %s\n"
              "  If the change is intended, re-measure the references: scripts/rockcut regression update %s"
              % (name, len(failures), ", ".join(failures), name))
        return 1
    print("regression %s: all %d values within their tolerances" % (name, len(case["keys"])))
    return 0


def measure(names, coupler, seeds, threads, jobs):
    runs.side_by_side(jobs)
    for name in names:
        case = load_case(name)
        variants = [("dem.specimen.seed=%d" % s, "dem.threads=%d" % t) for s in seeds for t in threads]
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            summaries = list(pool.map(lambda v: run_case(case, coupler, v), variants))
        stats, tolerance, centre = {}, {}, {}
        for key in case["keys"]:
            values = [s[key] for s in summaries]
            lo, hi = min(values), max(values)
            centre[key] = 0.5 * (lo + hi)
            is_count = all(isinstance(v, int) for v in values)
            floor = max(0.01 * abs(centre[key]), 1.0 if is_count else 0.0)
            tolerance[key] = max(hi - lo, floor)
            stats[key] = {"min": lo, "max": hi}
        case["values"] = centre
        case["tolerance_abs"] = tolerance
        case["spread"] = {"runs": ["%s, %s" % v for v in variants], "per_key": stats,
                          "command": "scripts/rockcut regression update %s --seeds %s --threads %s" %
                          (name, ",".join(map(str, seeds)), ",".join(map(str, threads)))}
        save_case(name, case)
        print("regression %s: reference and tolerance from %d runs" % (name, len(variants)))
        for key in case["keys"]:
            print("  %-32s reference %12.5g  range [%12.5g, %12.5g]" %
                  (key, case["values"][key], stats[key]["min"], stats[key]["max"]))
    return 0


def main(argv):
    parser = argparse.ArgumentParser(prog="rockcut regression", description=__doc__.split("\n")[0])
    parser.add_argument("command", choices=["check", "update", "spread"])
    parser.add_argument("names", nargs="*")
    parser.add_argument("--coupler", help="the coupler to run (default build/bin/coupler)")
    parser.add_argument("--seeds", default="1,2,3,4")
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(argv)
    args.coupler = runs.coupler(args.coupler)
    names = args.names or all_names()
    for n in names:
        if not os.path.exists(case_path(n)):
            parser.error("no regression case %s (have: %s)" % (n, ", ".join(all_names())))
    try:
        if args.command == "check":
            return max(check(n, args.coupler) for n in names)
        return measure(names, args.coupler, [int(s) for s in args.seeds.split(",")],
                      [int(t) for t in args.threads.split(",")], args.jobs)
    except RuntimeError as e:
        print("regression: " + str(e), file=sys.stderr)
        return 1

