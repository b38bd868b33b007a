"""The rock's Mohr-Coulomb envelope from biaxial (confined) compression tests.

Runs cases/calibration/biaxial.pbtxt at each confining stress and a UCS test
(cases/calibration/ucs.pbtxt) on each specimen seed, side by side, and fits
sigma_1 = sigma_c + k sigma_3 to the peak and to the residual strengths (mohr_coulomb.py): the
cohesion c and friction angle phi on each seed, their means and standard errors over the seeds,
and the check that the UCS measured on the same seeds agrees with the envelope's
sigma_c = 2 c cos(phi) / (1 - sin(phi)) (paired over the seeds: their difference within two
standard errors). Writes
  OUT/envelope_runs.csv   one row per run
  OUT/envelope.json       the fits and the check
  OUT/rock_block.pbtxt    the rock { } lines for the analytical cutting models
  OUT/envelope.png        the strengths of each seed and the fitted lines
A run already finished in OUT is not run again. `--scheduler slurm` runs them as Slurm job arrays
(one per test and confining stress) and waits for them.

  rockcut envelope out/envelope                       # the default rock, 1, 2, 4 MPa, seeds 1-4
  rockcut envelope out/env --rock cases/rock/my_rock.pbtxt --confining-mpa 2,5,10 --seeds 1,2,3

One biaxial run of the default rock takes 25-40 s on one core.
"""
import argparse
import json
import math
import os

from . import campaign, mohr_coulomb, rock_tests, runs
from .run_data import scalar_fields
from .stats import mean_and_error


def parse_numbers(text, what):
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise SystemExit(f"rockcut envelope: {what}: a comma-separated list of numbers, got '{text}'")
    if not values:
        raise SystemExit(f"rockcut envelope: {what}: give at least one value")
    return values


def fit(points):
    """Mohr-Coulomb fit of [(sigma_3, sigma_1)] [Pa] -> dict of sigma_c, k, c, phi_deg (NaN with
    fewer than two distinct confining stresses)."""
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    try:
        a, b, a_se, b_se = mohr_coulomb.line_fit(xs, ys)
    except ValueError:
        return {"sigma_c_pa": math.nan, "k": math.nan, "cohesion_pa": math.nan,
                "friction_angle_deg": math.nan, "sigma_c_se_pa": math.nan, "k_se": math.nan}
    c, phi = mohr_coulomb.from_line(a, b)
    return {"sigma_c_pa": a, "k": b, "cohesion_pa": c, "friction_angle_deg": phi,
            "sigma_c_se_pa": a_se, "k_se": b_se}


def summarise(per_seed, pooled):
    """Means and standard errors over the seeds of each fitted value; with one seed the pooled
    least-squares fit and its errors (none for c and phi)."""
    pooled_se = {"sigma_c_pa": pooled["sigma_c_se_pa"], "k": pooled["k_se"]}
    out = {}
    for key in ("sigma_c_pa", "k", "cohesion_pa", "friction_angle_deg"):
        if len(per_seed) < 2:
            out[key], out[key + "_se"] = pooled[key], pooled_se.get(key, math.nan)
        else:
            out[key], out[key + "_se"] = mean_and_error([f[key] for f in per_seed.values()])
    return out


def default_confining_mpa(ucs_scene, coupler):
    """7.5, 15 and 30 % of the rock's UCS (its rock.ucs_pa), to one digit: the same share of the
    strength for a weak and a strong rock (1, 2 and 4 MPa for the default rock). 1, 2 and 4 MPa
    when the rock gives no UCS."""
    ucs = scalar_fields(runs.effective_scene(ucs_scene, [], coupler), "rock").get("ucs_pa")
    if not ucs:
        return [1.0, 2.0, 4.0]
    return [float(f"{f * ucs / 1e6:.1g}") for f in (0.075, 0.15, 0.3)]


