"""rockcut VERB ...: the command-line entry (`rockcut` once installed with pip, scripts/rockcut in a
checkout, or python3 -m rockcut)."""
import importlib
import sys

# verb -> (module, what it does). Each module has main(argv) -> exit status.
VERBS = {
    "sweep": ("sweep", "run a scene once per value of a field (and seed); sweep.csv, figures 8-12"),
    "status": ("status", "state of each run of a sweep folder: pending, running, done, failed, "
                         "interrupted"),
    "collect": ("collect", "sweep.csv, sweep_mean.csv and the figures from a sweep folder's "
                           "finished runs"),
    "windows": ("windows", "means of a cut's time series over windows of tool travel"),
    "compare": ("compare", "several water-depth sweeps side by side: where shear breaks take over"),
    "paired": ("paired", "paired differences over specimen seeds in a sweep's sweep.csv"),
    "plot": ("plot", "figures of runs: forces, damage, breaks of a cut; stress-strain of a "
                     "calibration"),
    "animate": ("animate", "a film (MP4 or GIF) of a run: discs to scale, the tool, a colour bar"),
    "calibrate": ("calibrate", "micro-parameters for a rock's UCS, BTS, E and nu (--target), or "
                               "UCS and Brazilian runs per parameter set and seed"),
    "envelope": ("envelope", "the rock's Mohr-Coulomb envelope (c, phi) from biaxial tests"),
    "accuracy": ("accuracy", "work-precision study of the coupled cut (error against wall time)"),
    "extreme": ("extreme", "run the stiff and extreme scenes (cases/extreme) and tabulate them"),
    "regression": ("regression", "regression cases (tests/regression): check, or re-measure"),
    "study": ("study", "error against run time of the pore-pressure models (verification scenes)"),
    "crop-packing": ("crop_packing", "cut a window out of a disc packing file, optionally scaled"),
}

USAGE = "usage: rockcut VERB [options]   (rockcut VERB --help for a verb's options)"


def usage():
    width = max(map(len, VERBS))
    lines = [USAGE, "", "The tool around the coupler (`coupler run CASE` runs a scene). Verbs:"]
    lines += [f"  {verb:<{width}}  {what}" for verb, (_, what) in VERBS.items()]
    lines += ["", "From Python: import rockcut; run = rockcut.read_run(\"out/saturated_reduced\")"]
    return "\n".join(lines)


def main(argv):
    if not argv or argv[0] in ("-h", "--help", "help"):
        print(usage())
        return 0 if argv else 2
    verb, rest = argv[0], argv[1:]
    if verb not in VERBS:
        from difflib import get_close_matches
        near = get_close_matches(verb, VERBS, n=1)
        print(f"rockcut: no verb '{verb}'" + (f"; did you mean '{near[0]}'?" if near else "")
              + "\n" + usage(), file=sys.stderr)
        return 2
    module = importlib.import_module(f"rockcut.{VERBS[verb][0]}")
    return module.main(rest) or 0


def entry():
    """The `rockcut` command of an installed package (pyproject.toml's console script)."""
    sys.exit(main(sys.argv[1:]))


if __name__ == "__main__":
    entry()
