"""Nonlinear Hertzian ball bearing (#0 or #5 of the power turbine), paper section 2.2, eqs. (1)-(10), Table 3.

Model (kernel.py):
* inner race = the rotor node at the bearing, motion given by the inputs X_inner, V_inner (3: x, y, z);
* Z balls, each with its own radial and axial DOF and mass in its r-z plane, eq. (4), with the centrifugal force
  F_c = m_b (d_m/2) omega_c^2; the balls' angles advance at the cage speed omega_c = omega/2 (1 - D cos a0 / d_m);
* outer race + damper journal: a 2-DOF body, eq. (5), driven by the ball contacts and the damper force input
  F_journal (film + centering spring), axially fixed;
* contact geometry eqs. (1), (6)-(8) with the thermal growths eps = [eps_i, eps_e, eps_b] (eqs. 13-15): the radial
  growth of the inner race, of the outer race and of the ball radius, positive = expansion. Inner race and ball
  growth close the contacts (raise the loads), outer race growth opens them, as in eqs. (6)-(7);
* Hertz contact with the contact damping of eq. (9) (no tensile force: Q >= 0), stress at the centre of the contact
  ellipse, eq. (10), reported as a positive compressive stress;
* an addition to the paper: a light viscous damping of each ball against the mean motion of its two races
  (``ball_damping``; oil film and cage). Eq. (9) damps only the normal approach, so without it the ball's
  tangential (rocking) mode, at ~2-3 kHz, would ring undamped for ever;
* force on the rotor, eq. (2): F_rotor = sum T^T Q + (0, 0, P). The axial preload P is applied by placing the
  inner race axially at z0, the offset at which the balls carry P at speed omega with no radial load; the preload's
  reaction closes through the shaft and the housing, so F_rotor is zero at the preloaded rest state X_inner = 0 and
  only the change from it reaches the rotor;
* drag torque after Palmgren (drag.py) with the SAE 30 viscosity at T_oil (oil.py), at the mean of the step's
  sub-step values; P_drag = M omega, omega the inner race speed (the outer race does not rotate).

A jump of the thermal growths between two steps larger than any thermal rate can give (the TO -> TM restart
of the staggered scheme) re-seats the balls quasi-statically first (:meth:`BallBearing._reseat`).

Integration inside do_step: symplectic Euler sub-steps of cfl / omega_ball (omega_ball the highest linearised
ball-contact frequency at the start of the step), the journal linearly implicit in the damper force
F_journal + K_journal (x - x0) + C_journal (v - v0) about the journal state x0, v0 at the start of the step
(where the damper evaluated F_journal); with K_journal = C_journal = 0 this is the held force.

``axial_direction = -1`` mirrors the bearing axially (z -> -z of X_inner, V_inner and F_rotor): with one bearing
of each direction on a shaft the pair is preloaded against each other (back-to-back / face-to-face), and thermal
growth then raises the axial load of both; with the same direction a free axial rotor DOF lets them relax.

The inner race moves linearly over the step: with ``inner_motion = "step_end"`` (default) X_inner, V_inner are the
rotor's state at the END of the step (Gauss-Seidel with the rotor first, as in scenarios/blade_loss.toml), and the
path is X_inner - V_inner (h - tau); with ``"step_start"`` they are at the start and the path is X_inner + V_inner tau.
"""
from __future__ import annotations

import math

import numpy as np

from ..contract import ContractError, Variable
from ..errors import Diverged
from ..kernels import PYTHON, KernelComponent
from ..numba_internals import address_of
from ..oil_fit import T_MAX_K, T_MIN_K
# ``bearing`` = NO_RECORD: no record of the paper's Table 3; every geometry parameter and the preload are given
from ..records import NO_RECORD, check_selection
from ..speeds import PT_OMEGA
from ..validity import Check
from .drag import static_load_rating
from .geometry import DATA, BEARINGS, DN_LIMIT, build_geometry, speed_limit
from .kernel import (DRAG, G_EPS_LIMIT, G_F_C, G_OMEGA, G_OMEGA_CAGE, G_Z0, GEO, NUM, O_SIZE, O_SUBSTEPS,
                     BearingParams, BearingState, oil_viscosity, pack, step, tm_step, viscous_power)
