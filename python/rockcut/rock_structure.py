"""The bonded discs' structure as `rockcut calibrate --target` uses it (its numbers in
cases/rock/bonded_disc_structure.json): where the first round starts, and how each round moves the
micro-parameters from the means measured in the rounds before."""
import math


def interpolate(table, x, column_in, column_out):
    """Piecewise linear through the rows of `table`, clamped at its ends."""
    rows = sorted(table, key=lambda r: r[column_in])
    if x <= rows[0][column_in]:
        return rows[0][column_out]
    for a, b in zip(rows, rows[1:]):
        if x <= b[column_in]:
            t = (x - a[column_in]) / (b[column_in] - a[column_in])
            return a[column_out] + t * (b[column_out] - a[column_out])
    return rows[-1][column_out]


def bond_friction_for(phi_deg, model):
    """phi_b [deg] whose envelope has the peak friction angle phi (the structure's table)."""
    return interpolate(model["friction_angle"]["table"], phi_deg, 1, 0)


def lattice_shape(r):
    """(1 + r)/(3 + r): how E changes with K_s/K_n at fixed K_n (hexagonal lattice)."""
    return (1.0 + r) / (3.0 + r)


def cold_start(targets, rock, model):
    """Parameters from the structure alone: nothing of the starting rock but its disc size, its
    strength ratio and its bond friction (and its stiffnesses where E or nu are not targets), and
    the damping model the loading tests run under (`rock["damping_model"]`, e.g. "viscous")."""
    r = rock["ks_ratio"]
    if "nu" in targets:
        nu = model["poisson_ratio"]
        r = math.exp((nu["a"] - targets["nu"]) / nu["b"])
    kn = rock["kn"] * lattice_shape(rock["ks_ratio"]) / lattice_shape(r)
    if "E" in targets:
        kn = targets["E"] / (model["youngs_modulus"]["c"] * lattice_shape(r))
    s = model["strength"]
    guesses = []
    if "ucs" in targets:
        guesses.append(targets["ucs"] * s["ucs_factor"] * rock["diameter_m"])
    if "bts" in targets:
        guesses.append(targets["bts"] * s["bts_factor"] * rock["diameter_m"])
    tn = math.exp(sum(math.log(g) for g in guesses) / len(guesses))
    if rock.get("damping_model") == "viscous":
        tn /= s["viscous_factor"]  # the factors above are local damping's; dashpots weaken ~10 %
    phi_b = bond_friction_for(targets["phi"], model) if "phi" in targets else rock["phi_b_deg"]
    # The softening ratio starts at the starting rock's: the work of fracture at the target
    # strengths is not known before a round has measured it (it depends on the damping too).
    lam = rock.get("softening", 0.0)
    return {"kn": kn, "ks_ratio": r, "tn": tn / strength_factor(lam, model),
            "ts_ratio": rock["ts_ratio"], "phi_b_deg": phi_b, "softening": lam}


def strength_factor(lam, model):
    """The strengths' factor of softening ratio `lam` over the paper's bond at a fixed T."""
    return interpolate(model["softening"]["table"], lam, 0, 1)


def fracture_factor(lam, model):
    """The work of fracture's factor of softening ratio `lam` over the paper's bond at a fixed T."""
    return interpolate(model["softening"]["table"], lam, 0, 2)


