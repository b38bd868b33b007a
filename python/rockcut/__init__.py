"""rockcut: the command-line tool and Python library around the coupler.

From the shell:   scripts/rockcut VERB ...   (scripts/rockcut --help lists the verbs)
From Python:      import rockcut; run = rockcut.read_run("out/saturated_reduced")
"""
__all__ = ["Run", "read_run"]


def __getattr__(name):
    # Loaded when first used: `rockcut --help` and the verbs that need no HDF5 start without h5py.
    if name in __all__:
        from . import run_data
        return getattr(run_data, name)
    raise AttributeError(f"module 'rockcut' has no attribute '{name}'")
