"""Calibration against Table 1's outputs (UCS 13.8 MPa, BTS 2.55 MPa, E 5.5 GPa, nu 0.22).

With --target, finds the micro-parameters for a rock's properties instead (calibrate_target.py;
`rockcut calibrate --target ucs=13.8MPa,bts=2.55MPa,E=5.5GPa,nu=0.22 --out DIR`). Without it,
evaluates the parameter sets given:

Runs the UCS and Brazilian scenes for each parameter set on several specimen seeds, concurrently,
and writes
  OUT/calibration_runs.csv  one row per set and seed;
  OUT/calibration.csv       per set: the mean over the seeds, its standard error, and the
                            deviation of the mean from Table 1.
Without --no-defaults the sets include the scenes as they are (the calibrated set), Table 1 as
printed and Table 1 with K_n and K_s swapped (DESIGN section 4). Each further set is a NAME and its
--set options in one argument, applied to both scenes. --fracture also runs the fracture test
(cases/calibration/fracture.pbtxt) of every set and seed, and adds its work of fracture [J/m^2] and
net tensile strength [MPa] to both tables (Table 1 gives neither: no deviation).

  rockcut calibrate out/calibration
  rockcut calibrate out/cal --seeds 1,2,3,4,5 --no-defaults tuned \\
      "--set dem.bonds.tensile_strength_n_per_m=1.3e4 --set dem.loading_test.platen_speed_m_s=0.01"

One UCS run takes 30-60 s, one Brazilian run about 25 s and one fracture test 5-15 s on one core.
"""
import argparse
import concurrent.futures
import csv
import math
import os
import shlex

from . import campaign, runs
from .run_data import read_summary
from .stats import mean_and_error

TABLE1 = {"ucs_mpa": 13.8, "youngs_modulus_gpa": 5.5, "poisson_ratio": 0.22, "bts_mpa": 2.55}
# --fracture: measured, with no target.
FRACTURE = ("fracture_energy_j_per_m2", "net_tensile_strength_mpa")
STRENGTHS = ("--set dem.bonds.tensile_strength_n_per_m=1e4 "
             "--set dem.bonds.shear_strength_n_per_m=2e4")
PRINTED = ("--set dem.bonds.normal_stiffness_pa=1e10 --set dem.bonds.shear_stiffness_pa=2.5e10 "
           "--set dem.contact.normal_stiffness_pa=1e10 --set dem.contact.shear_stiffness_pa=2.5e10 "
           + STRENGTHS)
SWAP = ("--set dem.bonds.normal_stiffness_pa=2.5e10 --set dem.bonds.shear_stiffness_pa=1e10 "
        "--set dem.contact.normal_stiffness_pa=2.5e10 --set dem.contact.shear_stiffness_pa=1e10 "
        + STRENGTHS)


def set_options(text):
    """"--set a=1 --set b=2" -> ["a=1", "b=2"]."""
    words = shlex.split(text)
    if len(words) % 2 or any(w != "--set" for w in words[0::2]):
        raise SystemExit(f"rockcut calibrate: expected --set PATH=VALUE pairs, got '{text}'")
    return words[1::2]


def run_one(out, name, sets, seed, test, coupler=None):
    """One coupler run; returns the summary.json of it."""
    run_dir = os.path.join(out, name, f"seed{seed}", test)
    p = runs.run(runs.case("calibration", f"{test}.pbtxt"), run_dir,
                 [f"dem.specimen.seed={seed}"] + set_options(sets), coupler, log=run_dir + ".log")
    if p.returncode != 0:
        raise RuntimeError(f"{test} of {name}, seed {seed} exited with {p.returncode}; "
                           f"see {run_dir}.log")
    return read_summary(run_dir)


