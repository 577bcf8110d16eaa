"""8-node trilinear solid (hexahedron) element: stiffness and consistent mass by 2 x 2 x 2 Gauss quadrature.

Standard isoparametric formulation (Zienkiewicz & Taylor, The Finite Element Method, vol. 1, ch. 6/9; Cook et
al., Concepts and Applications of FEA, ch. 6). Node order: the bottom face (zeta = -1) counter-clockwise
(-1,-1), (1,-1), (1,1), (-1,1) in (xi, eta), then the top face in the same order. DOFs (ux, uy, uz) per node.
|det J| is used so a left-handed node order gives the same matrices.
"""
from __future__ import annotations

import numpy as np

_NAT = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                 [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
_G = 1.0 / np.sqrt(3.0)
_GAUSS = np.array([[a, b, c] for a in (-_G, _G) for b in (-_G, _G) for c in (-_G, _G)])


def _shape(pt):
    xi, eta, zeta = pt
    N = 0.125 * (1 + _NAT[:, 0] * xi) * (1 + _NAT[:, 1] * eta) * (1 + _NAT[:, 2] * zeta)
    dN = np.empty((8, 3))
    dN[:, 0] = 0.125 * _NAT[:, 0] * (1 + _NAT[:, 1] * eta) * (1 + _NAT[:, 2] * zeta)
    dN[:, 1] = 0.125 * _NAT[:, 1] * (1 + _NAT[:, 0] * xi) * (1 + _NAT[:, 2] * zeta)
    dN[:, 2] = 0.125 * _NAT[:, 2] * (1 + _NAT[:, 0] * xi) * (1 + _NAT[:, 1] * eta)
    return N, dN


_SHAPES = [_shape(p) for p in _GAUSS]


def isotropic_D(E: float, nu: float) -> np.ndarray:
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[np.arange(3), np.arange(3)] += 2 * mu
    D[3:, 3:] = np.eye(3) * mu
    return D


def hex8(xyz: np.ndarray, E: float, nu: float, rho: float):
    """24 x 24 stiffness and consistent mass of one hexahedron with node coordinates ``xyz`` (8 x 3)."""
    D = isotropic_D(E, nu)
    K = np.zeros((24, 24))
    M = np.zeros((24, 24))
    for N, dN in _SHAPES:
        J = dN.T @ xyz
        detJ = np.linalg.det(J)
        if abs(detJ) < 1e-300:
            raise ValueError("degenerate hexahedral element (zero Jacobian)")
        dNx = dN @ np.linalg.inv(J).T          # (8, 3) derivatives in x, y, z
        B = np.zeros((6, 24))
        B[0, 0::3] = dNx[:, 0]
        B[1, 1::3] = dNx[:, 1]
        B[2, 2::3] = dNx[:, 2]
        B[3, 0::3] = dNx[:, 1]
        B[3, 1::3] = dNx[:, 0]
        B[4, 1::3] = dNx[:, 2]
        B[4, 2::3] = dNx[:, 1]
        B[5, 0::3] = dNx[:, 2]
        B[5, 2::3] = dNx[:, 0]
        w = abs(detJ)
        K += B.T @ D @ B * w
        Nm = np.zeros((3, 24))
        for d in range(3):
            Nm[d, d::3] = N
        M += rho * Nm.T @ Nm * w
    return K, M
