"""Builders shared by the FMI-boundary tests (not tests themselves)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorcosim import scenarios
from rotorcosim.master.observers import Observer
from rotorcosim.master.scenario import build_simulation, load_scenario
from rotorcosim.master.schedule import Interval, Timeline

TOY = Path(scenarios.__file__).with_name("toy_thermomechanical.toml")


def export_toy(dest: Path) -> dict[str, Path]:
    from rotorcosim.fmus.export import export_scenario

    return export_scenario(load_scenario(TOY), dest)


class Capture(Observer):
    """Every output of every component at every base step: the full trajectory of a run."""

    def __init__(self):
        self.t: list[float] = []
        self.rows: list[dict[str, np.ndarray]] = []

    def step(self, sim, t):
        self.t.append(t)
        self.rows.append({f"{n}.{k}": np.array(v, dtype=float) for n, c in sim.system.components.items()
                          for k, v in c.y.items()})

    def series(self, ref: str) -> np.ndarray:
        return np.array([r[ref] for r in self.rows])


def run_intervals(sc, intervals: list[tuple[str, float, float]]) -> Capture:
    """Run scenario ``sc`` through the given (phase, duration, step) intervals, capturing every output."""
    cap = Capture()
    sim = build_simulation(sc, [cap])
    try:
        sim.run(Timeline([Interval(p, d, h) for p, d, h in intervals]))
    finally:
        for c in sim.system.components.values():
            c.terminate()
    return cap


def max_rel_diff(a: Capture, b: Capture, refs) -> float:
    """Largest |a - b| / max(|a|, |b|, tiny) over all captured outputs ``refs`` and times (same length runs)."""
    assert len(a.rows) == len(b.rows) and a.rows, "the two runs took different numbers of steps"
    worst = 0.0
    for ref in refs:
        x, y = a.series(ref), b.series(ref)
        scale = np.maximum(np.max(np.abs(x)), np.max(np.abs(y)))
        if scale == 0:
            continue
        worst = max(worst, float(np.max(np.abs(x - y)) / scale))
    return worst
