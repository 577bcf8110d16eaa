"""The rotor component: the linear engine structure, MTA-reduced, stepped by Newmark-beta.

Paper sections 2.1, 3.1 and 4.1: the flexible power turbine + gas generator + casing (model), reduced by modal
truncation augmentation, eqs. (16)-(22) (mta), integrated by the Newmark-beta method (newmark) at constant speeds
(16 000 / 15 000 rev/min), with the blade-loss force rotating at the power-turbine speed at the outboard end.

Conventions:
* the ports follow the engine file's [attach] (attach.py: any number of bearings and rub rings, by id); what
  follows is the paper's engine (bearings and rub rings #0 and #5);
* the reduced basis is [lowest ``n_modes`` modes of the model without bearings #0/#5, augmentation vectors for
  every DOF where a force enters]: PT node at bearing #0 and #5 (x y z), the two housing hubs (x y), the PT nodes
  at the rub rings (x y; the rings act at the bearing nodes, engine.toml, so these add no vector) and the
  blade-loss node (x y): 12 independent vectors. Default 30 modes, from the
  convergence study of bench/bench_rotor.py: the blade-loss peaks on linear supports are within 0.05 % (#0) and
  0.25 % (#5, a 0.03 mm peak) of the full model there, and at #0 MTA's error keeps falling with n_modes (0.015 %
  at 40) while plain truncation stalls at ~0.2 %. The 30th and 31st modes of the engine are a degenerate pair
  (1378.714 Hz), kept whole (mta.modes), so the reduced size is 43;
* inputs are held over a step; the unbalance force is evaluated at the end of the step (t + h), where Newmark's
  equilibrium is enforced; outputs are the displacements/velocities at t + h;
* unbalance: F_u(t) = F_residual (cos Wt, sin Wt) from t = 0 plus, from ``t_blade_loss`` on, a step onset of
  F_unbalance (cos(Wt + phase), sin(Wt + phase)) (W = omega_pt). The residual defaults to 0 (an engine has no
  residual unbalance unless its file gives one, [unbalance] residual_N). The paper's engine gives 87 N
  (components/rotor/data/engine.toml): ISO 21940-11 balance grade G 2.5 (gas turbines: e W <= 2.5 mm/s) for a
  ~20 kg power turbine at 16 000 rev/min (F = m G W; 87 N for the 20.8 kg of the first layout, 83 N for the
  19.9 kg of the layout calibrated on the 2850 N response: 87 N kept, G 2.6 here, 4 N apart, immaterial next to
  the blade-loss force), all put at the outboard end (conservative: the whole residual at the blade-loss node).
  The paper gives neither the residual nor its
  phase. Default phase 90 deg (quadrature, the residual changes the amplitude by (87/712)^2 / 2 = 0.7 % at
  712 N): the paper's own 712 N and 1425 N cases have the same whirl per newton (0.0719 and 0.0734 mm/kN) and
  transmissibility (1.03, 1.02), where a residual in phase (0 deg) would make the
  712 N case 6 % larger per newton than the 1425 N one (+12 % against +6 %), and in opposition 6 % smaller.
  Eq. (23) divides by the blade-loss force alone (``F_unbalance``, "the unbalance force induced by blade
  loss"), as cases/blade_loss/results.py does;
* the blade release is a time event (``next_event``, docs/explanation/events.md): a held interval that would span
  it ends at it (the rotor is frozen there) and records it; inside a coupled interval these steps apply it, from
  the end of the step that holds ``t_blade_loss`` (``time_events_in_steps``), and the master records nothing;
* the output ``F_u`` is the total applied rotating force vector (residual + blade loss); it cannot be called
  F_unbalance like the amplitude parameter, since variable names are unique (FMI, contract);
* the Newmark step map is formed once per step size (sizes equal to 12 significant digits share it, so round-off
  in the master's interval arithmetic does not rebuild it) and kept for the life of the instance;
* the structure starts at rest at t0 (no gravity, the paper has none); both rotors spin in the +z sense
  (co-rotating; the paper does not say), which fixes the sign of the gyroscopic terms.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..contract import ContractError, Variable
from ..errors import Diverged
from ..kernels import PositionalKernelComponent
from ..speeds import GG_OMEGA, PT_OMEGA
from . import attach
from . import model as fem
from . import shaft_model
from .mta import mta_basis, project
from .kernel import RotorParams, RotorState, pack, tm_step
from .newmark import check_parameters, initial_acceleration, step_operator

RPM = fem.RPM



def port_variables(lay: attach.Layout, w: attach.Words = attach.Words()) -> tuple[Variable, ...]:
    """The rotor component's port variables for the attached bearings, rub rings and mounts (attach.py), then
    F_u, described in the engine's words ``w``. (A mount's spring on a rotation carries N m in its entry of
    ``F_mount_NAME``, rad in ``X_mount_NAME``.)"""
    ins = attach.input_ports(lay, w)
    outs = attach.output_ports(lay, w)
    by_kind = {k: [v for v in ins if v[0].startswith(k)]
               for k in ("F_brg", "F_sfd_housing", "F_rub_housing", "F_fusehub")}
    by_kind["F_rub"] = [v for v in ins if v[0].startswith("F_rub") and not v[0].startswith("F_rub_housing")]
    by_kind["F_fuse"] = [v for v in ins if v[0].startswith("F_fuse") and not v[0].startswith("F_fusehub")]
    by_kind["F_mount"] = [v for v in ins if v[0].startswith("F_mount_")]
    out = [Variable(name, "input", n, "N", desc) for k in by_kind for name, _, n, desc in by_kind[k]]
    for prefix in ("brg", "housing", "rub", "fuse", "mount_"):
        group = [o for o in outs if o[0].startswith(prefix)]
        out += [Variable(x, "output", n, "m", d.format("displacement")) for _, x, _, n, d in group]
        out += [Variable(v, "output", n, "m/s", d.format("velocity")) for _, _, v, n, d in group]
    out.append(Variable("F_u", "output", 2, "N", "applied rotating unbalance force vector (residual + blade loss)"))
    return tuple(out)


def layout_of_file(model_file: str = "") -> attach.Layout:
    """The bearings and rub rings of a model file's [attach] (a test rotor's [shaft] has the paper's)."""
    return engine_of_file(model_file)[0]


