"""The support fuse component (``fuse.support``): a support that breaks at a load, its break located in time.

Between a supported point (a rotor node, or a bearing's housing) and the structure: inputs the point's
displacement ``X`` and velocity ``V`` (x, y, axial; the axial element carries no force) and the structure's
``X_structure``, ``V_structure`` (x, y; unconnected: fixed, 0); the fuse's law acts on the difference. Outputs the
force the fuse carries, ``F_support`` (x, y) [N], the force on the structure, and the force on the supported body
``F_rotor`` (= -F_support, its axial element 0, the rotor's port convention). The force law and the break
are kernel.py's. One stage (``stages = 1``): the fuse breaks once, from intact to the soft path ``k_broken``; two
(``stages = 2``): the soft path breaks again at ``break_load_2`` into ``k_broken_2``.

A break is an event: the component declares one event indicator (``break``, kernel.break_indicator: the present
stage's), and the master locates its zero within ``event_tolerance`` [s] (master/core/events.py) and calls
:meth:`SupportFuse.update_discrete`, which records the break. The step itself breaks the fuse at its end when the
indicator reached zero there, so that the fuse also breaks without the master's event location (an FMU in another
tool: the break then falls on the communication point after the load was reached).

Its state is ``broken`` (the stages broken), ``reported`` (those located) and the indicator's last value ``g``;
its force follows its inputs of the step (the point's state at the end of the step in Gauss-Seidel order after
the rotor). The step is a compiled kernel (kernel.step) that reports the indicator's changes of sign, so that the
compiled loop runs it (``KERNEL_EVENTS``).
"""
from __future__ import annotations

import math

import numpy as np

