"""rockcut plot of calibration runs (UCS or Brazilian: /timeseries/axial_strain): the load against
the axial strain, one figure per run or all in one (plot.py documents the verb).
"""
import os

import h5py

from .figures import plt
from .run_data import h5_path, read_summary


def load_calibration(out):
    with h5py.File(h5_path(out), "r") as f:
        ts = f["timeseries"]
        strain = ts["axial_strain"][:]
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
            ax.plot(strain * 1e3, load_, label=name)
            ax.set_ylabel(label)
        ax.set_xlabel("axial strain [1e-3]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        target = png or os.path.join(group[0], "stress_strain.png")
        fig.savefig(target, dpi=100)
        plt.close(fig)
        print(f"{', '.join(group)}: wrote {target}")
