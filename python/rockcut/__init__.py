"""rockcut: the command-line tool and Python library around the coupler.

From the shell:   scripts/rockcut VERB ...   (scripts/rockcut --help lists the verbs)
From Python:      import rockcut; run = rockcut.read_run("out/saturated_reduced")
"""
from .run_data import Run, read_run

__all__ = ["Run", "read_run"]