def engine_of_file(model_file: str = "") -> tuple[attach.Layout, attach.Words]:
    """:func:`layout_of_file`, and what the port descriptions call the file's parts (attach.Words)."""
    key = fem.file_digest(model_file or None)
    found = _LAYOUTS.get(key)
    if found is None:
        data, _ = fem.load_data(model_file or None)
        lay = (attach.PAPER if shaft_model.is_shaft_model(data)
               else attach.with_mounts(attach.layout(data.get("attach", {}), fem.fuse_ids(data)), data))
        found = _LAYOUTS[key] = (lay, attach.words(data, lay))
    return found


_LAYOUTS: dict[str, tuple[attach.Layout, attach.Words]] = {}
#: the paper's engine's load groups (brg0, brg5, housing0, housing5, rub0, rub5, unbalance)
LOAD_GROUPS = attach.load_groups(attach.PAPER)
# reduced models, per process: (file digest, n_modes, omega_pt, omega_gg) -> dict
_REDUCED: dict[tuple, dict] = {}
_FULL: dict[tuple, fem.FullModel] = {}


def full_model(model_file: str = "", omega_pt=None, omega_gg=None) -> fem.FullModel:
    # the digest first: parsing the TOML on every set-up cost ~4 ms a run when the model is already built
    model = _FULL.get((fem.file_digest(model_file or None), omega_pt, omega_gg))
    if model is None:
        data, digest = fem.load_data(model_file or None)
        build = shaft_model.build if shaft_model.is_shaft_model(data) else fem.build   # a test rotor's [shaft]
        model = _FULL[(digest, omega_pt, omega_gg)] = build(data, digest, omega_pt, omega_gg,
                                                            source=model_file or None)
    return model