def main(arguments):
    if any(a == "--target" or a.startswith("--target=") for a in arguments):
        from . import calibrate_target
        return calibrate_target.main(arguments)
    parser = argparse.ArgumentParser(prog="rockcut calibrate", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="output directory")
    parser.add_argument("sets", nargs="*", help="NAME \"--set a=b ...\" pairs")
    parser.add_argument("--seeds", default="1,2,3", help="specimen seeds (default 1,2,3)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                        help="runs at once (default: the number of cores)")
    parser.add_argument("--no-defaults", action="store_true",
                        help="skip the scenes', the as-printed and the swapped sets")
    parser.add_argument("--fracture", action="store_true",
                        help="also run the fracture test: work of fracture and net strength")
    # A set's options start with "--set", which argparse would take for an option of this script:
    # pass every argument that is not one of this script's options as a positional one.
    argv, rest = [], []
    it = iter(arguments)
    for a in it:
        if a in ("-h", "--help", "--no-defaults", "--fracture"):
            argv.append(a)
        elif a in ("--seeds", "--jobs"):
            argv += [a, next(it, "")]
        elif a.startswith(("--seeds=", "--jobs=")):
            argv.append(a)
        else:
            rest.append(a)
    args = parser.parse_args(argv + ["--"] + rest)
    if len(args.sets) % 2:
        parser.error("each extra set is a NAME followed by its --set options in one argument")
    try:
        seeds = [int(s) for s in args.seeds.split(",")]
    except ValueError:
        parser.error(f"--seeds: a comma-separated list of integers, got '{args.seeds}'")
    coupler = runs.coupler()

    sets = [] if args.no_defaults else [("scenes", ""), ("as_printed", PRINTED), ("swapped", SWAP)]
    sets += list(zip(args.sets[0::2], args.sets[1::2]))
    for name, _ in sets:
        for seed in seeds:
            os.makedirs(os.path.join(args.out, name, f"seed{seed}"), exist_ok=True)

    jobs = {}
    tests = ("ucs", "brazilian") + (("fracture",) if args.fracture else ())
    runs.side_by_side(args.jobs)
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for name, opts in sets:
            for seed in seeds:
                for test in tests:
                    jobs[(name, seed, test)] = pool.submit(run_one, args.out, name, opts, seed, test, coupler)
        results = {key: job.result() for key, job in jobs.items()}

    nan = math.nan
    rows = []
    for name, opts in sets:
        for seed in seeds:
            u, b = results[(name, seed, "ucs")], results[(name, seed, "brazilian")]
            row = {"set": name, "seed": seed,
                   "ucs_mpa": u["ucs_pa"] / 1e6,
                   "youngs_modulus_gpa": u.get("youngs_modulus_pa", nan) / 1e9,
                   "poisson_ratio": u.get("poisson_ratio", nan),
                   "bts_mpa": b["bts_pa"] / 1e6,
                   "split_detected": b.get("split_detected", False)}
            if args.fracture:
                g = results[(name, seed, "fracture")]
                row.update({"fracture_energy_j_per_m2": g["fracture_energy_j_per_m2"],
                            "net_tensile_strength_mpa": g["net_tensile_strength_pa"] / 1e6,
                            "separated": g.get("separated", False)})
            row["wall_time_s"] = sum(results[(name, seed, t)]["wall_time_s"] for t in tests)
            row["overrides"] = opts
            rows.append(row)
    campaign.write_rows(os.path.join(args.out, "calibration_runs.csv"), rows)

    summary = os.path.join(args.out, "calibration.csv")
    with open(summary, "w", newline="") as f:
        w = csv.writer(f)
        header = ["set", "seeds"]
        measured = FRACTURE if args.fracture else ()
        for key in TABLE1:
            header += [key, key + "_stderr", key + "_deviation"]
        for key in measured:
            header += [key, key + "_stderr"]
        header += ["overrides"]
        w.writerow(header)
        print(f"{'set':<14}" + "".join(f"{k:>30}" for k in TABLE1)
              + "".join(f"{k:>26}" for k in measured))
        for name, opts in sets:
            mine = [r for r in rows if r["set"] == name]
            row, line = [name, len(mine)], f"{name:<14}"
            for key, target in TABLE1.items():
                m, e = mean_and_error([r[key] for r in mine])
                dev = m / target - 1.0
                row += [f"{m:.4g}", f"{e:.2g}", f"{dev:+.3f}"]
                line += f"{m:>12.3g} +- {e:<7.2g}({dev:+6.1%})"
            for key in measured:
                m, e = mean_and_error([r[key] for r in mine])
                row += [f"{m:.4g}", f"{e:.2g}"]
                line += f"{m:>15.3g} +- {e:<7.2g}"
            w.writerow(row + [opts])
            print(line)
        print(f"{'Table 1':<14}" + "".join(f"{v:>12.3g}{'':>18}" for v in TABLE1.values()))
    print(f"wrote {summary} and calibration_runs.csv")

