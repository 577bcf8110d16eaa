"""The spool component: one rotor's speed and angle as signals, prescribed or from its torque balance.

``profile`` picks the law:

* ``"constant"``: ``speed_rpm`` throughout;
* ``"ramp"``: ``speed_rpm`` until ``t_start``, linear to ``end_speed_rpm`` over ``duration``, then held;
* ``"table"``: ``table = "t rpm, t rpm, ..."`` (s, rev/min), linear in between, held outside;
* ``"torque"``: ``J dOmega/dt = T_drive - T_drag - T_rub - T_aero(Omega)`` from ``speed_rpm``: the drive (the
  turbine, its governor holding the speed) until the fuel is cut at ``t_fuel_cut``, then none; ``T_drag`` the
  bearings' drag torques (inputs) plus the spool's other bearings as a viscous ``drag_coefficient`` Omega;
  ``T_rub`` the rub rings' friction torques (inputs); ``T_aero = c (Omega - Omega_wm) |Omega - Omega_wm|`` the
  windmilling law, zero at the windmill speed ``windmill_rpm``, ``c`` set by its value ``aero_torque`` at
  ``speed_rpm`` (below the windmill speed the airflow drives the spool).

``flight_profile`` (a CSV file of time against flight condition, flight_profile.py; empty: none) makes the
windmilling law follow the flight: ``windmill_rpm`` and ``aero_torque`` are then the values at the profile's first
row, and at time t the windmill speed and ``c`` are scaled by turbomachinery similarity to the flight condition
there (windmill.py: the windmill speed with Walsh & Fletcher's referred windmilling speed at the Mach number times
``sqrt(theta)``, ``c`` with the inlet's total density ``delta / theta``), linear in time between rows.

The torque inputs are ``T_drag1`` .. ``T_dragN`` and ``T_rub1`` .. ``T_rubM``: one per co-simulated bearing and
rub ring of the engine file ``model_file`` on spool ``spool``, at least two of each (ports.py).

``inertia`` J [kg m^2]: 0 takes the polar inertia of rotor ``spool`` of the model file ``model_file``
(rotor/spool_inertia.py). Speeds are given in rev/min (the edge), outputs are SI: ``Omega`` [rad/s], ``theta``
[rad] (the integral of Omega from set-up), ``dOmega`` [rad/s^2], the torques, and ``energy`` = (kinetic energy,
work of the drive, drag, rub and aerodynamic torques) [J], whose balance (kernel.py) the run's summary reports.
It runs in thermal-only intervals too (its torque inputs then held by the master at their mean over the last
rotor cycles): the speed drifts with them.

Example (a scenario)::

    [components.spool]
    implementation = "spool.speed"
    parameters = { profile = "ramp", speed_rpm = 9000, end_speed_rpm = 3000, t_start = 0.0, duration = 1.0 }
"""
from __future__ import annotations

import math

import numpy as np

from ..contract import COUPLED, HELD, ContractError, Variable
from ..kernels import KernelComponent
from ..rotor.model import load_data
from ..speeds import PT_SPEED_RPM
from .kernel import CONSTANT, TABLE, TORQUE, SpoolParams, SpoolState, tm_step
from .ports import kind_of, torque_layout, torque_variables
from .flight_profile import read_profile
from .profile import RPM, cumulative_angle, parse_table, ramp_table
from .windmill import scales

PROFILES = {"constant": CONSTANT, "ramp": TABLE, "table": TABLE, "torque": TORQUE}
ENERGY_LABELS = ("kinetic", "drive", "drag", "rub", "aero")
#: how far past its time [s] an event still counts as to come (interval ends are sums of steps: round-off)
EVENT_TOL = 1e-9


