"""Cut a window out of a disc packing file and write it, optionally scaled, as a new packing file.

Packing files have one disc per line, `x_m y_m radius_m`; '#' starts a comment. A window of a dense
random packing is itself a dense random packing with free (cut) surfaces, which is what the
fluid-only verification scenes need. Scaling every coordinate and radius by the same factor keeps
the packing's geometry and changes the particle size: the error study uses it for its particle-size
ladder.

  rockcut crop-packing SOURCE OUT --window X0 Y0 WIDTH HEIGHT [--scale S] [--centre]

Discs are kept when their centre lies inside the window. --centre moves the window's centre to the
origin before scaling.
"""
import argparse

import numpy as np



def crop(source, window, scale=1.0, centre=False):
    data = np.loadtxt(source, comments="#", ndmin=2)
    x0, y0, w, h = window
    keep = (data[:, 0] >= x0) & (data[:, 0] < x0 + w) & (data[:, 1] >= y0) & (data[:, 1] < y0 + h)
    discs = data[keep].copy()
    if centre:
        discs[:, 0] -= x0 + 0.5 * w
        discs[:, 1] -= y0 + 0.5 * h
    discs *= scale
    return discs


def write(path, discs, note):
    with open(path, "w") as f:
        f.write(f"# x_m y_m radius_m ({len(discs)} discs) {note}\n")
        for x, y, r in discs:
            f.write(f"{x:.8g} {y:.8g} {r:.7g}\n")


def main(argv):
    p = argparse.ArgumentParser(prog="rockcut crop-packing", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("source")
    p.add_argument("out")
    p.add_argument("--window", nargs=4, type=float, required=True, metavar=("X0", "Y0", "WIDTH", "HEIGHT"))
    p.add_argument("--scale", type=float, default=1.0)
    p.add_argument("--centre", action="store_true")
    a = p.parse_args(argv)
    discs = crop(a.source, a.window, a.scale, a.centre)
    note = f"window {a.window} of {a.source}, scale {a.scale}{', centred' if a.centre else ''}"
    write(a.out, discs, note)
    print(f"{a.out}: {len(discs)} discs")