from .oil import WALTHER_A, WALTHER_B, sae30_kinematic_viscosity
from .static import preload_offset, solve_balls

RPM = math.pi / 30.0
_DESIGN, _DRAG, _NUM = DATA["design"], DATA["drag"], DATA["numerics"]
INNER_MOTION = ("step_end", "step_start")
#: the geometry parameters: (parameter, Table 3 key, SI per table unit)
GEOMETRY = (("balls", "balls", 1), ("ball_diameter", "ball_diameter_mm", 1e-3), ("bore", "bore_mm", 1e-3),
            ("outside_diameter", "outside_diameter_mm", 1e-3), ("width", "width_mm", 1e-3),
            ("contact_angle", "contact_angle_deg", math.pi / 180.0), ("journal_radius", "journal_radius_mm", 1e-3),
            ("journal_length", "journal_length_mm", 1e-3))
#: contact stress above which Hertz's elastic theory no longer describes a ball contact: ISO 76 sets the static
#: load rating of ball bearings at 4200 MPa at the centre of the most loaded contact, where the permanent
#: deformation of ball and race reaches 1e-4 of the ball diameter (data/bearings.toml [drag], the same value
#: defines C0). The paper's own damage criterion, 3200 MPa (incipient plastic flow), is the design margin its
#: blade-loss results are judged by, not the end of the model: its largest cases reach it by design.
ELASTIC_LIMIT_PA = float(_DRAG["static_rating_stress_MPa"]) * 1e6


def _largest(y):
    return y["sigma_max_step"].max(axis=1)


#: the envelope (BallBearing.validity): elastic Hertz contact, the largest stress of the step on either race. The
#: contact ellipse's truncation by the groove shoulder is not checked: Table 3 gives no shoulder height.
CHECKS = (Check("contact stress", ("sigma_max_step",), _largest, ELASTIC_LIMIT_PA, "MPa",
                "ISO 76: 4200 MPa, the static load rating's stress, where permanent deformation begins", scale=1e-6),)


