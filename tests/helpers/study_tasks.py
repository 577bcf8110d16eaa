"""Stand-in tasks for the studies' evaluator (rotorcosim.master.study.evaluate): each is called as a run would be,
``task(scenario, overrides, duration) -> summary``, and is importable by Dask workers (tests/ on PYTHONPATH)."""
from __future__ import annotations

import math
import os
from pathlib import Path


def ishigami(scenario, overrides, duration) -> dict:
    """The Ishigami function of the overrides' three values, in order (a = 7, b = 0.1: Ishigami & Homma 1990)."""
    x1, x2, x3 = list(overrides.values())[:3]
    y = math.sin(x1) + 7.0 * math.sin(x2) ** 2 + 0.1 * x3 ** 4 * math.sin(x1)
    return {"status": "complete", "y": y}


def fails_when_negative(scenario, overrides, duration) -> dict:
    """A run that diverges when its first value is negative, else returns that value as ``y``."""
    x = list(overrides.values())[0]
    if x < 0:
        return {"status": "failed", "error": f"SimulationDiverged: diverged at x = {x:g}"}
    return {"status": "complete", "y": x}


def dies_once(scenario, overrides, duration) -> dict:
    """Kills its worker process the first time it runs a value (a marker file in $STUDY_MARKERS remembers it),
    then returns the value: a worker dying mid-sample, whose job the evaluator must run again."""
    x = list(overrides.values())[0]
    marker = Path(os.environ["STUDY_MARKERS"]) / f"{x!r}"
    if not marker.exists():
        marker.write_text("died")
        os._exit(1)
    return {"status": "complete", "y": x}


def always_dies(scenario, overrides, duration) -> dict:
    """Kills its worker process every time: the job must end reported failed, not lost or retried forever."""
    os._exit(1)


def slow(scenario, overrides, duration) -> dict:
    """Returns the first value as ``y`` after 0.2 s: a study long enough to be stopped half-way."""
    import time

    time.sleep(0.2)
    return {"status": "complete", "y": list(overrides.values())[0]}
