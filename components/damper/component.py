"""Squeeze film damper components (paper sections 2.2 and 4.1, eq. (5)'s F_sfd; Fig. 7, Table 3).

The film force comes from the Reynolds equation of the non-rotating journal (reynolds_fe), with Guembel
cavitation (cavitation) and the SAE 30 viscosity at the oil temperature input (viscosity); the O-ring centering
spring acts in parallel. Two implementations share the ports and parameters:

* ``damper.fe`` (:class:`FEDamper`): the paper's direct FE solve at every call (tens of milliseconds);
* ``damper.fast`` (:class:`FastDamper`): the exact FE structure plus a table over the eccentricity ratio (fast).

Conventions: positions and velocities of the journal relative to the housing, d = X_journal - X_housing,
w = V_journal - V_housing. F_film is the pressure force on the journal, F_spring = -k_spring d,
F_contact is the wall contact beyond the clearance (wall.py: a stiff radial spring, or an error with k_wall = 0),
F_journal = F_film + F_spring + F_contact, F_housing = -F_journal. K_film = dF_journal/dX_journal (film +
spring + contact) and C_film = dF_journal/dV_journal (row-major 2x2) at the evaluated state feed the bearing's
linearly implicit journal integration (frame.py: exact derivatives of each model, no finite differences).
P_film = -F_film . w (>= 0), the film's viscous power
loss; the damper is memoryless (film inertia neglected) and its inputs are held over a step, so this is also the
mean power over the step. The film force is evaluated at the inputs given for the step (end of step).
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np

from ..contract import Component, ContractError, Memoryless, Variable
from ..errors import Diverged
from ..kernels import KernelComponent
from ..oil_fit import T_MAX_K, T_MIN_K
# ``damper`` = NO_RECORD: no record of the paper's Table 3; every one of GEOMETRY is given
from ..records import NO_RECORD, check_selection
from ..validity import Check
from . import wall
from . import table_cache
from .fast import (EPS_MAX, FAST_STEP_SIG, N_TABLE, DamperParams, DamperState, fast_step, fast_step_address,
                   film_table, tm_step)
from .reynolds_fe import EPS_FILM_MAX, build_mesh, fe_film_eval
from .supply import condition
from .viscosity import oil_constants, sae30_viscosity

DATA = Path(__file__).with_name("data") / "dampers.toml"
with open(DATA, "rb") as _f:
    _DATA = tomllib.load(_f)
DAMPERS = {int(k): v for k, v in _DATA["damper"].items()}
FILM = _DATA["film"]
#: parameters that follow the ``damper`` selection (Table 3) unless set explicitly
GEOMETRY = ("radius", "length", "clearance", "supply_pressure", "k_spring")
#: the largest radial clearance over journal radius the film model accepts: the Reynolds equation (eq. 7) is the
#: thin-film limit, its neglected terms of order c/R (Szeri, Fluid Film Lubrication, ch. 2); squeeze film dampers
#: run at c/R ~ 1e-3 (Table 3: 0.635 mm / 80 mm = 0.008), so 0.05 refuses only what is not a film (or is mm read
#: as m). An input check: no result of a valid case depends on it.
THIN_FILM = 0.05
#: largest film Reynolds number rho |V| c / mu of a journal velocity V the film model takes: the Reynolds equation
#: (eq. 7) is laminar lubrication theory, and film flows turn turbulent from Re ~ 1000-2000 (Hamrock, Schmid &
#: Jacobson, Fundamentals of Fluid Film Lubrication, 2nd ed., 2004, ch. 4, and Szeri ch. 7 on turbulent films).
#: The blade-loss runs stay below ~20 (0.17 m/s whirl velocity at 0.635 mm and 11 cP: Re ~ 9); an input check of
#: `rotorcosim damper-force` (--velocity 1e9 was computed), no run depends on it.
LAMINAR_FILM_RE = 1000.0
#: the largest film mesh (n_theta x n_z nodes), 16 times the paper's 128 x 64: the fast model's table (60 sparse
#: factorisations) took 5.4 s at 128 x 64 and 43 s at 256 x 128 (measured, ROTORCOSIM_CACHE=off), growing about as
#: nodes^1.5, so ~6 min here and hours beyond; n_theta = 100000 reached 2.6 GB in a minute with no end in sight
MAX_MESH_NODES = 16 * 128 * 64


class WallContactError(Diverged):
    """The journal reached the damper wall (eccentricity ratio >= 1): the film model no longer applies."""


def table3(damper: int) -> dict:
    """Table 3 data of damper 0 or 5 (SI units)."""
    if damper not in DAMPERS:
        raise ValueError(f"damper must be one of {sorted(DAMPERS)}, got {damper!r}")
    return dict(DAMPERS[damper])


class _Damper(Memoryless, Component):
    """Common ports, parameters, spring, viscosity and checks; subclasses provide :meth:`film_force`."""

    variables = (
        Variable("damper", "parameter", unit="1", start=NO_RECORD, type="Integer",
                 description="which damper of the paper's Table 3 (0 or 5) gives the geometry not set explicitly; "
                             "-1 (default): none, radius, length, clearance, supply_pressure and k_spring are all "
                             "given (a scenario takes them from its engine file's [damper.ID])"),
        # plausible ranges (a wider band around aircraft-engine practice: San Andres, "Squeeze film dampers:
        # operation, models and technical issues", Texas A&M Turbomachinery Laboratory notes, 2010: radial
        # clearances 0.1-0.5 mm, journal diameters 50-300 mm, L/D 0.1-0.5, centering springs 1-50 MN/m,
        # supply pressures up to a few bar); Table 3's values sit inside each
        Variable("radius", "parameter", unit="m", start=DAMPERS[0]["radius"], description="journal radius",
                 plausible=(0.01, 0.5)),
        Variable("length", "parameter", unit="m", start=DAMPERS[0]["length"], description="journal (film) length",
                 plausible=(0.003, 0.2)),
        Variable("clearance", "parameter", unit="m", start=DAMPERS[0]["clearance"], description="radial clearance",
                 plausible=(2e-5, 2e-3)),
        Variable("supply_pressure", "parameter", unit="Pa", start=DAMPERS[0]["supply_pressure"],
                 description="oil supply pressure at the journal ends (gauge)", plausible=(0.0, 2e6)),
        Variable("cavitation_pressure", "parameter", unit="Pa", start=FILM["cavitation_pressure"],
                 description="film rupture pressure (gauge), Guembel clipping"),
        Variable("cavitation", "parameter", unit="1", start=FILM["cavitation"], type="Boolean",
                 description="Guembel cavitation on (false: full film)"),
        Variable("k_spring", "parameter", unit="N/m", start=DAMPERS[0]["k_spring"],
                 description="O-ring centering spring stiffness", plausible=(1e5, 1e8)),
        Variable("n_theta", "parameter", unit="1", start=FILM["n_theta"], type="Integer",
                 description="FE elements around the circumference"),
        Variable("n_z", "parameter", unit="1", start=FILM["n_z"], type="Integer",
                 description="FE elements along the half length"),
        Variable("k_wall", "parameter", unit="N/m", start=FILM["k_wall"],
                 description="journal-housing contact stiffness beyond the clearance (0: touching the wall is an"
                             " error)"),
        Variable("oil_loss_time", "parameter", unit="s", start=-1.0,
                 description="time at which the oil supply is lost: no film from then on, the journal on the land "
                             "(k_wall, land_friction), no film power (< 0: never)",
                 event="the loss of the oil supply"),
        Variable("oil_loss_eccentricity", "parameter", unit="1", start=0.0,
                 description="journal eccentricity ratio |X_journal - X_housing| / clearance at which the oil supply "
                             "is lost, as at oil_loss_time (an event located in time; 0: never)"),
        Variable("event_tolerance", "parameter", unit="s", start=1e-7,
                 description="time to which the master locates the oil_loss_eccentricity event (at most the step)"),
        Variable("land_friction", "parameter", unit="1", start=FILM["land_friction"],
                 description="friction coefficient of the journal on the damper land once the oil supply is lost"),
        Variable("power_in_thermal_only", "parameter", unit="1", start=True, type="Boolean",
                 description="in thermal-only intervals, update the film power from the frozen journal motion at "
                             "the SFD oil viscosity (the master's hold follows it, master/manipulator/hold.py); false: held"),
        Variable("X_journal", "input", 2, "m", "journal displacement (absolute)"),
        Variable("V_journal", "input", 2, "m/s", "journal velocity (absolute)"),
        Variable("X_housing", "input", 2, "m", "housing displacement (absolute)"),
        Variable("V_housing", "input", 2, "m/s", "housing velocity (absolute)"),
        Variable("T_oil", "input", 1, "K", "squeeze-film oil temperature", start=303.15),
        Variable("F_journal", "output", 2, "N", "film + centering spring force on the journal"),
        Variable("F_housing", "output", 2, "N", "reaction on the housing, -F_journal"),
        Variable("F_film", "output", 2, "N", "squeeze film pressure force on the journal"),
        Variable("F_spring", "output", 2, "N", "centering spring force on the journal"),
        Variable("F_contact", "output", 2, "N", "journal-housing wall contact force on the journal"),
        Variable("K_film", "output", 4, "N/m",
                 "dF_journal/dX_journal, row-major [dFx/dx, dFx/dy, dFy/dx, dFy/dy] (film + spring + contact)",
                 labels=("xx", "xy", "yx", "yy")),
        Variable("C_film", "output", 4, "N.s/m", "dF_journal/dV_journal, row-major (film)",
                 labels=("xx", "xy", "yx", "yy")),
        Variable("P_film", "output", 1, "W", "viscous power loss of the film, -F_film . w, at the end of the step"),
        Variable("mu", "output", 1, "Pa.s", "oil viscosity at T_oil"),
    )
    preferred_step = 1e-5
    phases = frozenset({"TM"})
    step_cost_s, kernel_step_cost_s, setup_cost_s = 10e-6, 1e-6, 0.05  # the fast damper's; bench/bench_estimate.py

    #: layout of the evaluation vector: name -> slice (F_housing and mu are added separately)
    OUT = {"F_film": slice(0, 2), "K_film": slice(2, 6), "C_film": slice(6, 10), "F_spring": slice(10, 12),
           "F_contact": slice(12, 14), "F_journal": slice(14, 16), "P_film": slice(16, 17)}
    N_OUT = 19

    # -- set-up ----------------------------------------------------------------------------------------
    def setup(self, t0=0.0):
        super().setup(t0)
        p = self.p
        explicit = self.explicit
        check_selection(self, "damper", DAMPERS, GEOMETRY, what="Table 3 record", tables="[damper.ID]",
                        label=" (Table 3)")
        data = table3(p["damper"]) if p["damper"] != NO_RECORD else {}
        for key in GEOMETRY:
            if key not in explicit:
                p[key] = float(data[key])
        for key in ("radius", "length", "clearance"):
            if not p[key] > 0.0:
                raise ContractError(f"{self.name}.{key} must be > 0, got {p[key]}")
        for key in ("k_spring", "k_wall", "supply_pressure", "land_friction"):
            if not p[key] >= 0.0:   # (NaN too)
                raise ContractError(f"{self.name}.{key} must be >= 0, got {p[key]}")
        if not math.isfinite(p["oil_loss_time"]):
            raise ContractError(f"{self.name}.oil_loss_time must be a time in s (< 0: never), got {p['oil_loss_time']}")
        if p["oil_loss_time"] >= 0.0 and p["k_wall"] <= 0.0:
            raise ContractError(f"{self.name}.k_wall must be > 0 with oil_loss_time = {p['oil_loss_time']:g} s: "
                                "without its oil the journal runs on the damper land, a contact of that stiffness")
        e_loss = p["oil_loss_eccentricity"]
        if not 0.0 <= e_loss <= 1.0:   # (NaN too)
            raise ContractError(f"{self.name}.oil_loss_eccentricity must be within [0, 1] (an eccentricity ratio; "
                                f"0: never), got {e_loss}")
        if e_loss > 0.0 and p["k_wall"] <= 0.0:
            raise ContractError(f"{self.name}.k_wall must be > 0 with oil_loss_eccentricity = {e_loss:g}: without "
                                "its oil the journal runs on the damper land, a contact of that stiffness")
        if not p["event_tolerance"] > 0.0:
            raise ContractError(f"{self.name}.event_tolerance must be > 0 s, got {p['event_tolerance']}")
        if p["clearance"] > THIN_FILM * p["radius"]:
            # the film equation (eq. 7, Reynolds) drops terms of order c/R: a thick "film" is outside the model,
            # and in practice a length given in mm where metres are meant (0.635 -> 0.635 m)
            hint = (f"; lengths are in metres: {p['clearance']:g} mm = {p['clearance'] * 1e-3:g} m"
                    if p["clearance"] * 1e-3 <= THIN_FILM * p["radius"] else "")
            raise ContractError(f"{self.name}.clearance = {p['clearance']:g} m is not a thin film against the "
                                f"journal radius {p['radius']:g} m (c/R = {p['clearance'] / p['radius']:.3g} > "
                                f"{THIN_FILM:g}, the Reynolds equation's assumption){hint}")
        if p["n_theta"] < 8 or p["n_z"] < 2:
            raise ContractError(f"{self.name}: mesh n_theta={p['n_theta']} (>= 8), n_z={p['n_z']} (>= 2)")
        if p["n_theta"] * p["n_z"] > MAX_MESH_NODES:
            raise ContractError(f"{self.name}: mesh n_theta x n_z = {p['n_theta']} x {p['n_z']} = "
                                f"{p['n_theta'] * p['n_z']:.4g} nodes, above {MAX_MESH_NODES} (16 times the paper's "
                                f"{FILM['n_theta']} x {FILM['n_z']}): its film table would take hours to build")
        if p["cavitation"] and p["cavitation_pressure"] > p["supply_pressure"]:
            raise ContractError(f"{self.name}.cavitation_pressure = {p['cavitation_pressure']:g} Pa must not exceed "
                                f"the supply pressure ({p['supply_pressure']:g} Pa, gauge): the film ruptures below "
                                "the pressure it is fed at, never above it")
        self._c = p["clearance"]
        self._k = p["k_spring"]
        self._kw = p["k_wall"]
        self._ps, self._pcav, self._cav = p["supply_pressure"], p["cavitation_pressure"], bool(p["cavitation"])
        self._floor = self._pcav - self._ps
        self._T = None
        self._mu = 0.0
        self._prepare()
        #: oil_lost: 1 once the oil supply is lost (update_discrete at oil_loss_time, or the step that met
        #: oil_loss_eccentricity); reported: 1 once the loss is handed over (update_discrete); g: the condition's
        #: indicator (supply.py)
        self.state = {"oil_lost": np.zeros(1), "reported": np.zeros(1), "g": np.full(1, -1.0)}
        self.phases = frozenset({"TM", "TO"}) if p["power_in_thermal_only"] else frozenset({"TM"})
        self.holds_state_in_TO = bool(p["power_in_thermal_only"])
        self.phase = "TM"
        self._evaluate(t0)
        if self.state["oil_lost"][0]:
            dx, dy, _, _ = self._relative()
            raise ContractError(f"{self.name}.oil_loss_eccentricity = {e_loss:g}: the journal starts at eccentricity "
                                f"ratio {math.hypot(dx, dy) / self._c:.4g}, at or beyond it")

    @property
    def event_indicators(self):
        """``("oil_loss",)`` with an ``oil_loss_eccentricity`` (supply.py), else none: a damper without the condition
        is no concern of the event location."""
        return ("oil_loss",) if self.p.get("oil_loss_eccentricity", 0.0) > 0.0 else ()

    def indicators(self):
        st = self.state
        live = self.event_indicators and not st["reported"][0]
        return st["g"].copy() if live else np.zeros(0)

    def _prepare(self):
        raise NotImplementedError

    def _compute(self, mu: float, out: np.ndarray) -> int:
        """Fill ``out`` (layout OUT) from the inputs at viscosity mu; return a wall.* status code."""
        raise NotImplementedError

    # -- the loss of the oil supply: a time event or on a condition (master/core/events.py, supply.py) ---------
    def get_state(self):
        st = self.state
        return (*super().get_state(), st["oil_lost"].copy(), st["reported"].copy(), st["g"].copy())

    def set_state(self, snapshot):
        *snap, lost, reported, g = snapshot
        super().set_state(tuple(snap))
        st = self.state
        st["oil_lost"][0], st["reported"][0], st["g"][0] = lost[0], reported[0], g[0]

    def next_event(self, t):
        """The loss of the oil supply while it is to come (at ``t`` itself too, as the spool's fuel cut)."""
        te = self.p["oil_loss_time"]
        return float(te) if te >= 0.0 and not self.state.get("oil_lost", [0.0])[0] and te >= t - 1e-9 else None

    def update_discrete(self, t, which):
        """The oil supply lost at ``t`` (``which`` empty: at ``oil_loss_time``; else its condition,
        ``oil_loss_eccentricity``, met): the film goes, its power drops to zero, the journal runs on the land from
        this state on (the outputs re-evaluated at the present inputs). The values: the film power it had (on the
        condition, whose step already ended on the land: the film's at the present motion) and the eccentricity
        ratio."""
        before = float(self.y["P_film"][0]) if not which else self._film_power()
        st = self.state
        st["oil_lost"][0] = 1.0
        st["reported"][0] = 1.0
        if self.phase == "TO" and self.holds_state_in_TO:
            self._thermal_only_step(t, 0.0)
        else:
            self._evaluate(t)
        dx, dy, _, _ = self._relative()
        values = {"P_film_W": before, "eccentricity_ratio": math.hypot(dx, dy) / self._c}
        if which:
            values["oil_loss_eccentricity"] = float(self.p["oil_loss_eccentricity"])
        return {"kind": "oil_supply_loss", "values": values}

    def _film_power(self) -> float:
        """The film's power at the present motion and oil temperature, -F_film . w [W] (the oil still there)."""
        dx, dy, dvx, dvy = self._relative()
        out = np.zeros(self.N_OUT)
        self._film(dx, dy, dvx, dvy, self.viscosity(float(self.u["T_oil"][0])), out)
        return -(float(out[0]) * dvx + float(out[1]) * dvy)

    # -- stepping --------------------------------------------------------------------------------------
    def viscosity(self, T):
        if T != self._T:
            try:
                self._mu = sae30_viscosity(T)
            except ValueError as exc:
                raise ContractError(f"{self.name}.T_oil: {exc}") from None
            self._T = T
            self._mu_out = np.array([self._mu])   # a new array when mu changes: held outputs stay valid
        return self._mu

    def _relative(self):
        u = self.u
        d = u["X_journal"] - u["X_housing"]
        w = u["V_journal"] - u["V_housing"]
        return float(d[0]), float(d[1]), float(w[0]), float(w[1])

    def _evaluate(self, t):
        mu = self.viscosity(float(self.u["T_oil"][0]))
        out = np.empty(self.N_OUT)   # fresh each call: the outputs below are views of it
        status = self._compute(mu, out)
        if status != wall.OK:
            self._fail(status, t)
        y = self.y
        y["F_film"] = out[0:2]
        y["K_film"] = out[2:6]
        y["C_film"] = out[6:10]
        y["F_spring"] = out[10:12]
        y["F_contact"] = out[12:14]
        y["F_journal"] = out[14:16]
        y["P_film"] = out[16:17]
        y["F_housing"] = -out[14:16]
        y["mu"] = self._mu_out

    def _fail(self, status, t):
        if status == wall.NOT_FINITE:
            raise ContractError(f"{self.name}: non-finite journal/housing motion at t = {t:.9g} s "
                                f"(X_journal={self.u['X_journal']}, V_journal={self.u['V_journal']}, "
                                f"X_housing={self.u['X_housing']}, V_housing={self.u['V_housing']})")
        dx, dy, _, _ = self._relative()
        eps = math.hypot(dx, dy) / self._c
        if status == wall.WALL_ERROR:
            raise WallContactError(
                f"{self.name}: the journal hit the damper wall at t = {t:.9g} s (eccentricity ratio {eps:.4f} >= 1,"
                f" clearance {self._c * 1e3:.4g} mm) and the wall contact is off (k_wall = 0)")
        raise WallContactError(
            f"{self.name}: the journal is {(eps - 1.0) * self._c * 1e3:.4g} mm into the damper wall at t = {t:.9g} s"
            f" (eccentricity ratio {eps:.3f} >= {wall.EPS_DIVERGED}): the simulation diverged")

    def do_step(self, t, h):
        if self.phase == "TO" and self.holds_state_in_TO:
            self._thermal_only_step(t, h)
            return
        st = self.state
        dx, dy, _, _ = self._relative()
        condition(st["oil_lost"], st["reported"], st["g"], self.p["oil_loss_eccentricity"], self._c, dx, dy)
        self._evaluate(t + h)
        self.time = t + h

    def _thermal_only_step(self, t, h):
        """Thermal-only interval (TO update): the journal motion stays as it froze; only the film power follows
        the oil viscosity at the input T_oil (the film's pressures, at fixed kinematics, scale with it). The
        forces keep their frozen values (their consumer, the bearing, is frozen too)."""
        mu = self.viscosity(float(self.u["T_oil"][0]))
        out = np.empty(self.N_OUT)
        status = self._compute(mu, out)
        if status != wall.OK:
            self._fail(status, t + h)
        self.y["P_film"] = out[16:17]
        self.time = t + h

    def validity(self):
        """The journal inside the part of its clearance the film model resolves (eccentricity ratio up to
        reynolds_fe.EPS_FILM_MAX: beyond it the film is held at its value there and, from 1 on, the wall model of
        wall.py takes over); a laminar film (Reynolds number of the journal's velocity below LAMINAR_FILM_RE).
        The eccentricity is read from the spring's force F_spring = -k_spring d: without a spring it is not
        checked. Not checked: the film's inertia, which the paper's model (and this one) neglects. Its squeeze-film
        Reynolds number rho omega c^2 / mu at the running speed is 4 (cold oil) to 7 at 2850 N and up to 50 at
        14 252 N (damper #0's oil at 43-98 C), where lubrication theory is strictly valid only well below 1 (direct
        force measurements, ASME Gas Turbine Conference 1984, GT1984-V005T13A003: up to twice the inertialess
        theory's forces at 10): a limit of the model at every load of the paper, not of a result, and the damper
        knows no whirl frequency to compute it from."""
        c, k = self.p["clearance"], self.p["k_spring"]
        _, _, rho300, drho = oil_constants()

        def eccentricity(y):
            f = y["F_spring"]
            return np.hypot(f[:, 0], f[:, 1]) / (k * c)

        def reynolds(y):
            w = y["V_journal"] - y["V_housing"]
            rho = rho300 + drho * (y["T_oil"][:, 0] - 300.0)
            return rho * np.hypot(w[:, 0], w[:, 1]) * c / y["mu"][:, 0]

        checks = [Check("film Reynolds number", ("V_journal", "V_housing", "T_oil", "mu"), reynolds, LAMINAR_FILM_RE,
                        "1", "laminar lubrication theory (Reynolds equation): films turn turbulent from ~1000 "
                        "(Hamrock, Schmid & Jacobson, Fundamentals of Fluid Film Lubrication, ch. 4)")]
        if k > 0.0:
            checks.insert(0, Check("journal eccentricity ratio", ("F_spring",), eccentricity, EPS_FILM_MAX, "1",
                                   f"the film is evaluated up to {EPS_FILM_MAX:g} (closer to the wall the FE mesh no "
                                   "longer resolves the minimum film); beyond, it is held there, and the wall "
                                   "model acts from 1"))
        return tuple(checks)

    def film_force(self, dx, dy, dvx, dvy, mu):
        """(Fx, Fy) of the film alone at relative position/velocity (journal minus housing)."""
        out = np.empty(self.N_OUT)
        self._film(dx, dy, dvx, dvy, mu, out)
        return float(out[0]), float(out[1])

class FEDamper(_Damper):
    """Squeeze film damper, direct finite-element Reynolds solve at every call (the paper's model)."""

    description = "Squeeze film damper: direct FE Reynolds solution (Guembel cavitation) + O-ring centering spring"
    #: CPU seconds of one step per (mesh nodes)^1.5, the sparse solve's growth: 21 ms at the paper's 128 x 64
    #: mesh (bench/bench_estimate.py)
    STEP_COST_PER_NODE_1_5 = 3.0e-8

    @classmethod
    def step_cost(cls, parameters, compiled):
        start = {v.name: v.start for v in cls.variables}
        nodes = int(parameters.get("n_theta", start["n_theta"])) * int(parameters.get("n_z", start["n_z"]))
        return cls.STEP_COST_PER_NODE_1_5 * nodes ** 1.5

    def _prepare(self):
        p = self.p
        self._mesh = build_mesh(p["radius"], p["length"], int(p["n_theta"]), int(p["n_z"]))

    def _film(self, dx, dy, dvx, dvy, mu, out):
        fe_film_eval(self._mesh, self._c, dx, dy, dvx, dvy, mu, self._floor, self._cav, out)

    def _compute(self, mu, out):
        dx, dy, dvx, dvy = self._relative()
        if not math.isfinite(dx + dy + dvx + dvy):
            return wall.NOT_FINITE
        if self.state["oil_lost"][0]:
            return wall.dry_land(dx, dy, dvx, dvy, self._c, self._k, self._kw, self.p["land_friction"], out)
        out[:] = 0.0
        if math.hypot(dx, dy) < wall.EPS_DIVERGED * self._c:
            self._film(dx, dy, dvx, dvy, mu, out)
        out[16] = -(out[0] * dvx + out[1] * dvy)
        return wall.spring_and_wall(dx, dy, self._c, self._k, self._kw, out)


class FastDamper(KernelComponent, _Damper):
    """Squeeze film damper, the FE model's exact structure + a table over the eccentricity ratio (default)."""

    description = "Squeeze film damper: tabulated FE Reynolds fields (Guembel cavitation) + O-ring centering spring"

    def _prepare(self):
        p = self.p
        self._table = film_table(p["radius"], p["length"], p["clearance"], int(p["n_theta"]), int(p["n_z"]))
        t = self._table
        prm = np.array([t.u0, t.du, t.n, t.eps_max, t.clearance, self._floor, float(self._cav), self._k, self._kw,
                        float(p["land_friction"]), float(p["oil_loss_eccentricity"])])
        A, B, rho300, drho = oil_constants()
        self._kernel_p = DamperParams(t.NT, t.G, t.TW, t.toff, t.ftab, t.bounds, t.Wc, t.Ws, prm, np.zeros(self.N_OUT),
                                      np.full(2, np.nan), float(A), float(B), float(rho300), float(drho),
                                      T_MIN_K, T_MAX_K, fast_step_address())

    def prebuild(self):
        """The film table of this geometry (when not in the cache) and the film kernel (contract.prebuild)."""
        p = self.p
        try:
            data = table3(p["damper"])
            geo = tuple(float(p[k] if k in self.explicit else data[k]) for k in ("radius", "length", "clearance"))
            args = geo + (int(p["n_theta"]), int(p["n_z"]))
            k = table_cache.key(*args, N_TABLE, EPS_MAX)
        except (ValueError, KeyError, TypeError):
            return []
        # the kernel first: the longest, and needed right after the table, which this process can build while the
        # helper compiles (a helper building the table first leaves this process waiting for the kernel)
        jobs = [(None, fast_step, FAST_STEP_SIG)]
        if table_cache.enabled() and not table_cache.exists(k):
            jobs.append((f"damper/{k}", film_table, args))
        return jobs

    def _film(self, dx, dy, dvx, dvy, mu, out):
        self._table.evaluate(dx, dy, dvx, dvy, mu, self._floor, self._cav, out)

    # -- the compiled kernel (components/kernels.py): set-up and every step evaluate through it -------------
    STEP = staticmethod(tm_step)

    #: its kernel reports the oil supply's condition met (supply.py): the compiled loop stops there
    KERNEL_EVENTS = True

    def kernel_state(self):
        st = self.state
        return DamperState(st["oil_lost"], st["reported"], st["g"])

    def kernel_params(self):
        return self._kernel_p

    def kernel_available(self):
        return not (self.phase == "TO" and self.holds_state_in_TO)

    def do_step(self, t, h):
        if self.phase == "TO" and self.holds_state_in_TO:
            self._thermal_only_step(t, h)
            return
        self.kernel_step(t, h)

    def _compute(self, mu, out):
        """The film, spring and wall at viscosity mu (the thermal-only update's evaluation)."""
        p, u = self._kernel_p, self.u
        if self.state["oil_lost"][0]:
            dx, dy, dvx, dvy = self._relative()
            return wall.dry_land(dx, dy, dvx, dvy, self._c, self._k, self._kw, self.p["land_friction"], out)
        return fast_step(p.NT, p.G, p.TW, p.toff, p.ftab, p.bounds, p.Wc, p.Ws, p.prm, u["X_journal"], u["V_journal"],
                         u["X_housing"], u["V_housing"], mu, out)

    def kernel_status(self, status, t, h):
        if status == 5:
            self.viscosity(float(self.u["T_oil"][0]))      # names the fit's range
        if status >= 10:
            self._fail(status - 10, t + h)
        raise RuntimeError(f"{self.name}: kernel status {status} at t = {t + h:.9g} s")

    def _evaluate(self, t):
        self.kernel_step(t, 0.0)
        self.time = t
