"""Full model against its reductions: the blade-loss transient on linear supports (the MTA check).

Bearings #0 and #5 are represented by massless linear springs (model.FullModel.linear_support with
:data:`SUPPORTS`: any linear support serves this check of the reduction; the engine's own linearisation, with the
journal bodies, is rotorcosim.cases.blade_loss.linear_engine), so the full model is linear and can be integrated directly; the reduced models use the basis the component uses (built on the
model *without* #0/#5, where the co-simulation applies their forces through the ports) with the supports projected
on it, i.e. the same equations the component + a linear bearing would give with an exact (implicit) coupling.
All three are integrated by the same Newmark scheme and step, so the differences are the reduction's alone.
"""
from __future__ import annotations

import numpy as np

from . import model as fem
from .component import LOAD_GROUPS
from .mta import modal_basis, mta_basis, project
from .newmark import integrate


#: the supports of the check: contact in series with the O-ring, film damping in parallel (orders of magnitude of
#: the engine's: master.linear_engine)
SUPPORTS = {"h0": {"pt_node": 3, "hub": "h0", "k_contact": 2.2e8, "k_spring": 1.05e7, "c_film": 5000.0},
            "h5": {"pt_node": 21, "hub": "h5", "k_contact": 2.1e8, "k_spring": 1.05e7, "c_film": 12000.0}}


def linear_system(full: fem.FullModel):
    Ks, Cs = full.linear_support(SUPPORTS)
    C = full.C + Cs + full.omega_pt * full.G_pt + full.omega_gg * full.G_gg
    return full.M, C, full.K + Ks


def basis(full: fem.FullModel, kind: str, n_modes: int) -> np.ndarray | None:
    """'full' -> None; 'mta' -> n_modes modes + augmentation vectors; 'modal' -> the same number of plain modes."""
    load_dofs = np.concatenate([full.ports[g] for g in LOAD_GROUPS])
    if kind == "full":
        return None
    phi, n_aug = mta_basis(full.K, full.M, n_modes, load_dofs)
    if kind == "mta":
        return phi
    if kind == "modal":
        return modal_basis(full.K, full.M, phi.shape[1])
    raise ValueError(f"unknown basis kind {kind!r} (full, mta, modal)")


def blade_loss_transient(full: fem.FullModel, kind: str = "mta", n_modes: int = 20, F_u: float = 2850.0,
                         h: float = 2e-5, t_end: float = 0.03) -> dict:
    """Response at bearings #0/#5 (x, y of the PT node) to F_u rotating at the PT speed from t = 0 (step onset)
    at the blade-loss node; returns the time, the histories and the peak radial displacements."""
    M, C, K = linear_system(full)
    ux, uy = full.ports["unbalance"]
    W = full.omega_pt
    rows = np.concatenate([full.ports["brg0"][:2], full.ports["brg5"][:2]])
    n = int(round(t_end / h))
    Phi = basis(full, kind, n_modes)
    if Phi is None:
        def force(t):
            f = np.zeros(M.shape[0])
            f[ux], f[uy] = F_u * np.cos(W * t), F_u * np.sin(W * t)
            return f
        x = integrate(M, C, K, force, np.zeros(M.shape[0]), np.zeros(M.shape[0]), h, n, record=rows)
    else:
        Mr, Cr, Kr = project(Phi, M, C, K)
        pu = Phi[[ux, uy]].T
        x = integrate(Mr, Cr, Kr, lambda t: pu @ np.array([F_u * np.cos(W * t), F_u * np.sin(W * t)]),
                      np.zeros(Phi.shape[1]), np.zeros(Phi.shape[1]), h, n) @ Phi[rows].T
    r0 = np.hypot(x[:, 0], x[:, 1])
    r5 = np.hypot(x[:, 2], x[:, 3])
    return {"t": np.arange(n + 1) * h, "x": x, "peak0": float(r0.max()), "peak5": float(r5.max()),
            "size": M.shape[0] if Phi is None else Phi.shape[1]}
