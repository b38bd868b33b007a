"""What `rockcut calibrate --target` is asked for, and whether the bonded discs can give it: the
targets parsed from the command line (one clear line for a malformed or unphysical one), and the
reachable ranges of cases/rock/bonded_disc_structure.json checked before any run."""
import json
import re

from . import runs

UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}
# phi: the peak friction angle of the Mohr-Coulomb envelope through the UCS and one confined test;
# gf: the work of fracture of the fracture test (cases/calibration/fracture.pbtxt).
PROPERTIES = {"ucs": "ucs_pa", "bts": "bts_pa", "E": "youngs_modulus_pa", "nu": "poisson_ratio",
              "phi": "friction_angle_deg", "gf": "fracture_energy_j_per_m2"}
SHOWN = {"ucs": (1e6, "MPa"), "bts": (1e6, "MPa"), "E": (1e9, "GPa"), "nu": (1.0, ""),
         "phi": (1.0, "deg"), "gf": (1.0, "J/m^2")}


def fail(message):
    raise SystemExit(f"rockcut calibrate: {message}")


def parse_targets(text):
    """'ucs=13.8MPa,bts=2.55MPa,E=5.5GPa,nu=0.22' -> {name: value in Pa (nu: 1)}; one clear line
    (SystemExit) for an unknown name, a missing or unknown unit, or an unphysical value."""
    targets = {}
    for item in [t.strip() for t in text.split(",") if t.strip()]:
        name, eq, value = item.partition("=")
        name = name.strip()
        if not eq:
            fail(f"--target: '{item}' is not NAME=VALUE (names: {', '.join(PROPERTIES)})")
        if name not in PROPERTIES:
            near = [p for p in PROPERTIES if p.lower() == name.lower()]
            fail(f"--target: unknown property '{name}'"
                 + (f" (did you mean '{near[0]}'?)" if near else "")
                 + f"; allowed: {', '.join(PROPERTIES)}")
        if name in targets:
            fail(f"--target: '{name}' is given twice")
        m = re.fullmatch(r"\s*([-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?)\s*([A-Za-z/^0-9]*)\s*", value)
        if not m:
            fail(f"--target: {name}: '{value}' is not a number")
        number, unit = float(m.group(1)), m.group(2)
        if name == "nu":
            if unit:
                fail(f"--target: nu has no unit, got '{value}'")
            if not 0.0 < number < 0.5:
                fail(f"--target: nu = {number:g} is outside 0 < nu < 0.5")
            targets[name] = number
            continue
        if name == "gf":
            if unit not in ("J/m2", "J/m^2"):
                fail(f"--target: gf={value} needs the unit J/m2, e.g. gf=60J/m2")
            if number <= 0:
                fail(f"--target: gf = {value} must be above 0")
            targets[name] = number
            continue
        if name == "phi":
            if unit != "deg":
                fail(f"--target: phi={value} needs the unit deg, e.g. phi=20deg")
            if not 0.0 < number < 90.0:
                fail(f"--target: phi = {number:g} deg is outside 0 < phi < 90")
            targets[name] = number
            continue
        if not unit:
            fail(f"--target: {name}={value} needs a unit ({', '.join(UNITS)})")
        if unit not in UNITS:
            fail(f"--target: {name}: unknown unit '{unit}' (allowed: {', '.join(UNITS)})")
        if number <= 0:
            fail(f"--target: {name} = {value} must be above 0")
        targets[name] = number * UNITS[unit]
    if not targets:
        fail("--target: give at least one of " + ", ".join(PROPERTIES))
    if "ucs" not in targets and "bts" not in targets:
        fail("--target: give ucs or bts (or both): the bond strengths need a strength to follow")
    if "ucs" in targets and "bts" in targets and targets["bts"] >= targets["ucs"]:
        fail(f"--target: bts ({targets['bts'] / 1e6:g} MPa) must be below ucs "
             f"({targets['ucs'] / 1e6:g} MPa)")
    return targets


def structure():
    with open(runs.case("rock", "bonded_disc_structure.json")) as f:
        return json.load(f)


def refuse_unreachable(targets, model):
    """Says, before any run, when a target lies outside what the bonded discs produce."""
    lo, hi = model["ucs_over_bts"]["reachable"]
    if "ucs" in targets and "bts" in targets:
        ratio = targets["ucs"] / targets["bts"]
        if not lo <= ratio <= hi:
            fail(f"UCS/BTS = {ratio:.2f} is outside what bonded circular discs reach ({lo:g}-{hi:g}; "
                 "T_s/T_n, dem.bonds.friction_angle_deg and rolling friction hardly move it: "
                 "cases/rock/bonded_disc_structure.json). No knob of this model lifts it (grains "
                 "that interlock do: clumps, polygons or flat joints, Potyondy 2012). Calibrate to "
                 "one strength instead: leave bts= (or ucs=) out of --target, and the other "
                 f"follows at UCS/BTS ~ {0.5 * (lo + hi):.1f}")
    nlo, nhi = model["poisson_ratio"]["reachable"]
    if "nu" in targets and not nlo <= targets["nu"] <= nhi:
        fail(f"nu = {targets['nu']:g} is outside what the bonded discs reach ({nlo:g}-{nhi:g} for "
             "K_s/K_n from about 0.1 to 1.3); leave nu out of --target to keep the starting rock's "
             "stiffness ratio")
    table = model["friction_angle"]["table"]
    plo, phi_hi = table[0][1], table[-1][1]
    if "phi" in targets and not plo <= targets["phi"] <= phi_hi:
        fail(f"phi = {targets['phi']:g} deg is outside what the bonded discs reach ({plo:g}-"
             f"{phi_hi:g} deg for dem.bonds.friction_angle_deg {table[0][0]:g}-{table[-1][0]:g}: "
             "the bonds carry the load to the peak, and a bond's friction lifts the envelope only "
             "so far); leave phi out of --target, and measure the rock's envelope with "
             "`rockcut envelope`")


def fmt(name, value):
    scale, unit = SHOWN[name]
    return f"{value / scale:.4g}{(' ' + unit) if unit else ''}"