def softening_for(rounds, targets, model):
    """(lambda, R, T0): the softening ratio whose work of fracture meets targets["gf"] at the
    strengths the targets ask, from the rounds so far. Every round estimates the bond strength
    that meets the strength targets with the paper's bond, T0 (its T times its lambda's strength
    factor times target / measured), and its work of fracture per T^2 with the paper's bond,
    g0 = G_F / (fracture factor T^2); both are pooled as geometric means over the rounds. At
    lambda the strengths ask T0 / S(lambda), so the work of fracture is g0 T0^2 Gamma / S^2:
    lambda solves Gamma/S^2 = R = gf / (g0 T0^2), through the table (Gamma/S^2 grows with
    lambda there). R below 1 is below what the paper's bond gives; lambda is then 0. Above the
    table's last row lambda is that row's."""
    names = [k for k in ("ucs", "bts") if k in targets]
    t0, g0 = [], []
    for _, q, m, _ in rounds:
        lam = q.get("softening", 0.0)
        t = q["tn"] * strength_factor(lam, model)
        t0.append(math.log(t) + sum(math.log(targets[k] / m[k]) for k in names) / len(names))
        if m.get("gf") == m.get("gf"):
            g0.append(math.log(m["gf"] / (fracture_factor(lam, model) * q["tn"] ** 2)))
    t0 = math.exp(sum(t0) / len(t0))
    if not g0:
        return rounds[-1][1].get("softening", 0.0), math.nan, t0
    ratio = targets["gf"] / (math.exp(sum(g0) / len(g0)) * t0 ** 2)
    rows = [(r[0], r[2] / r[1] ** 2) for r in model["softening"]["table"]]
    if ratio <= rows[0][1]:
        return rows[0][0], ratio, t0
    for (la, ha), (lb, hb) in zip(rows, rows[1:]):
        if ratio <= hb:
            return la + (ratio - ha) / (hb - ha) * (lb - la), ratio, t0
    return rows[-1][0], ratio, t0


def next_params(rounds, targets, model):
    """One step of the structure's rules from the rounds so far [(k, params, means, errors)]. The
    stiffnesses move from the last round (E and nu scatter by 1-3 % between specimens). The
    strength scale pools every round: strength is proportional to T, so each round k estimates
    the T that meets the targets as T_k (target / measured) (the geometric mean over the targeted
    strengths), and the next T is the geometric mean of those estimates. One round's BTS scatters
    by 6-7 % over four seeds; the pooled estimate does not chase it."""
    _, params, measured, _ = rounds[-1]
    p = dict(params)
    if "nu" in targets and "nu" in measured:
        p["ks_ratio"] = params["ks_ratio"] * math.exp(
            (measured["nu"] - targets["nu"]) / model["poisson_ratio"]["b"])
    if "E" in targets and "E" in measured:
        p["kn"] = (params["kn"] * targets["E"] / measured["E"] * lattice_shape(params["ks_ratio"])
                   / lattice_shape(p["ks_ratio"]))
    if "phi" in targets and measured.get("phi") == measured.get("phi"):
        # Each round estimates the phi_b that meets the target from its miss and the table's
        # slope there; the next phi_b is their mean. A seed's phi, from two specimens, scatters
        # by degrees, and the slope is a quarter: one round's miss alone would throw phi_b about.
        table = model["friction_angle"]["table"]

        def slope(phi_b, h=5.0):
            return max((interpolate(table, phi_b + h, 0, 1) - interpolate(table, phi_b - h, 0, 1))
                       / (2 * h), 0.05)

        estimates = [q["phi_b_deg"] + (targets["phi"] - m["phi"]) / slope(q["phi_b_deg"])
                     for _, q, m, _ in rounds if m.get("phi") == m.get("phi")]
        p["phi_b_deg"] = min(max(sum(estimates) / len(estimates), 0.0), table[-1][0])
    names = [k for k in ("ucs", "bts") if k in targets]
    # Only the rounds at this bond friction: it lifts the strengths too.
    same = [r for r in rounds if abs(r[1]["phi_b_deg"] - p["phi_b_deg"]) < 0.5] or rounds[-1:]
    if "gf" in targets:
        # The softening ratio and the bond strength move together: softening lifts the strengths.
        p["softening"], _, t0 = softening_for(same, targets, model)
        p["tn"] = t0 / strength_factor(p["softening"], model)
        return p
    estimates = [math.log(q["tn"]) + sum(math.log(targets[k] / m[k]) for k in names) / len(names)
                 for _, q, m, _ in same]
    p["tn"] = math.exp(sum(estimates) / len(estimates))
    return p