from ..contract import ContractError, Variable
from ..kernels import KernelComponent
from .kernel import FuseParams, FuseState, break_indicator, indicator_of, publish, step


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
                 description="stiffness of the soft path after the (first) break (0: none)"),
        Variable("stages", "parameter", unit="1", start=1, type="Integer",
                 description="break stages: 1, or 2 (the soft path breaks again at break_load_2)"),
        Variable("break_load_2", "parameter", unit="N", start=0.0,
                 description="with stages = 2: the soft path's radial elastic force k_broken |x| at which it breaks"),
        Variable("k_broken_2", "parameter", unit="N/m", start=0.0,
                 description="with stages = 2: stiffness after the second break (below k_broken; 0: none)"),
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
        Variable("X_structure", "input", 2, "m", "displacement of the structure at the fuse (x, y; unconnected: 0)",
                 start=0.0, has_default=True),
        Variable("V_structure", "input", 2, "m/s", "velocity of the structure at the fuse (x, y; unconnected: 0)",
                 start=0.0, has_default=True),
        Variable("F_support", "output", 2, "N", "force the fuse carries, transmitted to the structure"),
        Variable("F_rotor", "output", 3, "N", "force of the fuse on the supported body, -F_support (axial 0)"),
        Variable("broken", "output", 1, "1", "stages broken: 0 intact, 1 after the first break, 2 after the second"),
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
        checks += self._stage_checks()
        for key, ok, what in checks:
            # NaN fails every comparison above: named with the rest
            if not (ok and math.isfinite(p[key])):
                raise ContractError(f"{self.name}.{key} {what}, got {p[key]!r}")
        #: (stiffness, load that breaks it) of each stage that can break, then the last stage's stiffness
        self._stages = [(p["k_intact"], p["break_load"])] + ([(p["k_broken"], p["break_load_2"])]
                                                             if p["stages"] == 2 else [])
        self._k_last = p["k_broken_2"] if p["stages"] == 2 else p["k_broken"]
        ks = [k for k, _ in self._stages] + [self._k_last]
        self._kernel_p = FuseParams(np.array(ks, dtype=float), np.array([load for _, load in self._stages]),
                                    float(p["damping"]), float(p["bumper_stiffness"]), float(p["bumper_clearance"]),
                                    float(p["bumper_friction"]))
        #: broken: the stages broken (0 intact); reported: those the master has located (update_discrete);
        #: g: the indicator's last value (kernel.step)
        self.state = {"broken": np.zeros(1), "reported": np.zeros(1), "g": np.zeros(1)}
        self._publish()

    def _stage_checks(self) -> list:
        """The checks of the second stage's keys (``stages``, ``break_load_2``, ``k_broken_2``): one stage leaves
        them at 0; two need a soft path that carries load (k_broken > 0), a lower stiffness after the second break,
        and a second load above what the soft path carries at the first break (else both break at once)."""
        p = self.p
        if p["stages"] not in (1, 2):
            return [("stages", False, "must be 1 or 2")]
        if p["stages"] == 1:
            return [(k, p[k] == 0.0, "is a second stage's key: give it with stages = 2")
                    for k in ("break_load_2", "k_broken_2")]
        first = p["break_load"] * p["k_broken"] / p["k_intact"]
        return [
            ("k_broken", p["k_broken"] > 0.0, "must be > 0 with stages = 2 (the second stage breaks the soft path)"),
            ("break_load_2", p["break_load_2"] > first,
             f"must be above {first:g} N with stages = 2 (the soft path's force k_broken |x| at the first break; "
             "a lower one breaks both stages at once)"),
            ("k_broken_2", 0.0 <= p["k_broken_2"] < p["k_broken"],
             f"must be within [0, k_broken = {p['k_broken']:g} N/m) (each stage softer than the one before)"),
        ]

    def _relative(self) -> tuple[float, float, float, float]:
        """The supported point's displacement and velocity (x, y) against the structure."""
        u = self.u
        x, v, xs, vs = u["X"], u["V"], u["X_structure"], u["V_structure"]
        return (float(x[0]) - float(xs[0]), float(x[1]) - float(xs[1]), float(v[0]) - float(vs[0]),
                float(v[1]) - float(vs[1]))

    def _indicator(self) -> float:
        """The present stage's indicator (kernel.break_indicator); the fuse must not be at its last stage."""
        x, y, _, _ = self._relative()
        k, load = self._stages[int(self.state["broken"][0])]
        return break_indicator(x, y, k, load)

    def _break_through(self) -> None:
        """Every stage whose load the present displacement reaches breaks (the next one's too, if already over)."""
        while self.state["broken"][0] < len(self._stages) and self._indicator() >= 0.0:
            self.state["broken"] = self.state["broken"] + 1.0

    def _publish(self) -> None:
        """The outputs and the indicator's value ``g`` of the present state (kernel.publish, kernel.indicator_of)."""
        s, p, u, y = self.kernel_args()
        has, g = indicator_of(s, p, u)
        if has:
            s.g[0] = g
        publish(s, p, u, y)

    # -- the compiled kernel (components/kernels.py); do_step is the kernel's step -------------------------------
    STEP = staticmethod(step)
    KERNEL_EVENTS = True

    def kernel_state(self):
        st = self.state
        return FuseState(st["broken"], st["reported"], st["g"])

    def kernel_params(self):
        return self._kernel_p

    def indicators(self) -> np.ndarray:
        # the kernel's value (a stage broken by its step and not yet handed over: 1, crossed); none after the last
        # stage: nothing left to break
        s, reported = self.state["broken"][0], self.state["reported"][0]
        return self.state["g"].copy() if s > reported or s < len(self._stages) else np.zeros(0)

    def update_discrete(self, t, which):
        x, y, _, _ = self._relative()
        r = math.hypot(x, y)
        first = int(self.state["reported"][0])
        if self.state["broken"][0] <= first:
            self.state["broken"] = np.array([first + 1.0])
        self._break_through()
        self.state["reported"] = self.state["broken"].copy()
        self._publish()
        # the values of the stage that broke first (a second one broken at once shows in the stage reached)
        k, load = self._stages[first]
        values = {"F_elastic_N": k * r, "break_load_N": load, "X_m": [x, y]}
        if len(self._stages) > 1:
            values["stage"] = int(self.state["broken"][0])
        return {"kind": "break", "values": values}
