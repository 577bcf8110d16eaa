"""The airframe component (``airframe.modal``): the aircraft side of the engine's mounts, a reduced linear model.

Given the engine file (``model_file``, a scenario's ``"engine:file"``), it takes the engine's mounts
(``[mount.NAME]``, components/rotor/mounts.py) and the airframe's reduced model (``[airframe] model``, modal.py),
and steps the airframe's modes under the engine's motion at the mounts (kernel.py: the equations). Its ports
follow the engine file:

* inputs ``X_mount_NAME``, ``V_mount_NAME`` [m, m/s] (one value per spring of mount NAME, along its axis): the
  rotor's outputs of the same name;
* outputs ``F_engine_NAME`` [N] (per spring): the force the airframe's motion puts on the engine through the mount,
  to the rotor's input ``F_mount_NAME``; ``F_NAME`` [N] (x y z): the mount's load on the airframe (the interface
  load), and ``M_NAME`` [N m] (x y z, about the interface point) when a spring of the mount acts on a rotation or
  ends off the point (``offset_mm``); ``a_POINT`` [m/s2] (x y z):
  the acceleration at each response point of the airframe model.

It takes part in the coupled phase only: in a held interval its outputs are held (the hold manipulator), as the
rotor's. At set-up the airframe is at rest.

Example (a scenario; the connections follow the mounts)::

    [components.airframe]
    implementation = "airframe.modal"
    parameters = { model_file = "engine:file" }
    # rotor.X_mount_fwd -> airframe.X_mount_fwd, rotor.V_mount_fwd -> airframe.V_mount_fwd,
    # airframe.F_engine_fwd -> rotor.F_mount_fwd (and the same per mount)
"""
from __future__ import annotations

import numpy as np

from ..contract import COUPLED, ContractError, Variable
from ..kernels import PositionalKernelComponent
from ..rotor.model import DEFAULT_FILE
from ..rotor.newmark import step_operator
from .kernel import AirframeParams, AirframeState, tm_step
from .modal import ModalModel
from .mounting import installed, spring_rows

#: a response point's output: its acceleration
ACCELERATION = "a_"
#: the columns of a moment's and an acceleration's x y z (the time series' ``columns``; they read 1, 2, 3)
AXES = ("x", "y", "z")


def port_variables(found: dict, model: ModalModel | None) -> tuple[Variable, ...]:
    """The ports of the mounts ``found`` and the response points of ``model`` (module docstring)."""
    out = []
    for m in found.values():
        n = len(m.springs)
        out += [Variable(f"X_mount_{m.name}", "input", n, "m", f"engine displacement at the {n} springs of mount "
                                                               f"{m.name}, along their axes"),
                Variable(f"V_mount_{m.name}", "input", n, "m/s", f"engine velocity at the {n} springs of mount "
                                                                 f"{m.name}, along their axes")]
    for m in found.values():
        out.append(Variable(f"F_engine_{m.name}", "output", len(m.springs), "N",
                            f"the airframe's motion's force on the engine through each spring of mount {m.name}"))
    for m in found.values():
        out.append(Variable(f"F_{m.name}", "output", 3, "N", f"load of mount {m.name} on the airframe (x y z)"))
        if m.moment:
            out.append(Variable(f"M_{m.name}", "output", 3, "N.m",
                                f"moment of mount {m.name} on the airframe (about x y z)", labels=AXES))
    for p in (model.response if model is not None else ()):
        out.append(Variable(f"{ACCELERATION}{p}", "output", 3, "m/s2", f"acceleration at response point {p} "
                                                                       "(x y z)", labels=AXES))
    return tuple(out)