class BallBearing(KernelComponent):
    """Ball bearing #0 / #5 with ball dynamics, journal body and thermal growth (eqs. 1-10)."""

    description = ("Nonlinear Hertzian angular-contact ball bearing with ball dynamics, outer race + SFD journal "
                   "body, thermal growths and Palmgren drag torque (paper eqs. 1-10, Table 3)")
    preferred_step = 1e-5
    phases = frozenset({"TM"})
    #: the parameter that is the speed of the rotor node the bearing is linked to: the scenario build refuses a
    #: value other than that node's spool speed (master/scenario/build.check_speeds)
    fixed_speed = "omega"
    step_cost_s, kernel_step_cost_s, setup_cost_s = 13e-6, 2.5e-6, 0.1  # bench/bench_estimate.py
    variables = (
        Variable("bearing", "parameter", start=NO_RECORD, type="Integer",
                 description="which bearing of the paper's Table 3 (0 or 5) gives the geometry and preload not set "
                             "explicitly; -1 (default): none, every one is given (a scenario takes them from its "
                             "engine file's [bearing.ID] and [damper.ID])"),
        Variable("omega", "parameter", unit="rad/s", start=PT_OMEGA,
                 description="inner race (power turbine) speed; outer race stationary; at most the model's "
                             f"speed limit, bore x speed <= {DN_LIMIT:.3g} mm rev/min (data/bearings.toml dn_limit)"),
        Variable("groove_curvature_inner", "parameter", start=_DESIGN["groove_curvature_inner"],
                 description="inner groove radius / ball diameter f_i"),
        Variable("groove_curvature_outer", "parameter", start=_DESIGN["groove_curvature_outer"],
                 description="outer groove radius / ball diameter f_o"),
        Variable("contact_damping", "parameter", unit="s/m", start=_DESIGN["contact_damping"],
                 description="Hertz contact damping alpha of eq. (9) (paper: 0.08-0.32 s/m)"),
        Variable("ball_damping", "parameter", unit="N.s/m", start=_DESIGN["ball_damping"],
                 description="viscous damping of each ball against the mean race motion (oil/cage; not in the paper)"),
        Variable("drag_in_thermal_only", "parameter", start=True, type="Boolean",
                 description="in thermal-only intervals, update the drag power from the frozen state at the oil "
                             "viscosity (the master's hold follows it, master/manipulator/hold.py); false: held (the paper)"),
        Variable("m_journal", "parameter", unit="kg", start=0.0,
                 description="outer race + journal mass of eq. (5); 0 (default): solid steel rings from Table 3"),
        Variable("preload", "parameter", unit="N", start=BEARINGS[0]["preload_N"],
                 description="axial preload (default Table 3: 800 N for #0, 1100 N for #5)"),
        # the geometry: by default the Table 3 record of ``bearing``; each one set replaces that record's value
        Variable("balls", "parameter", unit="1", start=BEARINGS[0]["balls"], type="Integer",
                 description="number of balls (default: Table 3 of `bearing`)"),
        Variable("ball_diameter", "parameter", unit="m", start=BEARINGS[0]["ball_diameter_mm"] * 1e-3,
                 description="ball diameter (default: Table 3 of `bearing`)"),
        Variable("bore", "parameter", unit="m", start=BEARINGS[0]["bore_mm"] * 1e-3,
                 description="inner race bore (default: Table 3 of `bearing`)"),
        Variable("outside_diameter", "parameter", unit="m", start=BEARINGS[0]["outside_diameter_mm"] * 1e-3,
                 description="outer race outside diameter (default: Table 3 of `bearing`)"),
        Variable("width", "parameter", unit="m", start=BEARINGS[0]["width_mm"] * 1e-3,
                 description="bearing width (outer race mass; default: Table 3 of `bearing`)"),
        Variable("contact_angle", "parameter", unit="rad", start=math.radians(BEARINGS[0]["contact_angle_deg"]),
                 description="initial (unloaded) contact angle (default: Table 3 of `bearing`)"),
        Variable("journal_radius", "parameter", unit="m", start=BEARINGS[0]["journal_radius_mm"] * 1e-3,
                 description="squeeze film damper journal radius: the journal's mass of eq. (5) (default: Table 3 "
                             "of `bearing`; a scenario gives its damper's radius)"),
        Variable("journal_length", "parameter", unit="m", start=BEARINGS[0]["journal_length_mm"] * 1e-3,
                 description="squeeze film damper journal length: the journal's mass (default: Table 3 of "
                             "`bearing`; a scenario gives its damper's length)"),
        Variable("f0", "parameter", start=_DRAG["f0"], description="Palmgren lubrication factor of the drag torque"),
        Variable("inner_motion", "parameter", start="step_end", type="String",
                 description="X_inner/V_inner are the rotor state at the 'step_end' (Gauss-Seidel, rotor first) "
                             "or 'step_start' (Jacobi) of the step"),
        Variable("axial_direction", "parameter", start=1, type="Integer",
                 description="+1: the preload pushes the inner race towards +z (contact line as in eq. 6); -1: the "
                             "bearing is mounted the other way round (z mirrored), e.g. the second of a pair"),
        # bounds of cost, not of physics: the automatic count at cfl 0.5 is a few sub-steps per step (at least
        # min_substeps = 2, data/bearings.toml) and symplectic Euler is stable below cfl 2, so 10 000 sub-steps (or
        # cfl 1e-3, ~1000 times the default's count) gain nothing but multiply the bearing's cost; 1e12 hung the run
        Variable("substeps", "parameter", start=0, type="Integer", min=0, max=10_000,
                 description="sub-steps per do_step; 0 = automatic from the ball-contact frequency and cfl"),
        Variable("cfl", "parameter", start=_NUM["cfl"], min=1e-3, max=2.0,
                 description="automatic sub-step: dt = cfl / highest ball-contact frequency (stable below 2)"),
        Variable("X_inner", "input", 3, "m", "inner race (rotor node) displacement x, y, z"),
        Variable("V_inner", "input", 3, "m/s", "inner race (rotor node) velocity"),
        Variable("F_journal", "input", 2, "N", "damper film + centering spring force on the journal"),
        Variable("K_journal", "input", 4, "N/m", "dF_journal/dX_journal, row-major [xx, xy, yx, yy]",
                 labels=("xx", "xy", "yx", "yy")),
        Variable("C_journal", "input", 4, "N.s/m", "dF_journal/dV_journal, row-major [xx, xy, yx, yy]",
                 labels=("xx", "xy", "yx", "yy")),
        Variable("eps", "input", 3, "m", "thermal radial growths [inner race, outer race, ball], + = expansion",
                 labels=("inner_race", "outer_race", "ball")),
        Variable("T_oil", "input", 1, "K", "bearing oil temperature (drag torque viscosity)", start=303.15),
        Variable("F_rotor", "output", 3, "N", "force of the bearing on the rotor (eq. 2), zero at preloaded rest"),
        Variable("X_journal", "output", 2, "m", "outer race + journal displacement (absolute)"),
        Variable("V_journal", "output", 2, "m/s", "outer race + journal velocity (absolute)"),
        Variable("Q_max", "output", 2, "N", "max contact load over the balls [inner, outer], end of step",
                 labels=("inner", "outer")),
        Variable("Q_max_step", "output", 2, "N", "max contact load over the balls and the sub-steps of the step",
                 labels=("inner", "outer")),
        Variable("sigma_max", "output", 2, "Pa", "max contact stress eq. (10) [inner, outer], end of step",
                 labels=("inner", "outer")),
        Variable("sigma_max_step", "output", 2, "Pa", "max contact stress over the sub-steps of the step",
                 labels=("inner", "outer")),
        Variable("P_drag", "output", 1, "W", "drag torque power loss M omega, mean over the step"),
    )

    def speed_range(self) -> tuple[float, float]:
        """(bore [m], highest inner race speed [rad/s] of the model: geometry.speed_limit) from the parameters
        as given (the ``bearing`` record's bore when none is), known before set-up: what ``check-engine`` holds
        against the shaft and the spool's speed."""
        rec = BEARINGS.get(self.p["bearing"], BEARINGS[0])
        bore = float(self.p["bore"]) if "bore" in self.explicit else rec["bore_mm"] * 1e-3
        return bore, speed_limit(bore)

    def ball_pass_frequencies(self) -> tuple[float, float]:
        """The frequencies [Hz] at which the balls pass a point of the inner race, ``Z (omega - omega_c) / 2 pi``,
        and of the outer race, ``Z omega_c / 2 pi``, at the speed the bearing runs at now (after set-up): the
        periods of its own ripple, which a load turning with the shaft (the unbalance) sees at the first and a
        fixed load (gravity) at the second, in its contact loads and stresses however settled the run is."""
        if getattr(self, "_geo", None) is None:
            raise ContractError(f"{self.name}: its ball-pass frequencies are known after set-up (the speed and the "
                                "geometry it runs with)")
        w, wc = self._geo[G_OMEGA], self._geo[G_OMEGA_CAGE]
        z = self.geometry.Z / (2.0 * math.pi)
        return float(z * (w - wc)), float(z * wc)

    # -- set-up --------------------------------------------------------------------------------------------
    def setup(self, t0=0.0):
        super().setup(t0)
        p = self.p
        explicit = self.explicit
        record = p["bearing"] != NO_RECORD
        if record and p["bearing"] not in BEARINGS:
            raise ContractError(f"{self.name}.bearing: unknown bearing number {p['bearing']!r}; Table 3 has "
                                f"{sorted(BEARINGS)}, or -1 for none (then set the geometry parameters "
                                f"{', '.join(n for n, _, _ in GEOMETRY)} and preload)")
        check_selection(self, "bearing", BEARINGS, [g for g, _, _ in GEOMETRY] + ["preload"], what="Table 3 record",
                        tables="[bearing.ID], [damper.ID]")
        if "preload" not in explicit:
            p["preload"] = float(BEARINGS[p["bearing"]]["preload_N"])
        for key, lo in (("omega", 0.0), ("preload", 0.0), ("contact_damping", 0.0), ("ball_damping", 0.0),
                         ("f0", 0.0)):
            if not p[key] >= lo:
                raise ContractError(f"{self.name}.{key} must be >= {lo}, got {p[key]}")
        if p["axial_direction"] not in (1, -1):
            raise ContractError(f"{self.name}.axial_direction must be +1 or -1, got {p['axial_direction']}")
        if p["inner_motion"] not in INNER_MOTION:
            raise ContractError(f"{self.name}.inner_motion must be one of {INNER_MOTION}, got {p['inner_motion']!r}")
        if p["substeps"] < 0 or not p["cfl"] > 0.0 or p["cfl"] >= 2.0:
            raise ContractError(f"{self.name}: substeps must be >= 0 (0 = automatic) and 0 < cfl < 2, "
                                f"got substeps={p['substeps']}, cfl={p['cfl']}")
        raw = BEARINGS.get(p["bearing"], {})
        for name, key, scale in GEOMETRY:
            if name in explicit:
                v = p[name]
                if not (isinstance(v, (int, float)) and math.isfinite(v) and (v > 0 or name == "contact_angle")):
                    raise ContractError(f"{self.name}.{name} must be a finite number > 0, got {v!r}")
            else:
                p[name] = raw[key] * scale if name != "balls" else int(raw[key])
        table = {key: (p[name] / scale if name != "balls" else int(p[name]))
                 for name, key, scale in GEOMETRY if name in explicit}
        try:
            g = build_geometry(p["bearing"] if record else None, f_i=p["groove_curvature_inner"], f_o=p["groove_curvature_outer"],
                               preload=p["preload"], table=table)
        except ValueError as exc:
            raise ContractError(f"{self.name}: {exc}") from None
        if "m_journal" not in explicit or p["m_journal"] == 0.0:
            p["m_journal"] = g.m_outer_race + g.m_journal
        if not p["m_journal"] > 0.0:
            raise ContractError(f"{self.name}.m_journal must be > 0 kg, got {p['m_journal']}")
        self.geometry = g
        omega = p["omega"]
        self.omega_max = speed_limit(p["bore"])
        if omega > self.omega_max:
            raise ContractError(f"{self.name}.omega = {omega * 30.0 / math.pi:.0f} rev/min is above the ball bearing "
                                f"model's speed limit {self.omega_max * 30.0 / math.pi:.0f} rev/min (bore "
                                f"{p['bore'] * 1e3:g} mm x speed <= {DN_LIMIT:.3g} mm rev/min, data/bearings.toml "
                                "dn_limit)")
        Fc = g.centrifugal_force(omega)
        try:
            self.z0, st = preload_offset(g, Fc)
        except (ValueError, RuntimeError) as exc:
            raise ContractError(f"{self.name}: the preloaded rest state did not solve at omega = "
                                f"{omega * 30.0 / math.pi:.0f} rev/min with preload = {g.preload:g} N: {exc}") from None
        self.C0 = static_load_rating(g.Z, g.alpha0, max(g.inner.stress_coeff, g.outer.stress_coeff),
                                     _DRAG["static_rating_stress_MPa"] * 1e6, _DRAG["static_rating_stribeck"])
        self._geo = pack(GEO, l_oi=g.l_oi, l_oe=g.l_oe, cos_a0=math.cos(g.alpha0), sin_a0=math.sin(g.alpha0),
                         K_i=g.K_i, K_e=g.K_e, alpha_d=p["contact_damping"], F_c=Fc, m_b=g.m_b,
                         m_journal=p["m_journal"], omega_cage=g.cage_speed(omega), preload=g.preload,
                         stress_inner=g.inner.stress_coeff, stress_outer=g.outer.stress_coeff, omega=omega,
                         eps_limit=0.05 * g.D, ball_damping=p["ball_damping"],
                         axial_direction=p["axial_direction"], z0=self.z0)
        self._drag = pack(DRAG, nu=0.0, omega=omega, d_m=g.d_m, f0=p["f0"], f1_z=_DRAG["f1_z"], f1_y=_DRAG["f1_y"],
                          X0=_DRAG["X0"], Y0=_DRAG["Y0"], C0=self.C0)
        self._num = pack(NUM, cfl=p["cfl"], min_substeps=_NUM["min_substeps"], substeps=p["substeps"],
                         inputs_at_end=1.0 if p["inner_motion"] == "step_end" else 0.0)
        phi = 2.0 * math.pi * np.arange(g.Z) / g.Z
        self._cb, self._sb = np.cos(phi), np.sin(phi)
        self._eps_jump = float(_NUM["eps_jump"])
        self.state = {
            "balls": np.vstack([st.v, np.zeros((2, g.Z))]),
            "journal": np.zeros(4),
            "phi": np.zeros(1),
            "eps_seated": np.zeros(3),     # the growths the balls were last seated for
        }
        self.phases = frozenset({"TM", "TO"}) if p["drag_in_thermal_only"] else frozenset({"TM"})
        self.holds_state_in_TO = bool(p["drag_in_thermal_only"])
        self.phase = "TM"
        self._out = np.zeros(O_SIZE)
        self._kernel_p = BearingParams(self._cb, self._sb, self._geo, self._drag, self._num,
                                       np.full(3, np.nan), self._out, self._eps_jump, float(WALTHER_A),
                                       float(WALTHER_B), T_MIN_K, T_MAX_K, address_of(step))
        # outputs of the rest state: one zero-length evaluation
        self._advance(0.0, self.time)

    def validity(self):
        return CHECKS

    # -- stepping ------------------------------------------------------------------------------------------
    @property
    def substeps_used(self) -> int:
        """Sub-steps of the last step."""
        return int(self._out[O_SUBSTEPS])

    def _nu(self, T):
        if not (T_MIN_K < T <= T_MAX_K):
            try:
                sae30_kinematic_viscosity(T)       # its error names the fit's range
            except ValueError as exc:
                raise ContractError(f"{self.name}.T_oil: {exc}") from None
        return oil_viscosity(self._kernel_p, float(T))

    def _advance(self, h, t):
        """Outputs of the present state for a zero-length step (set-up): the kernel on copies of the state (the
        balls seated at the present growths), into fresh output arrays."""
        self._nu(float(self.u["T_oil"][0]))        # names a T_oil outside the viscosity fit
        st = self.state
        s = BearingState(st["balls"].copy(), st["journal"].copy(), st["phi"].copy(), self.u["eps"].copy())
        U, Y, ins, outs = self.kernel_ports()
        y = Y(*[np.zeros_like(self.y[n]) for n in outs])
        status = tm_step(s, self._kernel_p, U(*[self.u[n] for n in ins]), y, t, h)
        if status != 0:
            self._fail(float(status - 10), t + h)
        for n, a in zip(outs, y):
            self.y[n] = a

    def _reseat(self, h):
        """Put the balls at their quasi-static positions (eq. 4 without acceleration) for the present race
        positions and the new thermal growths, keeping their velocities.

        Thermal growth is slow (um/s): a jump of eps between two steps only happens when the thermal network ran
        on while the mechanics were frozen (a thermal-only interval of the staggered scheme). The balls would have
        followed it quasi-statically; taking the jump as a sudden overlap instead would start the next
        thermo-mechanical interval with an artificial impact of every ball."""
        g, u, s = self.geometry, self.u, self.state
        ax = float(self.p["axial_direction"])
        lag = h if self.p["inner_motion"] == "step_end" else 0.0
        X = np.array(u["X_inner"], dtype=float) - lag * np.array(u["V_inner"], dtype=float)
        phi = s["phi"][0] + 2.0 * np.pi * np.arange(g.Z) / g.Z
        c, sn = np.cos(phi), np.sin(phi)
        xe, ye = s["journal"][0], s["journal"][1]
        ur = X[0] * c + X[1] * sn
        wr = xe * c + ye * sn
        v, _ = solve_balls(g, ur, ax * X[2] + float(self._geo[G_Z0]), wr, tuple(u["eps"]), float(self._geo[G_F_C]),
                           v0=s["balls"][:2].copy())
        s["balls"][:2] = v

    def _fail(self, flag, t):
        if flag == 1.0:
            bad = [k for k in ("X_inner", "V_inner", "F_journal", "K_journal", "C_journal", "eps")
                   if not np.all(np.isfinite(self.u[k]))]
            raise ContractError(f"{self.name}: non-finite input {', '.join(bad)} at t = {t:.9g} s")
        if flag == 2.0:
            raise ContractError(f"{self.name}.eps: thermal growths {self.u['eps']} m exceed 5 % of the ball "
                                f"diameter ({self._geo[G_EPS_LIMIT]:.3g} m); not a thermal growth")
        # its state left the equations' domain: a divergence (reported as such), not a fault of the component
        raise Diverged(f"{self.name}: the bearing state became non-finite at t = {t:.9g} s")

    def _viscous_power(self, T):
        """omega M_v: the load-independent (viscous) part of the Palmgren drag power at oil temperature T (kept for
        the last T: T_oil changes only at the thermal network's, slower, step)."""
        self._nu(T)
        return viscous_power(self._kernel_p, float(T))

    # -- the compiled kernel (components/kernels.py) ---------------------------------------------------------
    STEP = staticmethod(tm_step)

    def kernel_available(self):
        return not (self.phase == "TO" and self.holds_state_in_TO)

    def kernel_state(self):
        st = self.state
        return BearingState(st["balls"], st["journal"], st["phi"], st["eps_seated"])

    def kernel_params(self):
        return self._kernel_p

    def kernel_status(self, status, t, h):
        if status == PYTHON:
            # the growths jumped (a thermal-only interval ended): re-seat the balls, then the kernel's step
            self._reseat(h)
            self.state["eps_seated"][:] = self.u["eps"]
            status = self.STEP(*self.kernel_args(), t, h)
            if status == 0:
                return
        if status == 5:
            self._nu(float(self.u["T_oil"][0]))
        if status >= 10:
            self._fail(float(status - 10), t + h)
        raise RuntimeError(f"{self.name}: kernel status {status} at t = {t + h:.9g} s")

    def do_step(self, t, h):
        if not (h > 0.0 and math.isfinite(h)):
            raise ContractError(f"{self.name}: step size must be a finite number > 0, got {h!r}")
        if self.phase == "TO" and self.holds_state_in_TO:
            self._thermal_only_step(t, h)
            return
        self.kernel_step(t, h)

    def enter_phase(self, phase):
        """Entering a thermal-only interval freezes the drag power's load term where the state froze."""
        super().enter_phase(phase)
        if phase == "TO":
            T = float(self.u["T_oil"][0])
            self._frozen_load = float(self.y["P_drag"][0]) - (self._viscous_power(T) if math.isfinite(T) else 0.0)

    def _thermal_only_step(self, t, h):
        """Thermal-only interval (TO update): the balls, races and journal stay frozen; the drag power of the
        frozen state at the present oil temperature: Palmgren's load term as it froze plus his viscous term at
        the input T_oil (the only term that depends on it). The master's hold (master/manipulator/hold.py) carries the
        window's mean drag along this output; holding the drag power as it was (the paper) keeps the cold-oil
        drag of the first interval, about three times the warm value, over the whole thermal-only interval."""
        T = float(self.u["T_oil"][0])
        if not math.isfinite(T):
            raise ContractError(f"{self.name}: non-finite input T_oil at t = {t:.9g} s")
        load = getattr(self, "_frozen_load", 0.0)
        self.y["P_drag"] = np.array([max(load + self._viscous_power(T), 0.0)])
        self.time = t + h