def reduced_model(model_file: str, n_modes: int, omega_pt: float, omega_gg: float) -> dict:
    """MTA-reduced matrices (eqs. 20-22) and the port rows of the basis, in the order of attach.py's groups and
    ports for the model's bearings and rub rings (``layout``); cached per process. Supports with coefficients over
    speed have them at ``omega_pt`` (the first spool's speed)."""
    full = full_model(model_file, omega_pt, omega_gg)
    lay = attach.layout_of_ports(full.ports)
    fem.require_ports(full, attach.load_groups(lay))
    key = (full.digest, int(n_modes), float(omega_pt), float(omega_gg))
    red = _REDUCED.get(key)
    if red is None:
        load_dofs = np.concatenate([full.ports[g] for g in attach.load_groups(lay)])
        speed_supports = bool(full.info.get("speed_supports"))
        # cross-coupled supports make K unsymmetric: the basis is of its symmetric part (a Ritz basis: the
        # projection below takes K whole)
        basis, n_aug = mta_basis(0.5 * (full.K + full.K.T) if speed_supports else full.K, full.M, int(n_modes),
                                 load_dofs)
        C = full.C + omega_pt * full.G_pt + omega_gg * full.G_gg
        Mr, Cr, Kr = project(basis, full.M, C, full.K)
        if speed_supports:    # their coefficients at the first spool's speed (the file's K, C hold its speed_rpm's)
            dK, dC = fem.projected_support_delta(full, basis, omega_pt)
            Kr, Cr = Kr + dK, Cr + dC
        in_dofs = np.concatenate([full.ports[g] for _, g, _, _ in attach.input_ports(lay)]
                                 + [full.ports["unbalance"]])
        out_dofs = np.concatenate([full.ports[g] for g, _, _, _, _ in attach.output_ports(lay)])
        red = {"M": Mr, "C": Cr, "K": Kr, "B_in": basis[in_dofs].T.copy(), "O": basis[out_dofs].copy(),
               "n": basis.shape[1], "n_aug": n_aug, "basis": basis, "layout": lay}
        _REDUCED[key] = red
    return red


def _in_words(v: Variable, w: attach.Words, descriptions: dict[str, str]) -> Variable:
    """``v`` described in the engine's words ``w`` where ``descriptions`` has it; else ``v``."""
    text = descriptions.get(v.name)
    if text is None:
        return v
    second = w.second or "second spool (this engine has none)"
    return dataclasses.replace(v, description=text.format(first=w.first, second=second))