class Airframe(PositionalKernelComponent):
    """The airframe's reduced linear model on the engine's mounts (module docstring)."""

    description = ("Airframe on the engine's mounts: a reduced linear (modal) model at the mounts' interface points "
                   "and response points, the mount springs between them and the engine. Its ports follow the "
                   "engine file: inputs X_mount_NAME, V_mount_NAME (per spring of mount NAME); outputs "
                   "F_engine_NAME (per spring, to the rotor's F_mount_NAME), F_NAME [N] and M_NAME [N m] (the "
                   "mount's load on the airframe, x y z), a_POINT [m/s2] (each response point, x y z)")
    file_parameters = ("model_file",)
    variables = (
        Variable("model_file", "parameter", unit="1", start="", type="String",
                 description="the engine file whose [mount.NAME] tables and [airframe] model this is (a scenario "
                             "gives \"engine:file\")"),
    )
    preferred_step = 5e-6
    phases = frozenset({COUPLED})
    step_cost_s = 10e-6

    def __init__(self, name: str = "airframe", parameters=None):
        # the ports follow the engine file's mounts and the airframe model's response points: a file that cannot
        # be read is refused here, before the ports are connected (a connection to a port the component would have
        # had would otherwise name the port, not the cause)
        self._found, self._model, self._problem = {}, None, None
        try:
            self._found, self._model = installed(str((parameters or {}).get("model_file", "") or ""))
        except (ValueError, OSError) as exc:
            raise ContractError(f"{name}.model_file: {exc}") from None
        self.variables = type(self).variables + port_variables(self._found, self._model)
        super().__init__(name, parameters)

    def standalone_problem(self) -> str | None:
        """An engine file without mounts on an airframe model gives no ports and nothing to step."""
        if self._model is None or not self._found:
            return (f"{self.name}.model_file: the engine file {self.p['model_file'] or DEFAULT_FILE} has no "
                    "[airframe] and [mount.NAME] tables (an engine on a rigid ground needs no airframe component)")
        return None

    def setup(self, t0=0.0):
        super().setup(t0)
        if self._problem is None:
            try:
                self._found, self._model = installed(self.p["model_file"])
            except (ValueError, OSError) as exc:
                self._problem = str(exc)
        if self._problem is not None:
            raise ContractError(f"{self.name}.model_file: {self._problem}")
        problem = self.standalone_problem()
        if problem is not None:
            raise ContractError(problem)
        self._matrices()
        self.state = {"s": np.zeros(3 * self._model.n)}
        self._ops: dict[float, np.ndarray] = {}
        self._kernel_h = None
        self._y_all = np.zeros(self._O.shape[0])
        self._w = np.zeros(self._O.shape[1])
        self._offsets()
        self._publish_rest()

    def _matrices(self) -> None:
        """B (springs x modes), the springs' k and c, and the output rows O over [s_new, u] (kernel.py)."""
        model = self._model
        _, B, ks, cs = spring_rows(self._found, model)
        n, ns = model.n, len(ks)
        self._B, self._k, self._c = B, ks, cs
        self._Keff = np.diag(model.w ** 2) + B.T @ (ks[:, None] * B)
        self._Ceff = np.diag(2.0 * model.zeta * model.w) + B.T @ (cs[:, None] * B)
        self._Bu = np.hstack([B.T * ks, B.T * cs])              # modal force per [x_e, v_e]
        out, self._out_rows = [], {}
        width = 3 * n + 2 * ns

        def add(name, block):
            self._out_rows[name] = sum(len(r) for r in out)
            out.append(block)

        # F_engine: k B q + c B q' (of the state one step on: kernel_prepare)
        at = 0
        for m in self._found.values():
            sel = slice(at, at + len(m.springs))
            blk = np.zeros((len(m.springs), width))
            blk[:, :n] = ks[sel, None] * B[sel]
            blk[:, n:2 * n] = cs[sel, None] * B[sel]
            add(f"F_engine_{m.name}", blk)
            at += len(m.springs)
        self._n_engine_rows = at
        at = 0
        for m in self._found.values():
            F = np.zeros((3, width))
            Mo = np.zeros((3, width))
            for j, s in enumerate(m.springs):
                i = at + j
                row = np.zeros(width)
                row[:n] = -ks[i] * B[i]
                row[n:2 * n] = -cs[i] * B[i]
                row[3 * n + i] = ks[i]
                row[3 * n + ns + i] = cs[i]
                (F if s.dir < 3 else Mo)[s.dir % 3] += row
                if s.offset is not None:          # r x (f e_d) about the interface point
                    Mo += np.outer(np.cross(s.offset, np.eye(3)[s.dir]), row)
            add(f"F_{m.name}", F)
            if m.moment:
                add(f"M_{m.name}", Mo)
            at += len(m.springs)
        for p, phi in model.response.items():
            blk = np.zeros((3, width))
            blk[:, 2 * n:3 * n] = phi[:, :3].T
            add(f"{ACCELERATION}{p}", blk)
        self._O = np.asfortranarray(np.vstack(out))

    def _offsets(self) -> None:
        ins, outs = self._ports("input"), self._ports("output")
        at, k = {}, 0
        for m in self._found.values():
            at[f"X_mount_{m.name}"] = k
            k += len(m.springs)
        for m in self._found.values():
            at[f"V_mount_{m.name}"] = k
            k += len(m.springs)
        self._in_off = np.array([at[n] for n in ins], dtype=np.int64)
        self._out_off = np.array([self._out_rows[n] for n in outs], dtype=np.int64)

    def _publish_rest(self) -> None:
        for name in self._ports("output"):
            self.y[name][:] = 0.0

    # -- the compiled kernel (components/kernels.py) ---------------------------------------------------------
    STEP = staticmethod(tm_step)

    def kernel_state(self):
        return AirframeState(self.state["s"])

    def kernel_prepare(self, h):
        if h != getattr(self, "_kernel_h", None):
            key = float(f"{h:.12g}")
            ops = self._ops.get(key)
            if ops is None:
                n = self._model.n
                T, Bn = step_operator(np.eye(n), self._Ceff, self._Keff, key)
                full = np.hstack([T, Bn @ self._Bu])
                # F_engine at the end of the coming step (kernel.py): its rows over the state, through one more step
                O = self._O.copy()
                r = self._n_engine_rows
                O[:r] = self._O[:r, :3 * n] @ full
                # the kernel steps the displacement rows and makes the velocities and accelerations from them
                ops = self._ops[key] = (np.asfortranarray(full[:n]), np.asfortranarray(O),
                                        np.array([4.0 / (key * key), 4.0 / key, 0.5 * key]))
            self._kernel_p = AirframeParams(*ops, self._w, self._y_all, self._in_off, self._out_off)
            self._kernel_h = h

    def kernel_params(self):
        return self._kernel_p

    def kernel_status(self, status, t, h):
        bad = [k for k in self._ports("input") if not np.all(np.isfinite(self.u[k]))]
        raise ContractError(f"{self.name}: non-finite input {', '.join(bad)} at t = {t + h:.9g} s")

    # -- for checks ----------------------------------------------------------------------------------------
    @property
    def model(self) -> ModalModel:
        return self._model

    @property
    def mounts(self) -> dict:
        return self._found
