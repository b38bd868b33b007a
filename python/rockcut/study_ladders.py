"""The ladders of rockcut study (study.py documents them): for each fluid verification scene, the
runs of each ladder and model as their --set overrides.
"""
import math
import os

from . import crop_packing, runs

ROOT = runs.REPO

D = 2e9 * 1e-14 / 1e-3  # Table 1: M kappa / mu [m^2/s]
C = 0.05                # explicit stability constant (fluid_module/models/explicit_model.hpp)
MODELS = ("explicit", "implicit")


def steps_dividing(interval, dt_max):
    """The largest step <= dt_max that divides `interval` into whole steps."""
    return interval / math.ceil(interval / dt_max * (1 - 1e-12))


# ---- terzaghi: lattice column of 4 x ny discs, L = (ny - 1/2) s = 19.5 mm ----------------------
TERZ_L = 0.0195
TERZ_LOAD = 2e-4  # the load ramp of the scene [s]


def terzaghi_runs(quick):
    runs = []
    sizes = [17, 33, 65] if quick else [17, 33, 65, 129]
    for model in MODELS:
        for ny in sizes:  # size ladder: h / s = 2.5
            runs.append(("size", model, terzaghi_sets(model, ny, 2.5, None)))
        for ny in ([33, 65, 129] if quick else [33, 49, 65, 97, 129]):  # size at h = 1.5 mm
            runs.append(("size_h", model, terzaghi_sets(model, ny, 0.0015 * (ny - 0.5) / TERZ_L, None)))
        for ny in ([17, 65] if quick else [17, 33, 65, 129]):  # h ~ sqrt(s): h / s grows, h falls
            s_ = TERZ_L / (ny - 0.5)
            s0 = TERZ_L / 16.5
            runs.append(("size_sqrt", model, terzaghi_sets(model, ny, 2.5 * math.sqrt(s0 / s_), None)))
        for ratio in ([2.0, 3.0, 4.0] if quick else [2.0, 2.5, 3.0, 4.0, 5.0]):  # at ny = 65
            runs.append(("ratio", model, terzaghi_sets(model, 65, ratio, None)))
        factors = [0.25, 0.5, 0.89] if model == "explicit" else [0.5, 1.78, 7.1, 35.6]
        if not quick and model == "implicit":
            factors = [0.44, 0.89, 1.78, 3.56, 7.1, 17.8, 35.6]
        if not quick and model == "explicit":
            factors = [0.125, 0.25, 0.5, 0.89]
        for f in factors:  # dt ladder at ny = 33, h / s = 2.5
            runs.append(("dt", model, terzaghi_sets(model, 33, 2.5, f)))
    return runs


def terzaghi_sets(model, ny, ratio, dt_factor):
    s = TERZ_L / (ny - 0.5)
    h = ratio * s
    limit = C * h * h / D
    dt = steps_dividing(TERZ_LOAD, (dt_factor or 0.89) * limit)
    # Wide enough that the middle columns are interior (div r > 1.5): a column narrower than ~2h
    # is all surface, and its inner "surface" would drain.
    nx = max(6, math.ceil(2 * ratio) + 3)
    return {
        "fluid.model": model,
        "dem.lattice.nx": nx,
        "dem.lattice.ny": ny,
        "dem.lattice.spacing_m": f"{s:.17g}",
        "dem.lattice.radius_m": f"{0.5 * s:.17g}",
        "fluid.smoothing_length_m": f"{h:.17g}",
        "time.dt_s": f"{dt:.17g}",
        "fluid.implicit.max_diffusion_number": 1000,
    }


# ---- gaussian_pulse: windows of pack57k scaled to a 40 mm domain --------------------------------
GAUSS_DOMAIN = 0.04
GAUSS_T = 2.25e-4  # end time of the scene: the peak has halved
PACK57K = os.path.join(ROOT, "bench", "data", "pack57k.txt")


def gaussian_runs(quick, work):
    crop = crop_packing
    packings = {}
    scales = [2.0, 1.0, 0.5] if quick else [2.0, 1.41, 1.0, 0.707, 0.5]
    for scale in scales:
        width = GAUSS_DOMAIN / scale
        discs = crop.crop(PACK57K, (0.1 - width / 2, 0.05 - width / 2, width, width), scale, True)
        path = os.path.join(work, f"packing_scale_{scale}.txt")
        crop.write(path, discs, f"study: {width} m window of pack57k scaled by {scale}")
        spacing = math.sqrt(GAUSS_DOMAIN ** 2 / len(discs))
        packings[scale] = (path, spacing, len(discs))
    runs = []
    for model in MODELS:
        for scale in scales:  # size ladder: h = 2.55 mean spacings (Table 1's ratio)
            path, s, _ = packings[scale]
            runs.append(("size", model, gaussian_sets(model, path, 2.55 * s, None)))
        for scale in scales:  # size ladder at Table 1's h = 1.5 mm (h / s grows)
            if scale <= 1.0:
                path, s, _ = packings[scale]
                runs.append(("size_h", model, gaussian_sets(model, path, 0.0015, None)))
        for scale in scales:  # h ~ sqrt(s): h / s grows while h falls
            path, s, _ = packings[scale]
            s0 = packings[scales[0]][1]
            runs.append(("size_sqrt", model, gaussian_sets(model, path, 2.55 * s0 * math.sqrt(s / s0), None)))
        path, s, _ = packings[0.5]
        for ratio in ([2.55, 3.4, 5.0] if quick else [2.55, 3.0, 3.4, 4.2, 5.0]):
            runs.append(("ratio", model, gaussian_sets(model, path, ratio * s, None)))
        path, s, _ = packings[1.0]
        factors = [0.25, 0.5, 0.89] if model == "explicit" else [0.5, 2.0, 8.0, 30.0]
        if not quick:
            factors = [0.125, 0.25, 0.5, 0.89] if model == "explicit" else [0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 30.0]
        for f in factors:
            runs.append(("dt", model, gaussian_sets(model, path, 2.55 * s, f)))
    return runs


def gaussian_sets(model, packing, h, dt_factor):
    limit = C * h * h / D
    dt = steps_dividing(GAUSS_T, (dt_factor or 0.89) * limit)
    return {
        "fluid.model": model,
        "dem.packing_file.path": packing,
        "fluid.smoothing_length_m": f"{h:.17g}",
        "time.dt_s": f"{dt:.17g}",
        "fluid.implicit.max_diffusion_number": 1000,
    }


# ---- undrained_step: the strain measure's first-order error in the step -------------------------
def undrained_runs(quick):
    runs = []
    for model in MODELS:
        # The load lasts 0.2 ms; the explicit limit (h = 1.5 mm) is 5.6 us, i.e. at least 36 steps.
        ks = [40, 160] if quick else [40, 80, 160, 320]
        if model == "implicit":
            ks = [2, 10, 40, 160] if quick else [2, 5, 10, 20, 40, 80, 160, 320]
        for k in ks:
            runs.append(("dt", model, {"fluid.model": model, "time.dt_s": f"{2e-4 / k:.17g}",
                                       "fluid.implicit.max_diffusion_number": 1000}))
    return runs


CASES = {
    "terzaghi": "cases/verification/terzaghi.pbtxt",
    "gaussian_pulse": "cases/verification/gaussian_pulse.pbtxt",
    "undrained_step": "cases/verification/undrained_step.pbtxt",
}