class Spool(KernelComponent):
    """A spool's speed, angle and torque balance (module docstring)."""

    description = "spool speed and angle: prescribed profile or torque balance J dOmega/dt = sum of torques"
    file_parameters = ("model_file", "flight_profile")
    variables = (
        Variable("profile", "parameter", unit="1", start="constant", type="String",
                 description="constant | ramp | table | torque"),
        Variable("speed_rpm", "parameter", unit="rpm", start=PT_SPEED_RPM,
                 description="start speed (the constant speed; the ramp's start; the torque balance's start), rev/min"),
        Variable("end_speed_rpm", "parameter", unit="rpm", start=PT_SPEED_RPM, description="ramp end speed, rev/min"),
        Variable("t_start", "parameter", unit="s", start=0.0, description="ramp start time"),
        Variable("duration", "parameter", unit="s", start=1.0, description="ramp duration"),
        Variable("table", "parameter", unit="1", start="", type="String",
                 description="speed table \"t rpm, t rpm, ...\" (s, rev/min), times increasing"),
        Variable("inertia", "parameter", unit="kg.m2", start=0.0,
                 description="polar moment of inertia J (0: from the rotor model file's spool)"),
        Variable("model_file", "parameter", unit="1", start="", type="String",
                 description="the engine file whose spool `spool` this is: J when inertia is 0, one torque "
                             "input per bearing and rub ring on the spool (a scenario gives \"engine:file\")"),
        Variable("spool", "parameter", unit="1", start="pt", type="String",
                 description="the spool of the model file ([spool.NAME]) this one is (for J and its torque "
                             "inputs)"),
        Variable("t_fuel_cut", "parameter", unit="s", start=-1.0,
                 description="torque law: the turbine drives (holds the speed) until this time (< 0: never cut)",
                 event="the fuel cut"),
        Variable("windmill_rpm", "parameter", unit="rpm", start=0.0,
                 description="torque law: the speed at which the aerodynamic torque vanishes, rev/min"),
        Variable("aero_torque", "parameter", unit="N.m", start=0.0,
                 description="torque law: aerodynamic drag torque at speed_rpm (sets c of c (W - W_wm)|W - W_wm|)"),
        Variable("flight_profile", "parameter", unit="1", start="", type="String",
                 description="windmilling law: CSV of time against flight condition (time_s with altitude_m or "
                             "altitude_ft and mach, or airspeed_m_s and density_kg_m3) that scales windmill_rpm and "
                             "aero_torque, given at its first row, by similarity (empty: they hold throughout)"),
        Variable("drag_coefficient", "parameter", unit="N.m.s", start=0.0,
                 description="viscous drag torque per rad/s of the spool's bearings not modelled as components"),
    ) + torque_variables(None) + (   # an instance declares those of its model file's spool (__init__)
        Variable("Omega", "output", 1, "rad/s", "spool speed"),
        Variable("theta", "output", 1, "rad", "spool angle (integral of Omega from set-up)"),
        Variable("dOmega", "output", 1, "rad/s2", "spool angular acceleration"),
        Variable("T_drive", "output", 1, "N.m", "drive torque (a prescribed profile: the one it implies)"),
        Variable("T_aero", "output", 1, "N.m", "aerodynamic (windmilling) drag torque"),
        Variable("energy", "output", 5, "J", "kinetic energy; work of the drive, drag, rub, aerodynamic torques",
                 labels=ENERGY_LABELS),
    )
    preferred_step = 1e-4
    phases = frozenset({COUPLED, HELD})

    def __init__(self, name: str = "spool", parameters=None):
        # the torque inputs follow the model file's bearings and rub rings on this spool (ports.py). A file that
        # cannot be read keeps the class's ports here; setup names its problem.
        params = parameters or {}
        self._model = None
        if params.get("model_file"):
            try:
                self._model, _ = load_data(str(params["model_file"]))
            except (ValueError, OSError):
                pass
        if self._model is not None:
            spool, spools = str(params.get("spool", "pt")), self._model.get("spool") or {}
            if "shaft" not in self._model and spool not in spools:
                # refused here, before its ports are connected: a connection to a port it would have had would
                # otherwise name the port, not the cause
                raise ContractError(f"{name}.spool = {spool!r} is not a spool of model_file "
                                    f"{params['model_file']} (its spools: {', '.join(spools) or 'none'})")
            lay = torque_layout(self._model, spool)
            if lay is not None:
                own = [v for v in type(self).variables if kind_of(v.name) is None]
                at = next(i for i, v in enumerate(type(self).variables) if kind_of(v.name) is not None)
                self.variables = tuple(own[:at]) + torque_variables(lay) + tuple(own[at:])
        super().__init__(name, parameters)

    def setup(self, t0=0.0):
        super().setup(t0)
        p = self.p
        where = self.name
        if p["profile"] not in PROFILES:
            raise ContractError(f"{where}.profile must be one of {', '.join(PROFILES)}, got {p['profile']!r}")
        mode = PROFILES[p["profile"]]
        for k in ("speed_rpm", "end_speed_rpm", "windmill_rpm", "inertia", "aero_torque", "drag_coefficient"):
            if not (math.isfinite(p[k]) and p[k] >= 0.0):
                raise ContractError(f"{where}.{k} must be a finite number >= 0, got {p[k]}")
        if p["model_file"]:
            self._check_model()
        try:
            if p["profile"] == "table":
                tt, tw = parse_table(p["table"], "table")
            elif p["profile"] == "ramp":
                tt, tw = ramp_table(p["speed_rpm"], p["end_speed_rpm"], p["t_start"], p["duration"])
            else:
                tt, tw = np.array([0.0]), np.array([p["speed_rpm"] * RPM])
            J = p["inertia"] or self._model_inertia()
        except (ValueError, FileNotFoundError, KeyError) as exc:
            raise ContractError(f"{where}: {exc}") from None
        if not J > 0.0:
            raise ContractError(f"{where}.inertia must be > 0 kg m^2, got {J}")
        w0 = p["speed_rpm"] * RPM
        c_aero = 0.0
        if mode == TORQUE:
            if p["windmill_rpm"] >= p["speed_rpm"] and p["aero_torque"] > 0.0:
                raise ContractError(f"{where}.windmill_rpm = {p['windmill_rpm']:g} is not below the start speed "
                                    f"speed_rpm = {p['speed_rpm']:g} rev/min: the windmilling law would drive the "
                                    "spool up after the fuel cut")
            if p["aero_torque"] > 0.0:
                c_aero = p["aero_torque"] / (w0 - p["windmill_rpm"] * RPM) ** 2
        try:
            fl_t, fl_wm, fl_c = self._windmill_table(p["windmill_rpm"] * RPM, c_aero)
        except (ValueError, OSError) as exc:
            raise ContractError(f"{where}.flight_profile: {exc}") from None
        th = cumulative_angle(tt, tw)
        theta0 = 0.0
        if mode != TORQUE:
            from .kernel import profile_at
            w0, theta0, _ = profile_at(tt, tw, th, float(t0))
        self.J = float(J)
        self._kernel_p = SpoolParams(mode, tt, tw, th, float(theta0), float(J),
                                     float(p["t_fuel_cut"]) if p["t_fuel_cut"] >= 0.0 else math.inf,
                                     fl_t, fl_wm, fl_c, float(p["drag_coefficient"]),
                                     sum(kind_of(n) == "drag" for n in self._ports("input")))
        self.state = {"x": np.array([w0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])}
        self.kernel_step(t0, 0.0)
        self.time = float(t0)

    def next_event(self, t):
        """The fuel cut of a torque-driven spool while it is to come, at ``t`` itself too: the step from the cut on
        is the first without drive, so a held interval starting at the cut (a coupled one ended there) would run
        the start of the rundown frozen. EVENT_TOL absorbs the round-off of interval ends."""
        cut = self.p["t_fuel_cut"]
        return float(cut) if self.p["profile"] == "torque" and cut >= 0.0 and cut >= t - EVENT_TOL else None

    def _windmill_table(self, w_wm: float, c_aero: float):
        """Times [s], windmill speeds [rad/s] and torque coefficients [N m s^2] of the windmilling law: one point
        without a flight profile, else one per row of it (windmill.py)."""
        if not self.p["flight_profile"]:
            return np.array([0.0]), np.array([w_wm]), np.array([c_aero])
        prof = read_profile(self.p["flight_profile"])
        if not prof.mach[0] > 0.0:
            raise ValueError(f"{self.p['flight_profile']}: the first row (the condition windmill_rpm and aero_torque "
                             "are given at) must have a Mach number > 0")
        speed, torque = scales(prof.mach, prof.theta, prof.delta)
        return prof.t, w_wm * speed, c_aero * torque

    def _check_model(self) -> None:
        """The model file readable, and an engine file's spool ``spool`` one of its spools (a single-shaft file
        has one, whatever it is called)."""
        try:
            data, _ = load_data(self.p["model_file"])
        except (ValueError, OSError) as exc:
            raise ContractError(f"{self.name}.model_file: {exc}") from None
        spools = data.get("spool") or {}
        if "shaft" not in data and self.p["spool"] not in spools:
            raise ContractError(f"{self.name}.spool = {self.p['spool']!r} is not a spool of model_file "
                                f"{self.p['model_file']} (its spools: {', '.join(spools) or 'none'})")

    def _model_inertia(self) -> float:
        if not self.p["model_file"]:
            raise ValueError("inertia not given and no model_file to compute it from (give the spool's polar inertia "
                             "[kg m^2] or the engine file; a scenario takes both from its engine)")
        from ..rotor.spool_inertia import polar_inertia
        return polar_inertia(self.p["model_file"], self.p["spool"])

    # -- the compiled kernel (components/kernels.py) ---------------------------------------------------------
    STEP = staticmethod(tm_step)

    def kernel_state(self):
        return SpoolState(self.state["x"])

    def kernel_params(self):
        return self._kernel_p

    def kernel_status(self, status, t, h):
        bad = [k for k in self._ports("input") if not np.all(np.isfinite(self.u[k]))]
        raise ContractError(f"{self.name}: non-finite torque input {', '.join(bad)} at t = {t + h:.9g} s")

    def do_step(self, t, h):
        if not (h > 0.0 and math.isfinite(h)):
            raise ContractError(f"{self.name}: step size must be a finite number > 0, got {h!r}")
        self.kernel_step(t, h)
