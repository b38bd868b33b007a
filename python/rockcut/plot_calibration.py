"""rockcut plot of calibration runs (UCS or Brazilian: /timeseries/axial_strain): the load against
the axial strain, one figure per run or all in one (plot.py documents the verb). A fracture test
(/timeseries/elongation_m) draws the pull against the elongation instead.
"""
import os

import h5py

from .figures import plt
from .run_data import h5_path, read_summary


def load_calibration(out):
    """x, load, the load's axis label and the summary. x: the axial strain [1e-3], or a fracture
    test's elongation [um]."""
    with h5py.File(h5_path(out), "r") as f:
        ts = f["timeseries"]
        if "elongation_m" in ts:
            return (ts["elongation_m"][:] * 1e6, ts["pulling_force_n_per_m"][:] / 1e3,
                    "pull [kN/m]", read_summary(out) or {})
        strain = ts["axial_strain"][:] * 1e3
        if "axial_stress_pa" in ts:
            load_, label = ts["axial_stress_pa"][:] / 1e6, "axial stress [MPa]"
        else:
            load_, label = ts["platen_force_n_per_m"][:] / 1e3, "platen force [kN/m]"
    return strain, load_, label, read_summary(out) or {}


def plot_calibration(outs, png=None):
    """Stress (or platen force) against axial strain: one figure per run, or all in `png`."""
    groups = [[o] for o in outs] if png is None else [outs]
    for group in groups:
        fig, ax = plt.subplots(figsize=(6, 4))
        for out in group:
            strain, load_, label, s = load_calibration(out)
            # Several runs: name each by its directory (e.g. swapped/ucs), else by the scene title.
            parts = os.path.normpath(out).split(os.sep)
            name = "/".join(parts[-2:]) if len(group) > 1 else (s.get("title") or parts[-1])
            if "ucs_pa" in s:
                name += f" (UCS {s['ucs_pa'] / 1e6:.1f} MPa"
                if "youngs_modulus_pa" in s:
                    name += (f", E {s['youngs_modulus_pa'] / 1e9:.2f} GPa, "
                             f"nu {s['poisson_ratio']:.2f}")
                name += ")"
            if "bts_pa" in s:
                name += f" (BTS {s['bts_pa'] / 1e6:.2f} MPa)"
            fracture = "fracture_energy_j_per_m2" in s
            if fracture:
                name += (f" (G_F {s['fracture_energy_j_per_m2']:.1f} J/m^2, net strength "
                         f"{s['net_tensile_strength_pa'] / 1e6:.2f} MPa)")
            ax.plot(strain, load_, label=name)
            ax.set_ylabel(label)
        ax.set_xlabel("elongation [um]" if fracture else "axial strain [1e-3]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        target = png or os.path.join(group[0],
                                     "force_elongation.png" if fracture else "stress_strain.png")
        fig.savefig(target, dpi=100)
        plt.close(fig)
        print(f"{', '.join(group)}: wrote {target}")