class Rotor(PositionalKernelComponent):
    """Flexible dual-rotor engine + casing (MTA-reduced FE model, Newmark-beta), blade-loss force."""

    description = ("Flexible dual-rotor gas turbine engine with casing: Timoshenko FE model reduced by modal "
                   "truncation augmentation, Newmark-beta integration, rotating blade-loss force")
    file_parameters = ("model_file",)   # a relative path: from the scenario file's folder
    variables = (
        Variable("F_unbalance", "parameter", unit="N", start=2850.0,
                 description="blade-loss force amplitude (rotating at the PT speed, PT outboard end)"),
        Variable("F_residual", "parameter", unit="N", start=0.0,
                 description="residual unbalance force before the blade loss, same node (0: none; the paper's "
                             "engine file gives 87 N, ISO 21940-11 G 2.5)"),
        Variable("unbalance_phase", "parameter", unit="rad", start=0.5 * math.pi,
                 description="angle of the lost blade relative to the residual unbalance (default 90 deg: the "
                             "residual adds in quadrature; see the module docstring)"),
        Variable("t_blade_loss", "parameter", unit="s", start=0.01, description="blade-loss time (step onset)",
                 event="the blade loss"),
        Variable("omega_pt", "parameter", unit="rad/s", start=PT_OMEGA, description="power-turbine speed"),
        Variable("omega_gg", "parameter", unit="rad/s", start=GG_OMEGA, description="gas-generator speed"),
        Variable("n_modes", "parameter", unit="1", start=30, type="Integer",
                 description="retained eigenmodes (the reduced size adds 12 augmentation vectors)"),
        Variable("model_file", "parameter", unit="1", start="", type="String",
                 description="TOML model data file ('' = the shipped data/engine.toml)"),
        Variable("newmark_beta", "parameter", unit="1", start=0.25, description="Newmark beta"),
        Variable("newmark_gamma", "parameter", unit="1", start=0.5, description="Newmark gamma"),
    ) + port_variables(attach.PAPER)   # an instance declares those of its model file's [attach] (__init__)
    #: the variables whose descriptions name the paper's spools, as an engine of other spools says them
    #: ({first}, {second}: its first and second spools, attach.Words)
    spool_descriptions = {
        "F_unbalance": "blade-loss force amplitude (rotating at the speed of the {first}, at [attach] unbalance)",
        "omega_pt": "speed of the {first} (the first spool)",
        "omega_gg": "speed of the {second}",
    }
    preferred_step = 1e-5
    phases = frozenset({"TM"})
    step_cost_s, kernel_step_cost_s, setup_cost_s = 16e-6, 5e-6, 0.2  # bench/bench_estimate.py

    def __init__(self, name: str = "rotor", parameters=None):
        # the ports follow the model file's [attach] (attach.py): any number of bearings and rub rings. A file that
        # cannot be read keeps the class's ports here; setup names its problem.
        try:
            lay, w = engine_of_file(str((parameters or {}).get("model_file", "") or ""))
        except (ValueError, OSError):
            lay, w = attach.PAPER, attach.Words()
        self._layout = lay
        if lay != attach.PAPER or w != attach.Words():
            declared = port_variables(attach.PAPER)
            names = {v.name for v in declared}
            own = [v for v in type(self).variables if v.name not in names]
            at = next(i for i, v in enumerate(type(self).variables) if v.name in names)
            self.variables = tuple(own[:at]) + port_variables(lay, w) + tuple(own[at:])
        if (w.first, w.second) != (attach.Words.first, attach.Words.second):
            # a time series or modelDescription of a user's engine read "power-turbine speed" for its one spool
            self.variables = tuple(_in_words(v, w, self.spool_descriptions) for v in self.variables)
        super().__init__(name, parameters)

    def port_speeds(self) -> dict[str, tuple[str, float]]:
        """``{output port: (parameter, speed [rad/s])}``: the speed the spool node of each bearing's and rub
        ring's output ports turns at, the parameter giving it (the first spool omega_pt, the second omega_gg), from
        the model file's [attach] before set-up; what a part linked to the port with a speed of its own must
        agree with (master/scenario/build.check_speeds). Empty when the file cannot say (a test rotor's [shaft],
        a file that cannot be read: set-up names its problem)."""
        try:
            data, _ = fem.load_data(str(self.p.get("model_file") or "") or None)
        except (ValueError, OSError):
            return {}
        at, spools = data.get("attach"), data.get("spool")
        if shaft_model.is_shaft_model(data) or not isinstance(at, dict) or not isinstance(spools, dict):
            return {}
        # a third spool and later turn at their files' ratio to the second: no parameter of their own to name
        own = dict(zip(spools, ("omega_pt", "omega_gg")))
        out = {}
        for ids, entry, ports in ((self._layout.bearings, "bearing", ("X_brg", "V_brg")),
                                  (self._layout.rubrings, "rubring", ("X_rub", "V_rub"))):
            for i in ids:
                where = at.get(f"{entry}{i}")
                node = where.get("node") if isinstance(where, dict) else None
                param = own.get(node[0]) if isinstance(node, list) and node and isinstance(node[0], str) else None
                if param is not None:
                    out.update({f"{port}{i}": (param, float(self.p[param])) for port in ports})
        return out

    # -- parameters ------------------------------------------------------------------------------------
    def _check_parameters(self):
        p = self.p
        for k in ("F_unbalance", "F_residual", "t_blade_loss"):
            if p[k] < 0.0:
                raise ContractError(f"{self.name}.{k} must be >= 0, got {p[k]}")
        for k in ("omega_pt", "omega_gg"):
            if p[k] <= 0.0:
                raise ContractError(f"{self.name}.{k} must be > 0 rad/s, got {p[k]}")
        if p["n_modes"] < 1:
            raise ContractError(f"{self.name}.n_modes must be >= 1, got {p['n_modes']}")
        try:
            check_parameters(p["newmark_beta"], p["newmark_gamma"])
        except ValueError as exc:
            raise ContractError(f"{self.name}: {exc}") from None

    def setup(self, t0=0.0):
        super().setup(t0)
        self._check_parameters()
        p = self.p
        try:
            red = reduced_model(p["model_file"], p["n_modes"], p["omega_pt"], p["omega_gg"])
        except (ValueError, FileNotFoundError) as exc:
            raise ContractError(f"{self.name}: {exc}") from None
        if red["layout"] != self._layout:
            raise ContractError(f"{self.name}: the model file's bearings {list(red['layout'].bearings)} and rub rings "
                                f"{list(red['layout'].rubrings)} are not those the component was made with "
                                f"({list(self._layout.bearings)}, {list(self._layout.rubrings)}): model_file "
                                "changed after it was made")
        self._red = red
        self._offsets()
        self._ops: dict[float, tuple] = {}
        self._W = p["omega_pt"]
        n, O = red["n"], red["O"]
        # outputs (X, V at the port DOFs) = Oxv @ (x, v, a)
        self._Oxv = np.zeros((2 * O.shape[0], 3 * n))
        self._Oxv[:O.shape[0], :n] = O
        self._Oxv[O.shape[0]:, n:2 * n] = O
        self._Oxv = np.asfortranarray(self._Oxv)
        self._f = np.zeros(red["B_in"].shape[1])
        x0 = np.zeros(n)
        f0 = red["B_in"] @ self._input_vector(t0)
        a0 = initial_acceleration(red["M"], red["C"], red["K"], x0, x0, f0)
        self.state = {"s": np.concatenate([x0, x0, a0]), "tau": np.array([float(t0)])}
        self._kernel_h = None
        self._write_outputs(self.state["s"], t0)

    # -- the blade release: a time event (master/core/events.py) --------------------------------------------
    #: the steps apply the release (the unbalance force from the end of the step that holds t_blade_loss): a
    #: coupled interval runs them as they are; a held interval ends at it and records it
    time_events_in_steps = True

    def next_event(self, t):
        """The blade release while it is to come, at ``t`` itself too (as the spool's fuel cut: the step from it
        on is the first to respond to it, so a held interval starting there would freeze its start); None
        without a blade-loss force. The 1e-9 s absorbs the round-off of interval ends."""
        tb = self.p["t_blade_loss"]
        return float(tb) if self.p["F_unbalance"] != 0.0 and tb >= t - 1e-9 else None

    # -- stepping --------------------------------------------------------------------------------------
    def _unbalance(self, t, tau=None):
        """The rotating unbalance force at time t. Its angle is the rotor's own angle W tau, where tau is the
        mechanical time (the time the rotor has actually been stepped, part of its state): over a thermal-only
        interval the frozen rotor keeps its angle with its frozen whirl, so the next thermo-mechanical interval
        resumes the same phase-locked orbit. Using the global time instead would turn the unbalance by W x (the
        thermal-only duration) against the frozen orbit and start every interval with an artificial transient."""
        p = self.p
        W = self._W
        a = W * (t if tau is None else float(np.asarray(tau).reshape(-1)[0]))
        fx = p["F_residual"] * math.cos(a)
        fy = p["F_residual"] * math.sin(a)
        if t >= p["t_blade_loss"]:
            ph = a + p["unbalance_phase"]
            fx += p["F_unbalance"] * math.cos(ph)
            fy += p["F_unbalance"] * math.sin(ph)
        return fx, fy

    def _offsets(self):
        """The offset tables of the ports (kernel.RotorParams): where each input enters the force vector, where
        each output is read from the output rows, and the Python side's output slices."""
        lay = self._layout
        ins = attach.input_ports(lay)
        at, k = {}, 0
        for name, _, n, _ in ins:
            at[name] = k
            k += n
        self._in_names = [name for name, _, _, _ in ins]
        rows, r = {}, 0
        outs = attach.output_ports(lay)
        for _, x, _, n, _ in outs:
            rows[x] = r
            r += n
        for _, _, v, n, _ in outs:
            rows[v] = r
            r += n
        sizes = {x: n for _, x, _, n, _ in outs} | {v: n for _, _, v, n, _ in outs}
        self._out_slices = [(name, rows[name], rows[name] + sizes[name]) for name in rows]
        _, _, in_fields, out_fields = self.kernel_ports()
        self._in_off = np.array([at.get(name, -1) for name in in_fields], dtype=np.int64)
        # where the speed inputs of the speed-following variant (spinning.py) are in the input tuple
        self._speed_at = np.array([in_fields.index(n) if n in in_fields else -1
                                   for n in ("Omega_pt", "Omega_gg", "dOmega_pt")], dtype=np.int64)
        self._out_off = np.array([rows.get(name, -1) for name in out_fields], dtype=np.int64)

    def _input_vector(self, t):
        u = self.u
        f = np.concatenate([u[name] for name in self._in_names] + [self._unbalance(t)])
        if not np.all(np.isfinite(f)):
            bad = [name for name in self._in_names if not np.all(np.isfinite(u[name]))]
            raise ContractError(f"{self.name}: non-finite input force(s) {bad} at t = {t:.9g} s")
        return f

    def _operators(self, h):
        ops = self._ops.get(h)
        if ops is None:
            key = float(f"{h:.12g}")
            ops = self._ops.get(key)
            if ops is None:
                red = self._red
                T, B = step_operator(red["M"], red["C"], red["K"], key, self.p["newmark_beta"],
                                     self.p["newmark_gamma"])
                ops = pack(T, B @ red["B_in"])
                if len(self._ops) > 32:        # many distinct steps (a variable-step master): do not grow forever
                    self._ops.clear()
                self._ops[key] = ops
            self._ops[h] = ops
        return ops

    def _write_outputs(self, s, t):
        self._publish(self._Oxv @ s, t)

    def _publish(self, xv, t, fux=None, fuy=None):
        y = self.y
        for name, a, b in self._out_slices:
            y[name] = xv[a:b]
        y["F_u"] = np.array(self._unbalance(t) if fux is None else (fux, fuy))

    # -- the compiled kernel (components/kernels.py) ---------------------------------------------------------
    STEP = staticmethod(tm_step)

    def kernel_state(self):
        return RotorState(self.state["s"], self.state["tau"])

    def kernel_prepare(self, h):
        if h != getattr(self, "_kernel_h", None):
            p = self.p
            n3 = 3 * self._red["n"]
            self._kernel_p = RotorParams(self._operators(h), self._Oxv, self._f, np.empty(n3),
                                         np.empty(self._Oxv.shape[0]), float(self._W), float(p["F_residual"]),
                                         float(p["F_unbalance"]), float(p["unbalance_phase"]),
                                         float(p["t_blade_loss"]), self._in_off, self._out_off)
            self._kernel_h = h
            self._last_h = h

    def kernel_params(self):
        return self._kernel_p

    def kernel_status(self, status, t, h):
        if status == 2:
            self._input_vector(t + h)          # names the offending input
        raise Diverged(f"{self.name}: the rotor response became non-finite at t = {t + h:.9g} s")

    # -- helpers for checks and the CLI ------------------------------------------------------------------
    @property
    def reduced(self) -> dict:
        return self._red

    def full_model(self) -> fem.FullModel:
        return full_model(self.p["model_file"], self.p["omega_pt"], self.p["omega_gg"])
