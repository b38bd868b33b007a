"""The bonded discs' structure as `rockcut calibrate --target` uses it (its numbers in
cases/rock/bonded_disc_structure.json): where the first round starts, and how each round moves the
micro-parameters from the means measured in the rounds before."""
import math

def lattice_shape(r):
    """(1 + r)/(3 + r): how E changes with K_s/K_n at fixed K_n (hexagonal lattice)."""
    return (1.0 + r) / (3.0 + r)


def cold_start(targets, rock, model):
    """Parameters from the structure alone: nothing of the starting rock but its disc size, its
    strength ratio and its bond friction (and its stiffnesses where E or nu are not targets)."""
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
    return {"kn": kn, "ks_ratio": r, "tn": tn, "ts_ratio": rock["ts_ratio"],
            "phi_b_deg": rock["phi_b_deg"]}


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
    names = [k for k in ("ucs", "bts") if k in targets]
    estimates = [math.log(q["tn"]) + sum(math.log(targets[k] / m[k]) for k in names) / len(names)
                 for _, q, m, _ in rounds]
    p["tn"] = math.exp(sum(estimates) / len(estimates))
    return p


