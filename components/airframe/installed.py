"""The installed engine: the engine's full model with its airframe's modes joined through the mounts.

For the linear engine (critical speeds, Campbell diagrams, the unbalance response: components/rotor/critical.py,
cases/blade_loss): the engine's matrices (model.FullModel, which holds each mount spring to ground at its engine
DOF) grow by the airframe's modal coordinates q (mass-normalised, modal.py), and each spring s of stiffness k_s
and damping c_s between the engine DOF i_s and the interface point's DOF B_s q (kernel.py) adds its remaining
terms

    K[q, q] += k_s B_s^T B_s,   K[i_s, q] = K[q, i_s] -= k_s B_s      (and the same for C with c_s),

so that the spring's energy k_s (u_i - B_s q)^2 / 2 is whole; the modes add M[q, q] = I, K[q, q] += diag(w^2),
C[q, q] += diag(2 zeta w). The engine's DOFs keep their indices (the ports, the whirl's DOFs, ``info["dof"]``);
the airframe's follow them, before the journals :meth:`FullModel.coupled` appends. An engine file without
``[airframe]``: :func:`installed_model` is the engine's model itself.

Example::

    >>> from rotorcosim.components.airframe.installed import installed_model
    >>> from rotorcosim.components.rotor.model import DEFAULT_FILE
    >>> m = installed_model(str(DEFAULT_FILE.with_name("engine_on_pylon.toml")))
    >>> m.info["airframe_modes"]
    40
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..rotor import model as fem
from ..rotor.mounts import port_group
from .modal import ModalModel
from .mounting import installed, spring_rows


def install(full: fem.FullModel, found: dict, model: ModalModel) -> fem.FullModel:
    """``full`` with the airframe ``model`` joined through the mounts ``found`` (module docstring)."""
    n0, na = full.n, model.n
    n = n0 + na
    q = np.arange(n0, n)
    dofs = np.concatenate([full.ports[port_group(m)] for m in found])
    _, B, k, c = spring_rows(found, model)

    def grow(A, modal, spring):
        out = np.zeros((n, n))
        out[:n0, :n0] = A
        if modal is not None:
            out[np.ix_(q, q)] += np.diag(modal) + B.T @ (spring[:, None] * B)
            for j, i in enumerate(dofs):
                out[i, q] -= spring[j] * B[j]
                out[q, i] -= spring[j] * B[j]
        return out

    M = grow(full.M, None, None)
    M[q, q] = 1.0
    K = grow(full.K, model.w ** 2, k)
    C = grow(full.C, 2.0 * model.zeta * model.w, c)
    info = dict(full.info, airframe_modes=na, airframe_dofs=q)
    return dataclasses.replace(full, M=M, K=K, C=C, G_pt=grow(full.G_pt, None, None),
                               G_gg=grow(full.G_gg, None, None), info=info)


def on_airframe(full: fem.FullModel, model_file: str) -> fem.FullModel:
    """``full`` (the model of the engine file ``model_file``) joined to its airframe (:func:`install`), or ``full``
    itself for an engine without one."""
    found, model = installed(model_file)
    if model is None or not found:
        return full
    return install(full, found, model)


def installed_model(model_file: str = "", **kw) -> fem.FullModel:
    """The engine of ``model_file`` ("" : the shipped one) with its airframe when it has one (:func:`install`),
    else its model alone; ``kw``: :func:`~rotorcosim.components.rotor.model.load`'s."""
    return on_airframe(fem.load(model_file or None, **kw), model_file)
