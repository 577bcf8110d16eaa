"""The rotor at a varying speed: the speed-following variant of the rotor component (``rotor.mta_spinning``).

The same MTA-reduced model and Newmark step as component.Rotor, with the power-turbine and gas-generator speeds as
inputs (``Omega_pt``, ``dOmega_pt``, ``Omega_gg``, from the spools, components/spool) instead of constants:

* gyroscopics: the reduced damping matrix is ``C_r + (Omega_pt - W_pt) G_r,pt + (Omega_gg - W_gg) G_r,gg`` about
  the reference speeds W (the parameters ``omega_pt``, ``omega_gg``) where the reduced model was projected:
  projected once, scaled per step. The Newmark step map is rebuilt whenever a speed has left the one it was
  built for by more than ``gyro_tolerance`` of its reference speed (the kernel hands that step to Python, status
  PYTHON), so the gyroscopic terms lag the speed by at most that fraction (default 1e-3); supports whose
  coefficients change with speed (model.py, ``speed_supports``) are taken at the power turbine's speed of the
  step map in the same way (model.projected_support_delta);
* unbalance: the force of a mass ``m e`` at the rotor's angle ``theta`` on the shaft is the reaction to the mass's
  acceleration, ``-m e d^2(e^{i theta})/dt^2 / e = m e (Omega^2 - i dOmega/dt) e^{i theta}``: ``m e Omega^2``
  outwards and the tangential ``m e dOmega/dt`` 90 deg behind, against the sense of rotation, while the speed
  rises (ahead of it in a rundown); ``m e = F / W_pt^2`` for each of ``F_residual`` and ``F_unbalance`` (the
  levels stay given as forces at the reference speed). The angle is the rotor's own: the integral of the speed
  over the steps the rotor has taken (its mechanical time), so that a thermal-only interval, which freezes the
  rotor, does not turn the unbalance against the frozen orbit (component.Rotor._unbalance);
* start: at rest, or (``start_synchronous = 1``) on the steady synchronous orbit of the linear model under the
  unbalance at the speed inputs' values at set-up, the spools' start speeds (the master hands them over before the
  set-up when the spools come first in the run's order: ``inputs_at_setup``).

At Omega_pt = W_pt and Omega_gg = W_gg throughout, every number is the constant-speed rotor's, bit for bit
(the angle is W tau, the scale factor 1.0, no tangential term, the same step map).

Example (a scenario)::

    [components.rotor]
    implementation = "rotor.mta_spinning"
    # connections: spool_pt.Omega -> rotor.Omega_pt, spool_pt.dOmega -> rotor.dOmega_pt, spool_gg.Omega -> rotor.Omega_gg
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..contract import ContractError, Variable
from ..kernels import PYTHON
from ..numba_internals import kernel_jit
from . import model as fem
from .component import Rotor, full_model
from .kernel import advance, pack
from .newmark import initial_acceleration, step_operator

SpinParams = namedtuple("SpinParams", "TB O f s_new xv F_residual F_unbalance unbalance_phase t_blade_loss "
                                      "W_ref op tol in_off out_off speed_at")
#: per process: (model digest, n_modes, reference speeds) -> the reduced gyroscopic matrices per rad/s
_GYRO: dict[tuple, tuple[np.ndarray, np.ndarray]] = {}


@kernel_jit
def spinning_step(s, p, u, y, t, h):
    """One Newmark step at the input speeds; status 2 a non-finite input, 3 a non-finite response, PYTHON: a speed
    left the step map's by more than the tolerance (rebuild it)."""
    w = u[p.speed_at[0]][0]          # the ports are a plain tuple (component.Rotor.kernel_ports): by position
    wg = u[p.speed_at[1]][0]
    dw = u[p.speed_at[2]][0]
    if not math.isfinite(w + wg + dw):
        return 2
    if abs(w - p.op[0]) > p.tol[0] or abs(wg - p.op[1]) > p.tol[1]:
        return PYTHON
    ang = s.ang                              # angle bookkeeping: [angle at tau_ref, tau_ref, speed since]
    if w != ang[2]:
        ang[0] += ang[2] * (s.tau[0] - ang[1])
        ang[1] = s.tau[0]
        ang[2] = w
    tau = s.tau[0] + h
    a = ang[0] + ang[2] * (tau - ang[1])
    scale = (w / p.W_ref) * (w / p.W_ref)
    fr = p.F_residual * scale
    fx = fr * math.cos(a)
    fy = fr * math.sin(a)
    fb = p.F_unbalance * scale
    blade = t + h >= p.t_blade_loss
    if blade:
        ph = a + p.unbalance_phase
        fx += fb * math.cos(ph)
        fy += fb * math.sin(ph)
    if dw != 0.0:
        # -i dOmega/dt (m e) e^{i angle}: the tangential part, behind the radial one while the speed rises
        tr = p.F_residual * dw / (p.W_ref * p.W_ref)
        fx += tr * math.sin(a)
        fy -= tr * math.cos(a)
        if blade:
            tb = p.F_unbalance * dw / (p.W_ref * p.W_ref)
            fx += tb * math.sin(ph)
            fy -= tb * math.cos(ph)
    return advance(s, p, u, y, fx, fy, tau)


