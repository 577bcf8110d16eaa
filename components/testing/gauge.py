"""A toy gauge with an input that declares a default, to test inputs left unconnected.

``Gauge``: ``y = F + bias``. ``bias`` is declared ``has_default=True``: a scenario may leave it unconnected and it
then keeps its start value, 2; ``F`` (N) must be connected or given a constant, as every native input without a
declared default. Stateless.

>>> g = Gauge("g")
>>> g.set_inputs({"F": [1.0]}); g.do_step(0.0, 0.1); g.y["y"]
array([3.])
"""
from __future__ import annotations

from ..contract import Component, Variable


class Gauge(Component):
    variables = (
        Variable("bias", "input", unit="N", start=2.0, description="offset; may stay unconnected (keeps 2 N)",
                 has_default=True),
        Variable("F", "input", unit="N", description="measured force"),
        Variable("y", "output", unit="N", description="F + bias"),
    )

    def do_step(self, t: float, h: float) -> None:
        self.y["y"] = self.u["F"] + self.u["bias"]
        self.time = t + h
