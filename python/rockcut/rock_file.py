"""The rock files `rockcut calibrate --target` writes: the fine one (`base:` the starting rock,
the micro-parameters found, the measured UCS and BTS in its `rock { }` block) and its coarse twin
beside it, the discs and the bond strengths scaled together."""
import math
import os
import re

from .calibration_targets import PROPERTIES, fmt

def base_of(rock_file):
    """The `base:` a rock file names, or None."""
    with open(rock_file) as f:
        m = re.search(r'^base:\s*"([^"]*)"', f.read(), flags=re.M)
    return m.group(1) if m else None


def write_rock(path, start_rock, params, targets, means, errors, seeds, command, coarse_factor,
               damping=None):
    """The fine rock file and the coarse one beside it. The fine one's base is the starting rock;
    written over the starting rock itself (regenerating a shipped rock), it keeps that file's own
    base and writes the disc sizes, density and grain friction it held. `damping`: the body of the
    `damping { }` block the loading tests ran under, when they set one; the rock file carries it,
    since a rock's strengths hold only under the damping they were calibrated with (docs/model.md,
    "Damping")."""
    path = os.path.abspath(path)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    over_start = path == os.path.abspath(start_rock)
    if over_start:
        base = base_of(start_rock)
    else:
        base = os.path.relpath(os.path.abspath(start_rock), os.path.dirname(path))
    kn, ks = params["kn"], params["kn"] * params["ks_ratio"]
    tn, ts = params["tn"], params["tn"] * params["ts_ratio"]
    lines = [f"# A rock calibrated by `{command}`",
             f"# on specimen seeds {','.join(map(str, seeds))} (mean +- standard error, deviation "
             "from the target):"]
    for name in PROPERTIES:
        if name in means and means[name] == means[name]:
            dev = f", {means[name] / targets[name] - 1:+.1%}" if name in targets else ""
            lines.append(f"#   {name}: {fmt(name, means[name])} +- {fmt(name, errors[name])}{dev}")
    stem = path[:-len(".pbtxt")] if path.endswith(".pbtxt") else path
    coarse = stem + "_coarse.pbtxt"
    lines += ["# Not a scene on its own: a scene uses it as its `base:`. The coarse discs: "
              f"{os.path.basename(coarse)}.",
              *([f'base: "{base}"'] if base else []), "",
              "dem {"]
    if over_start:
        lines += [f"  specimen {{ radius_min_m: {params['radius_min_m']:.6g} "
                  f"radius_max_m: {params['radius_max_m']:.6g} }}"]
        if params.get("density_kg_m3"):
            lines += [f"  density_kg_m3: {params['density_kg_m3']:.6g}"]
    friction = (f" friction: {params['friction']:.6g}"
                if over_start and params.get("friction") is not None else "")
    lines += [f"  contact {{ normal_stiffness_pa: {kn:.4g} shear_stiffness_pa: {ks:.4g}{friction} }}",
              "  bonds {",
              f"    normal_stiffness_pa: {kn:.4g}", f"    shear_stiffness_pa: {ks:.4g}",
              f"    tensile_strength_n_per_m: {tn:.4g}", f"    shear_strength_n_per_m: {ts:.4g}",
              f"    friction_angle_deg: {params['phi_b_deg']:.4g}"]
    if params.get("softening", 0.0) > 0 or "gf" in targets:
        lines += [f"    softening_ratio: {params.get('softening', 0.0):.4g}"]
    lines += ["  }"]
    if damping:
        lines += ["  # the damping the loading tests ran under: the strengths above hold under it",
                  f"  damping {{ {' '.join(damping.split())} }}"]
    lines += ["}", ""]
    ucs, bts, phi = means["ucs"], means["bts"], means.get("phi", math.nan)
    if phi == phi:  # measured: the envelope through the UCS and the confined test
        c = ucs * (1 - math.sin(math.radians(phi))) / (2 * math.cos(math.radians(phi)))
        source = ["# c and phi of the straight envelope through the UCS and the confined test the",
                  "# calibration ran (`rockcut envelope` fits one over more confining stresses)."]
    else:
        phi = math.degrees(math.asin((ucs - bts) / (ucs + bts)))
        c = math.sqrt(ucs * bts) / 2
        source = ["# c and phi of the straight envelope tangent to the UCS and BTS circles (Paul 1961,",
                  "# as default_rock.pbtxt); `rockcut envelope` measures the DEM rock's own (its c and",
                  "# phi in place of these: docs/cutting_models.md)."]
    lines += ["# For the analytical cutting models (the DEM does not read it): the measured UCS and BTS;"]
    lines += source + ["rock {", f"  ucs_pa: {ucs:.4g}", f"  bts_pa: {bts:.4g}",
                       f"  cohesion_pa: {c:.4g}", f"  friction_angle_deg: {max(phi, 0.0):.4g}", "}", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))
    with open(coarse, "w") as f:
        f.write("\n".join([
            f"# {os.path.basename(path)} on discs {coarse_factor:g} times as large, for reduced scenes. "
            "Not a scene on its own.",
            "# The bond strengths scale with the radius (a 2D bond's strength acts over about one",
            "# diameter), the stiffnesses (Pa) do not: the macro properties stay "
            "(default_rock_coarse.pbtxt).",
            f'base: "{os.path.basename(path)}"', "",
            "dem {",
            f"  specimen {{ radius_min_m: {params['radius_min_m'] * coarse_factor:.4g} "
            f"radius_max_m: {params['radius_max_m'] * coarse_factor:.4g} }}",
            f"  bonds {{ tensile_strength_n_per_m: {tn * coarse_factor:.4g} "
            f"shear_strength_n_per_m: {ts * coarse_factor:.4g} }}", "}", ""]))
    return path, coarse