class SpinningRotor(Rotor):
    """The rotor with its spools' speeds as inputs (module docstring)."""

    description = ("Flexible dual-rotor engine + casing (MTA, Newmark) at varying spool speeds: gyroscopics and "
                   "unbalance follow the speed inputs")

    def port_speeds(self) -> dict[str, tuple[str, float]]:
        # the speeds are the inputs Omega_pt, Omega_gg; omega_pt, omega_gg only the reference of the projection
        return {}

    variables = Rotor.variables + (
        Variable("gyro_tolerance", "parameter", unit="1", start=1e-3,
                 description="relative speed change that rebuilds the Newmark map (gyroscopic terms)"),
        Variable("start_synchronous", "parameter", unit="1", start=0, type="Integer",
                 description="1: start from the synchronous steady state of the linear model under the unbalance "
                             "at the spools' start speeds (the speed inputs at set-up; no port forces: a linear "
                             "rotor's check case); 0: at rest"),
        Variable("start_support", "parameter", unit="1", start="", type="String",
                 description="with start_synchronous: the port group (\"brg0\": F_brg0 at X_brg0) where a linear "
                             "support of start_support_stiffness and _damping acts on the start orbit (a support "
                             "component's intact stiffness); \"\": none"),
        Variable("start_support_stiffness", "parameter", unit="N/m", start=0.0,
                 description="stiffness (x and y) of the start orbit's linear support"),
        Variable("start_support_damping", "parameter", unit="N.s/m", start=0.0,
                 description="damping (x and y) of the start orbit's linear support"),
        Variable("Omega_pt", "input", 1, "rad/s", "power-turbine speed"),
        Variable("dOmega_pt", "input", 1, "rad/s2", "power-turbine angular acceleration (tangential unbalance)"),
        Variable("Omega_gg", "input", 1, "rad/s", "gas-generator speed"),
    )

    spool_descriptions = {
        **Rotor.spool_descriptions,
        "Omega_pt": "speed of the {first} (the first spool)",
        "dOmega_pt": "angular acceleration of the {first} (tangential unbalance)",
        "Omega_gg": "speed of the {second}",
    }
    inputs_at_setup = True

    def setup(self, t0=0.0):
        p = self.p
        if not (math.isfinite(p["gyro_tolerance"]) and p["gyro_tolerance"] > 0.0):
            raise ContractError(f"{self.name}.gyro_tolerance must be > 0, got {p['gyro_tolerance']}")
        self._op = (float(p["omega_pt"]), float(p["omega_gg"]))
        self.state = {}                 # no angle of an earlier set-up: _unbalance is the constant-speed one until set
        super().setup(t0)
        red = self._red
        full = full_model(p["model_file"], p["omega_pt"], p["omega_gg"])
        key = (full.digest, int(p["n_modes"]), float(p["omega_pt"]), float(p["omega_gg"]))
        if key not in _GYRO:
            B = red["basis"]
            _GYRO[key] = (B.T @ full.G_pt @ B, B.T @ full.G_gg @ B)
        self._G = _GYRO[key]
        self._full = full
        # supports whose coefficients change with the first spool's speed: the step map depends on it as on the
        # gyroscopic terms
        tables = bool(full.info.get("speed_supports"))
        # no gyroscopic coupling (a spool without polar inertia) and no such support: the step map never depends
        # on that spool's speed
        self._tol = np.array([math.inf if not (np.any(g) or (tables and i == 0)) else p["gyro_tolerance"] * abs(w)
                              for i, (g, w) in enumerate(zip(self._G, self._op))])
        self.state["ang"] = np.array([0.0, 0.0, float(p["omega_pt"])])
        if p["start_synchronous"]:
            w, wg = float(self.u["Omega_pt"][0]), float(self.u["Omega_gg"][0])
            if not (math.isfinite(w) and math.isfinite(wg) and w >= 0.0):
                raise ContractError(f"{self.name}.start_synchronous: the speed inputs at set-up (Omega_pt = {w}, "
                                    f"Omega_gg = {wg} rad/s) are no start speed")
            self.state["ang"][2] = w
            self._start_synchronous(float(t0), w, wg)

    def _start_synchronous(self, t0, w, wg):
        """x, v of the steady synchronous orbit X e^(i w t) of M x'' + C(w) x' + K x = B f_u (the unbalance alone,
        ``(w / W_pt)^2`` of its level at the reference speed) at the speeds ``w`` (power turbine) and ``wg`` [rad/s],
        at t0: the rotor's angle there is w t0."""
        red, p = self._red, self.p
        W = float(p["omega_pt"])
        Fh = p["F_residual"] * np.array([1.0, -1.0j])
        if t0 >= p["t_blade_loss"]:
            Fh = Fh + p["F_unbalance"] * np.exp(1j * p["unbalance_phase"]) * np.array([1.0, -1.0j])
        Fh = Fh * (w / W) ** 2
        K, C = self._at_speeds(w, wg)
        if p["start_support"]:
            # the support's force -(k x + c v) at the port, taken into the orbit's equation (and the start
            # acceleration's): the orbit a support component carries from t0, which hands its own force over
            # from the first step
            S = self._start_support()
            K = K + p["start_support_stiffness"] * S
            C = C + p["start_support_damping"] * S
        B_u = red["B_in"][:, -2:]
        X = np.linalg.solve(K - w * w * red["M"] + 1j * w * C, B_u @ Fh) * np.exp(1j * w * t0)
        x0, v0 = X.real.copy(), (1j * w * X).real.copy()
        f0 = red["B_in"] @ self._input_vector(t0)
        a0 = initial_acceleration(red["M"], C, K, x0, v0, f0)
        self.state["s"] = np.concatenate([x0, v0, a0])
        self._write_outputs(self.state["s"], t0)

    def _start_support(self) -> np.ndarray:
        """The reduced matrix B_F O_x of the group ``start_support`` (its radial x, y): a stiffness k at the port is
        k times it."""
        g, red = self.p["start_support"], self._red
        f_name, x_name = f"F_{g}", f"X_{g}"
        at = {}
        k = 0
        for name in self._in_names:
            at[name] = k
            k += self.variable(name).size
        rows = {name: a for name, a, _ in self._out_slices}
        if f_name not in at or x_name not in rows:
            raise ContractError(f"{self.name}.start_support: no port group {g!r} (ports {f_name}, {x_name}); "
                                f"known: {sorted(n[2:] for n in at if n.startswith('F_'))}")
        B_F = red["B_in"][:, at[f_name]:at[f_name] + 2]
        O_x = red["O"][rows[x_name]:rows[x_name] + 2]
        return B_F @ O_x

    def _unbalance(self, t, tau=None):
        """The rotating unbalance force at time t at the rotor's angle and speed (its state ``ang``: the angle at
        a reference mechanical time and the speed since) scaled to that speed; the constant-speed rotor's before
        the angle is set up. The set-up's outputs and initial acceleration (the kernel computes it at every step)."""
        ang = self.state.get("ang")
        if ang is None:
            return super()._unbalance(t, tau)
        p = self.p
        tau = t if tau is None else float(np.asarray(tau).reshape(-1)[0])
        a = ang[0] + ang[2] * (tau - ang[1])
        scale = (ang[2] / p["omega_pt"]) ** 2
        fx = p["F_residual"] * scale * math.cos(a)
        fy = p["F_residual"] * scale * math.sin(a)
        if t >= p["t_blade_loss"]:
            ph = a + p["unbalance_phase"]
            fx += p["F_unbalance"] * scale * math.cos(ph)
            fy += p["F_unbalance"] * scale * math.sin(ph)
        return fx, fy

    def _at_speeds(self, w: float, wg: float) -> tuple[np.ndarray, np.ndarray]:
        """The reduced K and C at the speeds ``w`` (power turbine, the first spool) and ``wg`` [rad/s]: the
        gyroscopic terms, and the speed-dependent supports' coefficients at w, moved from the reference speeds'."""
        red, p = self._red, self.p
        K, C = red["K"], red["C"]
        if (w, wg) == (p["omega_pt"], p["omega_gg"]):
            return K, C
        C = C + (w - p["omega_pt"]) * self._G[0] + (wg - p["omega_gg"]) * self._G[1]
        if self._full.info.get("speed_supports"):
            dK1, dC1 = fem.projected_support_delta(self._full, red["basis"], w)
            dK0, dC0 = fem.projected_support_delta(self._full, red["basis"], float(p["omega_pt"]))
            K, C = K + (dK1 - dK0), C + (dC1 - dC0)
        return K, C

    def _operators(self, h):
        key = (float(f"{h:.12g}"), self._op)
        ops = self._ops.get(key)
        if ops is None:
            red, p = self._red, self.p
            K, C = self._at_speeds(*self._op)
            T, B = step_operator(red["M"], C, K, key[0], p["newmark_beta"], p["newmark_gamma"])
            ops = pack(T, B @ red["B_in"])
            if len(self._ops) > 32:
                self._ops.clear()
            self._ops[key] = ops
        return ops

    STEP = staticmethod(spinning_step)

    def kernel_state(self):
        return _SpinState(self.state["s"], self.state["tau"], self.state["ang"])

    def kernel_prepare(self, h):
        if h != getattr(self, "_kernel_h", None):
            p = self.p
            n3 = 3 * self._red["n"]
            self._kernel_p = SpinParams(self._operators(h), self._Oxv, self._f, np.empty(n3),
                                        np.empty(self._Oxv.shape[0]), float(p["F_residual"]),
                                        float(p["F_unbalance"]), float(p["unbalance_phase"]),
                                        float(p["t_blade_loss"]), float(p["omega_pt"]), np.array(self._op),
                                        self._tol, self._in_off, self._out_off, self._speed_at)
            self._kernel_h = h
            self._last_h = h

    def kernel_status(self, status, t, h):
        if status == PYTHON:
            # a speed left the step map's: rebuild it at the present speeds, then the kernel's step
            self._op = (float(self.u["Omega_pt"][0]), float(self.u["Omega_gg"][0]))
            self._kernel_h = None
            self.kernel_prepare(h)
            status = self.STEP(*self.kernel_args(), t, h)
            if status == 0:
                return
        if status == 2:
            bad = [k for k in ("Omega_pt", "dOmega_pt", "Omega_gg") if not np.all(np.isfinite(self.u[k]))]
            if bad:
                raise ContractError(f"{self.name}: non-finite speed input {', '.join(bad)} at t = {t + h:.9g} s")
        super().kernel_status(status, t, h)


_SpinState = namedtuple("SpinState", "s tau ang")
