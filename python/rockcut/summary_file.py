"""summary.json of a run folder, read without NumPy or h5py: what `status` and the campaign need on
a machine (a cluster's login node) that has only the standard library."""
import json
import os


def read_summary(path):
    """summary.json of a run folder as a dict, or None while the run has none (or it is unreadable)."""
    try:
        with open(os.path.join(path, "summary.json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None
