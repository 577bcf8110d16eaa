"""The support fuse component (``fuse.support``): a support that breaks at a load, its break located in time.

Between a supported point (a rotor node, or a bearing's housing side) and the structure, taken as fixed: inputs
the point's displacement ``X`` and velocity ``V`` (x, y, axial; the axial element carries no force), outputs the
force the fuse carries, ``F_support`` (x, y) [N], transmitted to the structure, and the force on the supported
body ``F_rotor`` (= -F_support, its axial element 0, the rotor's port convention). The force law and the break
are kernel.py's. One stage: the fuse breaks once, from intact to the soft path.

The break is an event: the component declares one event indicator (``break``, kernel.break_indicator), and the
master locates its zero within ``event_tolerance`` [s] (master/core/events.py) and calls
:meth:`SupportFuse.update_discrete`, which records the break. The step itself breaks the fuse at its end when the
indicator reached zero there, so that the fuse also breaks without the master's event location (an FMU in another
tool: the break then falls on the communication point after the load was reached).

Its state is ``broken``, ``reported`` and the indicator's last value ``g``; its force follows its inputs of the
step (the point's state at the end of the step in Gauss-Seidel order after the rotor). The step is a compiled
kernel (kernel.step) that reports the indicator's change of sign, so that the compiled loop runs it.
"""
from __future__ import annotations

import math

import numpy as np

from ..contract import ContractError, Variable
from ..kernels import KernelComponent
from .kernel import FuseParams, FuseState, break_indicator, publish, step


class SupportFuse(KernelComponent):
    """A stiff support that breaks at a radial load into a soft path and a bumper (module docstring)."""

    description = ("Support fuse: intact stiffness and damping until the radial force reaches the break load, then "
                   "a soft path and a bumper at a clearance; the break is a located event")
    variables = (
        Variable("k_intact", "parameter", unit="N/m", start=0.0, description="intact stiffness (x and y)",
                 plausible=(1e4, 1e11)),
        Variable("damping", "parameter", unit="N.s/m", start=0.0,
                 description="damping, intact and after the break"),
        Variable("break_load", "parameter", unit="N", start=0.0,
                 description="the intact element's radial elastic force at which the fuse breaks"),
        Variable("k_broken", "parameter", unit="N/m", start=0.0,
                 description="stiffness of the soft path after the break (0: none)"),
        Variable("bumper_clearance", "parameter", unit="m", start=0.0,
                 description="radial clearance of the bumper"),
        Variable("bumper_stiffness", "parameter", unit="N/m", start=0.0,
                 description="contact stiffness of the bumper (0: no bumper)"),
        Variable("bumper_friction", "parameter", unit="1", start=0.0,
                 description="friction coefficient of the bumper contact"),
        Variable("event_tolerance", "parameter", unit="s", start=1e-7,
                 description="time to which the master locates the break (at most the step)"),
        Variable("X", "input", 3, "m", "displacement of the supported point (x, y, axial)"),
        Variable("V", "input", 3, "m/s", "velocity of the supported point (x, y, axial)"),
        Variable("F_support", "output", 2, "N", "force the fuse carries, transmitted to the structure"),
        Variable("F_rotor", "output", 3, "N", "force of the fuse on the supported body, -F_support (axial 0)"),
        Variable("broken", "output", 1, "1", "0 intact, 1 broken"),
    )
    required_parameters = ("k_intact", "break_load")
    event_indicators = ("break",)
    # its output at set-up follows the supported point's start (a rotor on its synchronous orbit)
    inputs_at_setup = True
    preferred_step = 1e-5
    step_cost_s = 15e-6

    def setup(self, t0=0.0):
        super().setup(t0)
        p = self.p
        checks = [
            ("k_intact", p["k_intact"] > 0.0, "must be > 0"),
            ("break_load", p["break_load"] > 0.0, "must be > 0"),
            ("damping", p["damping"] >= 0.0, "must be >= 0"),
            ("k_broken", 0.0 <= p["k_broken"] <= p["k_intact"],
             f"must be within [0, k_intact = {p['k_intact']:g} N/m] (the post-fuse path is the softer one)"),
            ("bumper_clearance", p["bumper_clearance"] >= 0.0, "must be >= 0"),
            ("bumper_stiffness", p["bumper_stiffness"] >= 0.0, "must be >= 0"),
            ("bumper_friction", p["bumper_friction"] >= 0.0, "must be >= 0"),
            ("event_tolerance", p["event_tolerance"] > 0.0, "must be > 0"),
        ]
        for key, ok, what in checks:
            # NaN fails every comparison above: named with the rest
            if not (ok and math.isfinite(p[key])):
                raise ContractError(f"{self.name}.{key} {what}, got {p[key]!r}")
        self._kernel_p = FuseParams(*(float(p[k]) for k in ("k_intact", "damping", "break_load", "k_broken",
                                                             "bumper_stiffness", "bumper_clearance",
                                                             "bumper_friction")))
        x = self.u["X"]
        #: broken: the fuse is on its soft path; reported: the master has located the break (update_discrete);
        #: g: the indicator's last value (kernel.step)
        self.state = {"broken": np.zeros(1), "reported": np.zeros(1),
                      "g": np.array([break_indicator(float(x[0]), float(x[1]), p["k_intact"], p["break_load"])])}
        self._publish()

    def _publish(self) -> None:
        s, p, u, y = self.kernel_args()
        publish(s, p, u, y)

    # -- the compiled kernel (components/kernels.py) ---------------------------------------------------------
    STEP = staticmethod(step)
    KERNEL_EVENTS = True

    def kernel_state(self):
        st = self.state
        return FuseState(st["broken"], st["reported"], st["g"])

    def kernel_params(self):
        return self._kernel_p

    def indicators(self) -> np.ndarray:
        # broken by its step and not yet handed over: the indicator has crossed (g = 1); then none (one stage)
        return np.zeros(0) if self.state["reported"][0] else self.state["g"].copy()

    def update_discrete(self, t, which):
        x = self.u["X"]
        elastic = self.p["k_intact"] * math.hypot(float(x[0]), float(x[1]))
        self.state["broken"][0] = 1.0
        self.state["reported"][0] = 1.0
        self._publish()
        return {"kind": "break", "values": {"F_elastic_N": elastic, "break_load_N": self.p["break_load"],
                                            "X_m": [float(x[0]), float(x[1])]}}