def draw(path, seeds, ucs, peak, residual, report):
    """envelope.png: each seed's UCS, confined peaks and residual strengths, and the fitted mean
    lines sigma_1 = sigma_c + k sigma_3 of the peak and the residual."""
    from .figures import plt  # only here: the verb's runs need no matplotlib
    fig, ax = plt.subplots(figsize=(6, 4.5))
    top = max(x for p in peak.values() for x, _ in p) * 1.05
    for name, points, colour in (("peak", peak, "C0"), ("residual", residual, "C1")):
        xs = [x / 1e6 for s in seeds for x, _ in points[s]]
        ys = [y / 1e6 for s in seeds for _, y in points[s]]
        ax.plot(xs, ys, "o", color=colour, alpha=0.6, label=f"{name}, each seed")
        e = report[name]
        if e["k"] == e["k"]:
            ax.plot([0, top / 1e6], [e["sigma_c_pa"] / 1e6, (e["sigma_c_pa"] + e["k"] * top) / 1e6],
                    "-", color=colour, label=f"{name}: c {e['cohesion_pa'] / 1e6:.3g} MPa, "
                                               f"phi {e['friction_angle_deg']:.3g} deg")
    ax.plot([0] * len(seeds), [ucs[s] / 1e6 for s in seeds], "s", color="C2", label="UCS test")
    ax.set_xlabel("confining stress sigma_3 [MPa]")
    ax.set_ylabel("axial stress sigma_1 [MPa]")
    ax.set_xlim(left=-0.05 * top / 1e6)
    ax.legend(fontsize=8)
    ax.set_title("Mohr-Coulomb envelope (rockcut envelope)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv):
    parser = argparse.ArgumentParser(prog="rockcut envelope", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="output folder")
    parser.add_argument("--rock", default=None,
                        help="rock file (cases/rock/*.pbtxt; default: the default rock)")
    parser.add_argument("--confining-mpa", default=None,
                        help="confining stresses [MPa], two or more above 0 (default: 7.5, 15 and "
                             "30 %% of the rock's rock.ucs_pa, one digit; 1,2,4 without it)")
    rock_tests.add_run_options(parser, "a scene override for every run (repeatable)")
    args = parser.parse_args(argv)
    slurm_options = rock_tests.slurm_options(args)
    seeds = args.seeds
    rock = args.rock or runs.case("rock", "default_rock.pbtxt")
    if not os.path.isfile(rock):
        parser.error(f"--rock: no file {rock}")
    os.makedirs(args.out, exist_ok=True)
    scenes = rock_tests.write_scenes(args.out, rock)
    if args.confining_mpa is None:
        confining = default_confining_mpa(scenes["ucs"], args.coupler)
    else:
        confining = parse_numbers(args.confining_mpa, "--confining-mpa")
    if len(set(confining)) < 2 or min(confining) <= 0:
        parser.error("--confining-mpa: two or more different stresses above 0 (the UCS test is "
                     "run beside them as the check)")

    jobs = []
    for seed in seeds:
        base = [f"dem.specimen.seed={seed}"] + args.set
        jobs.append((os.path.join(args.out, "ucs", f"seed={seed}"), scenes["ucs"], base))
        for s3 in confining:
            jobs.append((os.path.join(args.out, f"biaxial_{s3:g}mpa", f"seed={seed}"),
                         scenes["biaxial"],
                         base + [f"dem.loading_test.confining_stress_pa={s3 * 1e6:.6g}"]))
    print(f"envelope: {len(jobs)} runs ({len(seeds)} seeds x {len(confining)} confining stresses "
          f"+ UCS), {args.jobs} at a time, in {args.out}", flush=True)
    results = rock_tests.run_all(jobs, args.jobs, args.coupler, slurm_options)

    rows, peak, residual, ucs = [], {}, {}, {}
    for seed in seeds:
        u = results[os.path.join(args.out, "ucs", f"seed={seed}")]
        ucs[seed] = u["ucs_pa"]
        rows.append({"seed": seed, "test": "ucs", "confining_target_mpa": 0.0,
                     "confining_mpa": 0.0, "peak_axial_mpa": u["ucs_pa"] / 1e6,
                     "residual_axial_mpa": math.nan, "wall_time_s": u["wall_time_s"]})
        peak[seed], residual[seed] = [], []
        for s3 in confining:
            b = results[os.path.join(args.out, f"biaxial_{s3:g}mpa", f"seed={seed}")]
            peak[seed].append((b["confining_stress_pa"], b["peak_axial_stress_pa"]))
            if "residual_axial_stress_pa" in b:
                residual[seed].append((b["confining_stress_pa"], b["residual_axial_stress_pa"]))
            rows.append({"seed": seed, "test": "biaxial", "confining_target_mpa": s3,
                         "confining_mpa": b["confining_stress_pa"] / 1e6,
                         "peak_axial_mpa": b["peak_axial_stress_pa"] / 1e6,
                         "residual_axial_mpa": b.get("residual_axial_stress_pa", math.nan) / 1e6,
                         "wall_time_s": b["wall_time_s"]})
    campaign.write_rows(os.path.join(args.out, "envelope_runs.csv"), rows)

    report = {"rock": os.path.abspath(rock), "seeds": seeds, "confining_mpa": confining,
              "set": args.set}
    for name, points in (("peak", peak), ("residual", residual)):
        per_seed = {s: fit(p) for s, p in points.items()}
        pooled = fit([x for p in points.values() for x in p])
        report[name] = summarise(per_seed, pooled)
        report[name]["per_seed"] = {str(s): f for s, f in per_seed.items()}
    # The check: the measured UCS against the peak envelope's sigma_c, paired seed by seed.
    diffs = [ucs[s] - report["peak"]["per_seed"][str(s)]["sigma_c_pa"] for s in seeds]
    d, d_se = mean_and_error(diffs)
    if len(seeds) < 2:
        d_se = report["peak"]["sigma_c_pa_se"]
    u_mean, u_se = mean_and_error(list(ucs.values()))
    report["ucs_check"] = {"ucs_pa": u_mean, "ucs_se_pa": u_se,
                           "envelope_sigma_c_pa": report["peak"]["sigma_c_pa"],
                           "difference_pa": d, "difference_se_pa": d_se,
                           "consistent": bool(abs(d) <= 2 * d_se) if d_se == d_se else None}
    with open(os.path.join(args.out, "envelope.json"), "w") as f:
        json.dump(report, f, indent=1)

    p, r, chk = report["peak"], report["residual"], report["ucs_check"]
    print(f"{'envelope':<10}{'sigma_c [MPa]':>20}{'k':>16}{'c [MPa]':>18}{'phi [deg]':>18}")
    for name, e in (("peak", p), ("residual", r)):
        print(f"{name:<10}{e['sigma_c_pa'] / 1e6:>11.3f} +- {e['sigma_c_pa_se'] / 1e6:<6.2g}"
              f"{e['k']:>8.3f} +- {e['k_se']:<5.2g}{e['cohesion_pa'] / 1e6:>9.3f} +- "
              f"{e['cohesion_pa_se'] / 1e6:<6.2g}{e['friction_angle_deg']:>9.2f} +- "
              f"{e['friction_angle_deg_se']:<6.2g}")
    verdict = {True: "consistent", False: "NOT consistent", None: "not resolved"}[chk["consistent"]]
    print(f"UCS {chk['ucs_pa'] / 1e6:.3f} +- {chk['ucs_se_pa'] / 1e6:.2g} MPa against the peak "
          f"envelope's 2 c cos(phi) / (1 - sin(phi)) = {p['sigma_c_pa'] / 1e6:.3f} MPa: difference "
          f"{d / 1e6:+.3f} +- {d_se / 1e6:.2g} MPa over the seeds, {verdict} (two standard errors)")
    if p["k"] < 1:
        print("note: k < 1, the peak strength grows more slowly than the confining stress (a "
              "negative friction angle): the bonds' shear strength does not grow under "
              "compression (dem.bonds.friction_angle_deg 0, the paper's bond); "
              "docs/calibration.md, \"The Mohr-Coulomb envelope\"")
    with open(os.path.join(args.out, "rock_block.pbtxt"), "w") as f:
        f.write(f"# rockcut envelope {' '.join(argv)}\n# the peak envelope over seeds "
                f"{','.join(map(str, seeds))}: c {p['cohesion_pa']:.4g} +- "
                f"{p['cohesion_pa_se']:.2g} Pa, phi {p['friction_angle_deg']:.4g} +- "
                f"{p['friction_angle_deg_se']:.2g} deg\n"
                f"rock {{\n  cohesion_pa: {p['cohesion_pa']:.4g}\n"
                f"  friction_angle_deg: {max(p['friction_angle_deg'], 0.0):.4g}"
                + ("  # the fit's angle is negative; the field's least is 0"
                   if p["friction_angle_deg"] < 0 else "") + "\n}\n")
    draw(os.path.join(args.out, "envelope.png"), seeds, ucs, peak, residual, report)
    print(f"wrote {os.path.join(args.out, 'envelope.json')}, envelope_runs.csv, rock_block.pbtxt "
          "and envelope.png")
    return 0
