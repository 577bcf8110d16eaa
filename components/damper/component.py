"""Squeeze film damper components (paper sections 2.2 and 4.1, eq. (5)'s F_sfd; Fig. 7, Table 3).

The film force comes from the Reynolds equation of the non-rotating journal (reynolds_fe), with Guembel
cavitation (cavitation) and the SAE 30 viscosity at the oil temperature input (viscosity); the O-ring centering
spring acts in parallel. Two implementations share the ports and parameters:

* ``damper.fe`` (:class:`FEDamper`): the paper's direct FE solve at every call (milliseconds);
* ``damper.fast`` (:class:`FastDamper`): the exact FE structure plus a table over the eccentricity ratio (fast).

Conventions: positions and velocities of the journal relative to the housing, d = X_journal - X_housing,
w = V_journal - V_housing. F_film is the pressure force on the journal, F_spring = -k_spring d,
F_journal = F_film + F_spring, F_housing = -F_journal. P_film = -F_film . w (>= 0), the film's viscous power
loss; the damper is memoryless (film inertia neglected) and its inputs are held over a step, so this is also the
mean power over the step. The film force is evaluated at the inputs given for the step (end of step).
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np

from ..contract import Component, ContractError, Variable
from .fast import fast_film_force, film_table
from .reynolds_fe import build_mesh, fe_film_force
from .viscosity import sae30_viscosity

DATA = Path(__file__).with_name("data") / "dampers.toml"
with open(DATA, "rb") as _f:
    _DATA = tomllib.load(_f)
DAMPERS = {int(k): v for k, v in _DATA["damper"].items()}
FILM = _DATA["film"]
#: parameters that follow the ``damper`` selection (Table 3) unless set explicitly
GEOMETRY = ("radius", "length", "clearance", "supply_pressure", "k_spring")


class WallContactError(RuntimeError):
    """The journal reached the damper wall (eccentricity ratio >= 1): the film model no longer applies."""


def table3(damper: int) -> dict:
    """Table 3 data of damper 0 or 5 (SI units)."""
    if damper not in DAMPERS:
        raise ValueError(f"damper must be one of {sorted(DAMPERS)}, got {damper!r}")
    return dict(DAMPERS[damper])


class _Damper(Component):
    """Common ports, parameters, spring, viscosity and checks; subclasses provide :meth:`film_force`."""

    variables = (
        Variable("damper", "parameter", unit="1", start=0, type="Integer",
                 description="which damper of Table 3 (0 or 5) gives the geometry not set explicitly"),
        Variable("radius", "parameter", unit="m", start=DAMPERS[0]["radius"], description="journal radius"),
        Variable("length", "parameter", unit="m", start=DAMPERS[0]["length"], description="journal (film) length"),
        Variable("clearance", "parameter", unit="m", start=DAMPERS[0]["clearance"], description="radial clearance"),
        Variable("supply_pressure", "parameter", unit="Pa", start=DAMPERS[0]["supply_pressure"],
                 description="oil supply pressure at the journal ends (gauge)"),
        Variable("cavitation_pressure", "parameter", unit="Pa", start=FILM["cavitation_pressure"],
                 description="film rupture pressure (gauge), Guembel clipping"),
        Variable("cavitation", "parameter", unit="1", start=FILM["cavitation"], type="Boolean",
                 description="Guembel cavitation on (false: full film)"),
        Variable("k_spring", "parameter", unit="N/m", start=DAMPERS[0]["k_spring"],
                 description="O-ring centering spring stiffness"),
        Variable("n_theta", "parameter", unit="1", start=FILM["n_theta"], type="Integer",
                 description="FE elements around the circumference"),
        Variable("n_z", "parameter", unit="1", start=FILM["n_z"], type="Integer",
                 description="FE elements along the half length"),
        Variable("X_journal", "input", 2, "m", "journal displacement (absolute)"),
        Variable("V_journal", "input", 2, "m/s", "journal velocity (absolute)"),
        Variable("X_housing", "input", 2, "m", "housing displacement (absolute)"),
        Variable("V_housing", "input", 2, "m/s", "housing velocity (absolute)"),
        Variable("T_oil", "input", 1, "K", "squeeze-film oil temperature", start=303.15),
        Variable("F_journal", "output", 2, "N", "film + centering spring force on the journal"),
        Variable("F_housing", "output", 2, "N", "reaction on the housing, -F_journal"),
        Variable("F_film", "output", 2, "N", "squeeze film pressure force on the journal"),
        Variable("F_spring", "output", 2, "N", "centering spring force on the journal"),
        Variable("P_film", "output", 1, "W", "viscous power loss of the film (mean over the step)"),
        Variable("mu", "output", 1, "Pa.s", "oil viscosity at T_oil"),
    )
    preferred_step = 1e-5
    phases = frozenset({"TM"})

    def set_parameter(self, name, value):
        super().set_parameter(name, value)
        self.__dict__.setdefault("_explicit", set()).add(name)

    # -- set-up ----------------------------------------------------------------------------------------
    def setup(self, t0=0.0):
        super().setup(t0)
        p = self.p
        explicit = self.__dict__.get("_explicit", set())
        data = table3(p["damper"])
        for key in GEOMETRY:
            if key not in explicit:
                p[key] = float(data[key])
        for key in ("radius", "length", "clearance"):
            if not p[key] > 0.0:
                raise ContractError(f"{self.name}.{key} must be > 0, got {p[key]}")
        if p["k_spring"] < 0.0:
            raise ContractError(f"{self.name}.k_spring must be >= 0, got {p['k_spring']}")
        if p["n_theta"] < 8 or p["n_z"] < 2:
            raise ContractError(f"{self.name}: mesh n_theta={p['n_theta']} (>= 8), n_z={p['n_z']} (>= 2)")
        self._c = p["clearance"]
        self._k = p["k_spring"]
        self._ps, self._pcav, self._cav = p["supply_pressure"], p["cavitation_pressure"], bool(p["cavitation"])
        self._T = None
        self._mu = 0.0
        self._prepare()
        self.state = {}
        self._evaluate(t0)

    def _prepare(self):
        raise NotImplementedError

    def film_force(self, dx, dy, dvx, dvy, mu):
        """(Fx, Fy) of the film at relative position/velocity (journal minus housing)."""
        raise NotImplementedError

    # -- stepping --------------------------------------------------------------------------------------
    def viscosity(self, T):
        if T != self._T:
            try:
                self._mu = sae30_viscosity(T)
            except ValueError as exc:
                raise ContractError(f"{self.name}.T_oil: {exc}") from None
            self._T = T
        return self._mu

    def _relative(self, t):
        u = self.u
        xj, vj, xh, vh = u["X_journal"], u["V_journal"], u["X_housing"], u["V_housing"]
        dx, dy = float(xj[0] - xh[0]), float(xj[1] - xh[1])
        dvx, dvy = float(vj[0] - vh[0]), float(vj[1] - vh[1])
        if not math.isfinite(dx + dy + dvx + dvy):
            raise ContractError(f"{self.name}: non-finite journal/housing motion at t = {t:.9g} s")
        eps = math.hypot(dx, dy) / self._c
        if eps >= 1.0:
            raise WallContactError(
                f"{self.name}: the journal hit the damper wall at t = {t:.9g} s (eccentricity ratio {eps:.4f} >= 1,"
                f" clearance {self._c * 1e3:.4g} mm)")
        return dx, dy, dvx, dvy

    def _evaluate(self, t):
        dx, dy, dvx, dvy = self._relative(t)
        mu = self.viscosity(float(self.u["T_oil"][0]))
        fx, fy = self.film_force(dx, dy, dvx, dvy, mu)
        sx, sy = -self._k * dx, -self._k * dy
        y = self.y
        y["F_film"] = np.array([fx, fy])
        y["F_spring"] = np.array([sx, sy])
        y["F_journal"] = np.array([fx + sx, fy + sy])
        y["F_housing"] = np.array([-fx - sx, -fy - sy])
        y["P_film"] = np.array([-(fx * dvx + fy * dvy)])
        y["mu"] = np.array([mu])

    def do_step(self, t, h):
        self._evaluate(t + h)
        self.time = t + h

    def get_state(self):
        # memoryless: the snapshot is the time and the current inputs/outputs (cheap copies)
        return (self.time, {k: v.copy() for k, v in self.u.items()}, {k: v.copy() for k, v in self.y.items()})

    def set_state(self, snapshot):
        t, u, y = snapshot
        self.time = t
        self.u = {k: v.copy() for k, v in u.items()}
        self.y = {k: v.copy() for k, v in y.items()}

    def interface_jacobian(self):
        """d F_journal / d X_journal and d F_journal / d V_journal (2x2) by central differences of the film
        model (steps 1e-6 clearance and 1e-6 of the velocity scale) plus the exact spring term -k I."""
        dx, dy, dvx, dvy = self._relative(self.time)
        mu = self.viscosity(float(self.u["T_oil"][0]))
        c = self._c
        hx = 1e-6 * c
        eps = math.hypot(dx, dy) / c
        if eps + 2e-6 >= 1.0:
            hx = 0.25 * (1.0 - eps) * c
        hv = 1e-6 * max(math.hypot(dvx, dvy), 1e-3)
        base = np.array([dx, dy, dvx, dvy])
        J = np.empty((2, 4))
        for m, step in enumerate((hx, hx, hv, hv)):
            a, b = base.copy(), base.copy()
            a[m] += step
            b[m] -= step
            fa = np.array(self.film_force(*a, mu))
            fb = np.array(self.film_force(*b, mu))
            J[:, m] = (fa - fb) / (2.0 * step)
        JX = J[:, :2] - self._k * np.eye(2)
        return {("F_journal", "X_journal"): JX, ("F_journal", "V_journal"): J[:, 2:].copy()}


class FEDamper(_Damper):
    """Squeeze film damper, direct finite-element Reynolds solve at every call (the paper's model)."""

    description = "Squeeze film damper: direct FE Reynolds solution (Guembel cavitation) + O-ring centering spring"

    def _prepare(self):
        p = self.p
        self._mesh = build_mesh(p["radius"], p["length"], int(p["n_theta"]), int(p["n_z"]))

    def film_force(self, dx, dy, dvx, dvy, mu):
        return fe_film_force(self._mesh, self._c, dx, dy, dvx, dvy, mu, self._ps, self._pcav, self._cav)


class FastDamper(_Damper):
    """Squeeze film damper, the FE model's exact structure + a table over the eccentricity ratio (default)."""

    description = "Squeeze film damper: tabulated FE Reynolds fields (Guembel cavitation) + O-ring centering spring"

    def _prepare(self):
        p = self.p
        self._table = film_table(p["radius"], p["length"], p["clearance"], int(p["n_theta"]), int(p["n_z"]))

    def film_force(self, dx, dy, dvx, dvy, mu):
        return fast_film_force(self._table, dx, dy, dvx, dvy, mu, self._ps, self._pcav, self._cav)
