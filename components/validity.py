"""Validity envelopes: where a component's model holds, declared as data and checked on its ports.

A component lists :class:`Check` objects (``Component.validity()``): a quantity computed from rows of its
outputs (or inputs) and its parameters, an upper or lower limit in SI units, the unit the limit is reported in and the
source of the limit. A :class:`Tracker` evaluates them on rows of outputs as a run goes (or once, for the
``bearing-static`` / ``damper-force`` / ``thermal-steady`` commands) and keeps, for every check that was left,
the first time it was left and the worst value: the ``validity`` list of summary.json and of the commands' JSON
output, and one warning line each on stderr.

A value outside the envelope is not an error: the run goes on and its numbers are what the model gives there,
but they are no longer a description of the machine.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

import numpy as np

BOUNDS = ("max", "min")


@dataclass(frozen=True)
class Check:
    """One bound of a component's envelope.

    ``value(y)`` maps ``y`` (port name -> array of rows, shape (n, size)) to the quantity per row, shape (n,),
    SI units; ``ports`` names the ports it reads: outputs, cheapest, or inputs (a run sees those at the end of
    each compiled block only, master/observer/validity.py). ``limit`` is SI; ``unit`` is the unit the value and
    limit are reported in, ``scale`` the factor from SI to it (1e-6 for Pa -> MPa). ``bound`` "max": the model
    holds while value <= limit; "min": while value >= limit."""

    quantity: str
    ports: tuple[str, ...]
    value: Callable[[Mapping[str, np.ndarray]], np.ndarray]
    limit: float
    unit: str
    source: str
    scale: float = 1.0
    bound: str = "max"

    def __post_init__(self):
        if self.bound not in BOUNDS:
            raise ValueError(f"check {self.quantity!r}: bound {self.bound!r} not in {BOUNDS}")

    def outside(self, v: np.ndarray) -> np.ndarray:
        """Rows whose value leaves the envelope (NaN is not judged: a diverged run has its own error)."""
        return v > self.limit if self.bound == "max" else v < self.limit


class Tracker:
    """The checks of some components, evaluated on rows of their ports: for each check left, the first time and
    the worst value."""

    def __init__(self, checks: Mapping[str, tuple[Check, ...]]):
        #: (component name, check) in declaration order
        self.checks = [(name, c) for name, cs in checks.items() for c in cs]
        self.left: dict[int, dict] = {}   # index into checks -> entry (first time, worst value)

    def ports(self) -> list[str]:
        """The ``component.port`` ports the checks read."""
        out: list[str] = []
        for name, c in self.checks:
            for p in c.ports:
                if f"{name}.{p}" not in out:
                    out.append(f"{name}.{p}")
        return out

    def update(self, times: np.ndarray, rows: Mapping[str, np.ndarray], only=None) -> None:
        """Rows at ``times`` (shape (n,)); ``rows["component.port"]`` of shape (n, size); ``only``: the names of
        the components to check (None: all)."""
        for i, (name, c) in enumerate(self.checks):
            if only is not None and name not in only:
                continue
            v = np.asarray(c.value({p: rows[f"{name}.{p}"] for p in c.ports}), dtype=float).reshape(-1)
            bad = np.flatnonzero(c.outside(v))
            if not len(bad):
                continue
            worst = float(v[bad].max() if c.bound == "max" else v[bad].min())
            e = self.left.get(i)
            if e is None:
                self.left[i] = {"time_s": float(times[bad[0]]), "worst": worst}
            elif (worst > e["worst"]) if c.bound == "max" else (worst < e["worst"]):
                e["worst"] = worst

    def entries(self) -> list[dict]:
        """The ``validity`` list: one entry per check left, in declaration order; ``value`` is the worst value,
        ``time_s`` the first time the envelope was left; value and limit in ``unit``."""
        out = []
        for i, (name, c) in enumerate(self.checks):
            e = self.left.get(i)
            if e is not None:
                out.append({"component": name, "quantity": c.quantity, "value": e["worst"] * c.scale,
                            "limit": c.limit * c.scale, "unit": c.unit, "bound": c.bound,
                            "time_s": e["time_s"], "source": c.source})
        return out


def warning_line(program: str, entry: dict, with_time: bool = True) -> str:
    """One line for stderr: ``rotorcosim run: warning: bearing0 contact stress 4512 MPa is above the limit
    4200 MPa (first at t = 0.41 s): ISO 76 ...``."""
    side = "above" if entry["bound"] == "max" else "below"
    where = f" of {entry['component']}" if entry.get("component") else ""
    when = f" (first at t = {entry['time_s']:.6g} s)" if with_time and entry.get("time_s") is not None else ""
    unit = "" if entry["unit"] == "1" else f" {entry['unit']}"
    return (f"{program}: warning: {entry['quantity']}{where} {_num(entry['value'])}{unit} is {side} "
            f"{_num(entry['limit'])}{unit}{when}, outside the model's validity: {entry['source']}")


def _num(x: float) -> str:
    return f"{x:.5g}"


def once(checks: tuple[Check, ...], y: Mapping[str, np.ndarray], component: str) -> list[dict]:
    """The entries of ``checks`` left by one set of outputs ``y`` (port -> vector), without a time: a command's
    single evaluation."""
    t = Tracker({component: checks})
    t.update(np.zeros(1), {f"{component}.{p}": np.asarray(y[p], dtype=float).reshape(1, -1)
                           for _, c in t.checks for p in c.ports})
    out = t.entries()
    for e in out:
        e["time_s"] = None
    return out
