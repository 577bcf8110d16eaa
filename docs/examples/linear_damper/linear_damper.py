"""A linear spring-damper in place of a squeeze film damper: the worked example of docs/how-to/plugins.md.

    F_journal = -k (X_journal - X_housing) - c (V_journal - V_housing),   F_housing = -F_journal

The damper contract (see docs/how-to/plugins.md): journal and housing motion in, the force on the journal and its
reaction on the housing out, with the force's Jacobian (K_film = dF_journal/dX_journal, C_film =
dF_journal/dV_journal, row-major 2x2, so -k and -c on the diagonal here) for the bearing's linearly implicit
journal, and the dissipated power P_film = c |V_journal - V_housing|^2 (>= 0) for the thermal network.
"""
import numpy as np

from rotorcosim.components.contract import Component, Variable


class LinearDamper(Component):
    description = "linear spring-damper between journal and housing (plug-in example)"
    variables = (
        # defaults: the O-ring centering spring of damper #0 (5 254 N/mm) and the fast damper's film damping
        # at a centred journal and 40 degC (`rotorcosim damper-force --damper 0 --position 0 0 --velocity 0
        # 0.01 --temperature 40`: 29.1 N at 0.01 m/s)
        Variable("k", "parameter", unit="N/m", start=5.254e6, description="stiffness"),
        Variable("c", "parameter", unit="N.s/m", start=2.91e3, description="viscous damping"),
        Variable("X_journal", "input", 2, "m", "journal displacement (absolute)"),
        Variable("V_journal", "input", 2, "m/s", "journal velocity (absolute)"),
        Variable("X_housing", "input", 2, "m", "housing displacement (absolute)"),
        Variable("V_housing", "input", 2, "m/s", "housing velocity (absolute)"),
        Variable("F_journal", "output", 2, "N", "spring + damper force on the journal"),
        Variable("F_housing", "output", 2, "N", "reaction on the housing, -F_journal"),
        Variable("K_film", "output", 4, "N/m", "dF_journal/dX_journal, row-major", labels=("xx", "xy", "yx", "yy")),
        Variable("C_film", "output", 4, "N.s/m", "dF_journal/dV_journal, row-major", labels=("xx", "xy", "yx", "yy")),
        Variable("P_film", "output", 1, "W", "dissipated power c |V_journal - V_housing|^2"),
    )
    preferred_step = 1e-5

    def setup(self, t0=0.0):
        super().setup(t0)
        k, c = self.p["k"], self.p["c"]
        self.y["K_film"] = np.array([-k, 0.0, 0.0, -k])
        self.y["C_film"] = np.array([-c, 0.0, 0.0, -c])
        self._evaluate()

    def do_step(self, t, h):
        # memoryless: the force at the end of the step from the inputs the master gave for it
        self._evaluate()
        self.time = t + h

    def _evaluate(self):
        u = self.u
        dx = u["X_journal"] - u["X_housing"]
        dv = u["V_journal"] - u["V_housing"]
        f = -self.p["k"] * dx - self.p["c"] * dv
        self.y["F_journal"] = f
        self.y["F_housing"] = -f
        self.y["P_film"] = np.array([self.p["c"] * float(dv @ dv)])
