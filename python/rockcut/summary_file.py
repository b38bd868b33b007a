"""The JSON files of runs and campaigns (summary.json, sweep_plan.json, sweep_run.json), read
without NumPy or h5py: what `status` and the campaign need on a machine (a cluster's login node)
that has only the standard library."""
import json
import os


def read_json(path):
    """The JSON file `path` as Python values, or None while it is missing or unreadable (a run
    may be writing it)."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def read_summary(path):
    """summary.json of a run folder as a dict, or None while the run has none (or it is unreadable)."""
    return read_json(os.path.join(path, "summary.json"))
