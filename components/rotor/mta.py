"""Modal truncation augmentation (MTA), the paper's eqs. (16)-(22), and plain modal truncation for comparison.

Eq. (17): retained eigenmodes Phi of K Phi = M Phi w^2 (mass-normalised). For every spatial load vector F_o
(a unit force at each DOF where a force enters the model), eq. (18): the force truncation vector
F_t = F_o - M Phi Phi^T F_o, the part of the load the retained modes miss; X = K^-1 F_t its static response;
eq. (19): the small eigenproblem of (X^T K X, X^T M X) turns the static vectors into M-orthonormal modal
truncation vectors eta = X psi; the basis is [Phi eta] (Dickens, Nakagawa & Wittbrodt 1997). Eqs. (20)-(22):
q = Phi~ chi and the projected M~, C~ (with the gyroscopic terms), K~ and F~ = Phi~^T F.
Because K^-1 M Phi = Phi w^-2, eta is M- and K-orthogonal to Phi, so M~ = I and K~ is diagonal; only C~ (damping
and gyroscopics) couples the coordinates.
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla


#: eigenvalues closer than this (relative) form one degenerate group, kept or dropped whole
DEGENERATE_RTOL = 1e-8


class RigidModesOnly(Exception):
    """The retained modes are all rigid-body modes: :func:`augmentation_vectors` has no shift to work with."""


def _rigid_only(K, M, n: int) -> str:
    """Why ``n`` retained modes give no basis: they are all rigid-body modes (w^2 ~ 0, within 1e-6 of the
    highest), of which the message gives the count the retained modes must exceed."""
    w2 = sla.eigh(K, M, eigvals_only=True)
    rigid = int(np.sum(w2 <= 1e-6 * float(np.max(np.abs(w2)))))
    return (f"n_modes = {n} retains rigid-body modes only (the rotor moves freely without its co-simulated "
            f"bearings: {rigid} such modes); retain more than {rigid} (n_modes >= {rigid + 1})")


def modes(K: np.ndarray, M: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The lowest ``n`` eigenpairs (w^2, Phi) of eq. (17), Phi mass-normalised; more than ``n`` when the n-th
    eigenvalue is degenerate (repeated, e.g. a symmetric casing's pair of modes): the whole group is kept.

    Cutting inside a degenerate group would keep an arbitrary vector of its eigenspace, chosen by LAPACK's
    rounding: the reduced model (and every result) then changed with nothing but the install (measured: 0.6 %
    on the first step's response, modes 30/31 of the engine are a pair at 1378.714 Hz)."""
    size = K.shape[0]
    if not 1 <= n <= size:
        raise ValueError(f"number of modes must be between 1 and {size}, got {n}")
    extra = min(8, size - n)
    w2, Phi = sla.eigh(K, M, subset_by_index=[0, n - 1 + extra])
    while n < len(w2) and abs(w2[n] - w2[n - 1]) <= DEGENERATE_RTOL * abs(w2[n - 1]):
        n += 1
    return w2[:n], Phi[:, :n]


def unit_loads(n: int, dofs) -> np.ndarray:
    """The spatial load vectors F_o: one unit force per DOF in ``dofs`` (n x len(dofs))."""
    dofs = np.asarray(dofs, dtype=int).reshape(-1)
    F = np.zeros((n, dofs.size))
    F[dofs, np.arange(dofs.size)] = 1.0
    return F


def augmentation_vectors(K, M, Phi, F_o, rtol: float = 1e-10) -> np.ndarray:
    """Modal truncation vectors eta (eqs. 18-19), M-orthonormal and M-orthogonal to Phi.

    Load vectors whose truncation part is (numerically) dependent on the others are dropped (rtol on the
    eigenvalues of X^T M X)."""
    F_t = F_o - M @ (Phi @ (Phi.T @ F_o))                      # eq. (18)
    try:
        factor = sla.cho_factor(K)                             # K X = F_t
    except sla.LinAlgError:
        # K singular: a spool held only by the co-simulated bearings has rigid-body modes without them. Their
        # static response is then taken on the shifted K + sigma M ((K + sigma M)^-1 M Phi = Phi / (w^2 + sigma),
        # so X stays M-orthogonal to the retained modes, which include the rigid ones); sigma = 1e-3 of the
        # highest retained eigenvalue keeps the shifted problem well conditioned
        sigma = 1e-3 * float(np.max(np.diag(Phi.T @ K @ Phi)))
        try:
            factor = sla.cho_factor(K + sigma * M)
        except sla.LinAlgError:
            # every retained mode is a rigid one (sigma ~ 0): no shift to take the static response on
            raise RigidModesOnly() from None
    X = sla.cho_solve(factor, F_t)
    # orthonormalise X in the M inner product first so dependent load vectors cannot make eq. (19) singular
    Mb = X.T @ M @ X
    s, U = sla.eigh(Mb)
    keep = s > rtol * s.max()
    X = X @ (U[:, keep] / np.sqrt(s[keep]))
    Kb, Mb = X.T @ K @ X, X.T @ M @ X                           # eq. (19)
    _, psi = sla.eigh(Kb, Mb)
    eta = X @ psi
    return eta


def mta_basis(K, M, n_modes: int, load_dofs) -> tuple[np.ndarray, int]:
    """The pseudo-modal set [Phi eta] and the number of augmentation vectors."""
    _, Phi = modes(K, M, n_modes)
    try:
        eta = augmentation_vectors(K, M, Phi, unit_loads(K.shape[0], load_dofs))
    except RigidModesOnly:
        raise ValueError(_rigid_only(K, M, n_modes)) from None
    return np.hstack([Phi, eta]), eta.shape[1]


def modal_basis(K, M, n: int) -> np.ndarray:
    """Plain modal truncation: the lowest ``n`` modes only (the comparison of the MTA check)."""
    return modes(K, M, n)[1]


def project(basis: np.ndarray, *matrices: np.ndarray) -> list[np.ndarray]:
    """Phi~^T A Phi~ for each matrix (eq. 22)."""
    return [basis.T @ A @ basis for A in matrices]
