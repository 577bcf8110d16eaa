"""Finite-element Reynolds equation of a non-rotating squeeze-film damper journal (paper section 4.1, Fig. 7).

Reynolds equation of the squeeze film (no journal spin), in the unrolled film x = R theta, axial z:

    d/dx (h^3/(12 mu) dp/dx) + d/dz (h^3/(12 mu) dp/dz) = dh/dt,
    h = c - e cos(theta'),   dh/dt = -v_r cos(theta') - v_t sin(theta'),

in the frame rotated to the eccentricity direction (theta' = theta - phi, v_r along and v_t normal to it).
Galerkin with linear triangles (assembled here with numpy + scipy.sparse, no scikit-fem):

    sum_j [ int h^3/12 grad N_i . grad N_j dA ] P_j = int N_i (-dh/dt) dA,     p - p_s = mu P,

on half the journal (z from the journal end, z = 0, to the axial mid-plane, z = L/2), periodic in theta,
Dirichlet p = p_s (P = 0) at z = 0, natural zero flux (q_n = 0) at the mid-plane: the paper's Fig. 7(b).
The mesh is n_theta x n_z rectangles, each split into two right triangles (so "128 x 64" means 128 x 64 cells,
16 384 triangles, 128 x 65 nodes). h^3 is integrated per element as the mean of its nodal values (exact for the
linear interpolant of h^3). The first node column lies on the minimum film (theta' = 0): the mesh is aligned
with the eccentricity, which is the best-resolved placement and makes the solution a function of the
eccentricity ratio only (what the fast model tabulates).

Because P is linear in (v_r, v_t) and p - p_s in mu, one factorisation and two unit solves give P_r, P_t;
the film force of the whole journal (both halves) is F = -2 sum_i p_i W_i with W_i = int N_i (cos, sin) dA.

For the interface Jacobian (K_film, C_film: see frame) the same factorisation gives the exact sensitivity of
the discrete solution to the eccentricity, dP/deps = -K^-1 (dK/deps) P, and the force derivatives follow
from the full-film (unclipped) nodes. The film is evaluated up to EPS_FILM_MAX; beyond it the component
holds it there (wall.py).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.sparse as sp
from scipy.linalg import LinAlgError, cho_solve_banded, cholesky_banded
from scipy.sparse.linalg import splu

from .frame import EPS_DIFF, EPS_NEAR_CENTRE, frame, gphi, to_housing_axes

#: largest eccentricity ratio at which the film is evaluated: at eps = 0.99 the minimum film (6 um for
#: c = 0.635 mm) spans a thin zone of half-width sqrt(2 (1 - eps)) = 0.14 rad, i.e. ~3 cells of the paper's
#: 128-cell circumference; closer to the wall the mesh no longer resolves the film (the component's wall
#: model takes over, see component)
EPS_FILM_MAX = 0.99


@dataclass(frozen=True)
class Mesh:
    """Structured triangulation of the unrolled half film; node n = j * n_theta + i (i around, j axial)."""

    radius: float
    half_length: float
    n_theta: int
    n_z: int
    theta: np.ndarray        # (n_nodes,) angle from the minimum film, rad
    tri: np.ndarray          # (n_el, 3) node indices
    orient: np.ndarray       # (n_el,) 0 or 1: which of the two triangle shapes
    Ke: np.ndarray           # (2, 3, 3) stiffness of a unit-coefficient triangle of each shape
    Wc: np.ndarray           # (n_nodes,) int N_i cos(theta') dA over the half film
    Ws: np.ndarray           # (n_nodes,) int N_i sin(theta') dA
    free: np.ndarray         # (n_free,) node indices off the Dirichlet end
    rows: np.ndarray         # COO pattern of the element matrices (n_el * 9)
    cols: np.ndarray

    @property
    def n_nodes(self) -> int:
        return self.n_theta * (self.n_z + 1)


def _tri_stiffness(xy: np.ndarray) -> np.ndarray:
    """Stiffness int grad N_i . grad N_j dA of a linear triangle with vertices xy (3, 2)."""
    (x1, y1), (x2, y2), (x3, y3) = xy
    area2 = (x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1)
    b = np.array([y2 - y3, y3 - y1, y1 - y2])
    c = np.array([x3 - x2, x1 - x3, x2 - x1])
    return (np.outer(b, b) + np.outer(c, c)) / (2.0 * abs(area2))


@lru_cache(maxsize=8)
def build_mesh(radius: float, length: float, n_theta: int, n_z: int) -> Mesh:
    """The mesh, its element shapes and the load/force weights (depend on geometry only; cached)."""
    if n_theta < 8 or n_z < 2:
        raise ValueError(f"mesh too coarse: n_theta={n_theta} (>= 8), n_z={n_z} (>= 2)")
    dth = 2.0 * math.pi / n_theta
    dx, dz = radius * dth, 0.5 * length / n_z
    i = np.arange(n_theta)
    j = np.arange(n_z)
    I, J = np.meshgrid(i, j)                       # cells
    I, J = I.ravel(), J.ravel()
    ip = (I + 1) % n_theta                           # periodic in theta
    n00, n10, n11, n01 = J * n_theta + I, J * n_theta + ip, (J + 1) * n_theta + ip, (J + 1) * n_theta + I
    tri = np.concatenate([np.stack([n00, n10, n11], 1), np.stack([n00, n11, n01], 1)])
    orient = np.concatenate([np.zeros(len(I), np.int64), np.ones(len(I), np.int64)])
    Ke = np.stack([
        _tri_stiffness(np.array([[0, 0], [dx, 0], [dx, dz]], float)),
        _tri_stiffness(np.array([[0, 0], [dx, dz], [0, dz]], float)),
    ])
    theta = np.tile(i * dth, n_z + 1)
    # consistent mass matrix (area/12 * [2 1 1; 1 2 1; 1 1 2]) times nodal cos/sin: int N_i cos dA of the
    # linear interpolant; the same weights give the load vector of a unit radial / tangential velocity
    area = 0.5 * dx * dz
    Me = area / 12.0 * (np.ones((3, 3)) + np.eye(3))
    n_nodes = n_theta * (n_z + 1)
    rows = np.repeat(tri, 3, axis=1).ravel()
    cols = np.tile(tri, (1, 3)).ravel()
    M = sp.csr_matrix((np.tile(Me.ravel(), len(tri)), (rows, cols)), shape=(n_nodes, n_nodes))
    Wc, Ws = M @ np.cos(theta), M @ np.sin(theta)
    free = np.arange(n_theta, n_nodes)
    for a in (theta, Wc, Ws, tri, orient, Ke, free, rows, cols):
        a.setflags(write=False)
    return Mesh(radius, 0.5 * length, n_theta, n_z, theta, tri, orient, Ke, Wc, Ws, free, rows, cols)


def _reduced_operator(mesh: Mesh, clearance: float, coeff: np.ndarray) -> sp.csc_matrix:
    """The free-free block of sum_e coeff_e K_e (coeff per element)."""
    data = (coeff[:, None, None] * mesh.Ke[mesh.orient]).ravel()
    n = mesh.n_nodes
    K = sp.csc_matrix((data, (mesh.rows, mesh.cols)), shape=(n, n))
    f = mesh.free
    return K[f][:, f].tocsc()


def _cholesky_banded(ab: np.ndarray):
    """x = K^-1 b from K's upper band ``ab`` (LAPACK's storage: ab[bw + i - j, j] = K[i, j]), or None where
    LAPACK finds K not positive definite."""
    try:
        cb = cholesky_banded(ab, lower=False, check_finite=False)
    except LinAlgError:
        return None
    return lambda b: cho_solve_banded((cb, False), b, check_finite=False)


def _narrow(bw: int, n: int) -> bool:
    """A band of half-width ``bw`` narrow enough for the banded factorisation of ``n`` unknowns (_band_solver)."""
    return bw <= 1.5 * math.sqrt(n)


def spd_solver(K: sp.spmatrix):
    """A solve function x = K^-1 b of the symmetric positive definite Reynolds operator K by SuperLU: symmetric
    ordering, no pivoting (~1.5x faster than COLAMD, measured). The meshes' own operators take the banded path
    first (:func:`_band_solver`); this is the path of a wide band or of a matrix LAPACK finds not positive
    definite."""
    lu = splu(K.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    return lu.solve


_BAND_MAPS: dict[tuple[int, int], tuple[np.ndarray, np.ndarray, int] | None] = {}


def _band_map(mesh: Mesh) -> tuple[np.ndarray, np.ndarray, int] | None:
    """Where each element-matrix entry (mesh.rows / mesh.cols order) goes in the upper band of the free-free
    operator: (kept entries, their flat index in the (bw + 1, n_free) band, bw); None for a wide band. The
    connectivity of build_mesh depends on (n_theta, n_z) alone: one map per pair."""
    key = (mesh.n_theta, mesh.n_z)
    if key not in _BAND_MAPS:
        r, c = mesh.rows - mesh.n_theta, mesh.cols - mesh.n_theta   # free nodes: all but the first row
        keep = np.flatnonzero((r >= 0) & (c >= 0) & (r <= c))
        r, c = r[keep], c[keep]
        n = mesh.n_nodes - mesh.n_theta
        bw = int(np.max(c - r))
        _BAND_MAPS[key] = (keep, (bw + r - c) * n + c, bw) if _narrow(bw, n) else None
    return _BAND_MAPS[key]


def _band_solver(mesh: Mesh, coeff: np.ndarray):
    """x = K^-1 b for the free-free block K of sum_e coeff_e K_e by a banded Cholesky factorisation (LAPACK pbtrf),
    the band assembled straight from the element matrices; None where the band is wide or K not positive definite
    (the caller takes spd_solver's sparse path).

    The mesh's node numbering (j n_theta + i) gives K a band of half-width n_theta + 1 (the periodic seam
    included); where it is narrow against the size (half-width <= 1.5 sqrt(n): the paper's 128 x 64 mesh, 129
    against 136) the banded factorisation takes 25 ms against 51 ms for SuperLU on its 8 192 unknowns, and
    assembling the band directly saves the sparse matrix and its slicing (~10 ms a point): a table point 67 -> 27
    ms, solutions equal within 2.3e-13 relative (measured)."""
    if not np.array_equal(mesh.free, np.arange(mesh.n_theta, mesh.n_nodes)):
        return None
    m = _band_map(mesh)
    if m is None:
        return None
    keep, flat, bw = m
    n = mesh.n_nodes - mesh.n_theta
    data = (coeff[:, None, None] * mesh.Ke[mesh.orient]).ravel()[keep]
    return _cholesky_banded(np.bincount(flat, weights=data, minlength=(bw + 1) * n).reshape(bw + 1, n))


def unit_fields(mesh: Mesh, clearance: float, eps: float, derivative: bool = False):
    """P_r, P_t (n_nodes each, Pa per (Pa s . m/s)): p - p_s = mu (v_r P_r + v_t P_t) at eccentricity ratio eps
    (eps < 0: the journal displaced towards theta' = pi).

    One factorisation of the Reynolds operator with h^3/12 (unit viscosity, :func:`spd_solver`), two right-hand
    sides. With
    ``derivative`` also dP_r/deps, dP_t/deps of the discrete solution (K dP = -dK/deps P, same LU).
    """
    if not -1.0 < eps < 1.0:
        raise ValueError(f"eccentricity ratio {eps} outside (-1, 1)")
    cos = np.cos(mesh.theta)
    h = clearance * (1.0 - eps * cos)
    coeff = (h**3)[mesh.tri].mean(axis=1) / 12.0
    f = mesh.free
    rhs = np.stack([mesh.Wc[f], mesh.Ws[f]], axis=1)   # int N_i (-dh/dt) for v_r = 1 and v_t = 1
    solve = _band_solver(mesh, coeff) or spd_solver(_reduced_operator(mesh, clearance, coeff))
    sol = solve(rhs)
    n = mesh.n_nodes
    Pr = np.zeros(n)
    Pt = np.zeros(n)
    Pr[f], Pt[f] = sol[:, 0], sol[:, 1]
    if not derivative:
        return Pr, Pt
    # d(h^3)/deps = -3 h^2 c cos(theta), averaged per element like h^3 itself
    dK = _reduced_operator(mesh, clearance, (-3.0 * h**2 * clearance * cos)[mesh.tri].mean(axis=1) / 12.0)
    dsol = solve(-(dK @ sol))
    dPr = np.zeros(n)
    dPt = np.zeros(n)
    dPr[f], dPt[f] = dsol[:, 0], dsol[:, 1]
    return Pr, Pt, dPr, dPt


def aligned_force(mesh: Mesh, fields, a: float, b: float, floor: float, cavitation: bool):
    """F_r, F_t, dF_r/da, dF_r/db, dF_t/da, dF_t/db, dF_r/deps, dF_t/deps of the field a P_r + b P_t
    (clipped at ``floor`` = p_cav - p_s when ``cavitation``), fields = unit_fields(..., derivative=True)."""
    Pr, Pt, dPr, dPt = fields
    p = a * Pr + b * Pt
    if cavitation:
        active = p >= floor
        p = np.where(active, p, floor)
        Pr, Pt = Pr * active, Pt * active
        dPr, dPt = dPr * active, dPt * active
    Wc, Ws = mesh.Wc, mesh.Ws
    dp = a * dPr + b * dPt
    return (-2.0 * float(Wc @ p), -2.0 * float(Ws @ p), -2.0 * float(Wc @ Pr), -2.0 * float(Wc @ Pt),
            -2.0 * float(Ws @ Pr), -2.0 * float(Ws @ Pt), -2.0 * float(Wc @ dp), -2.0 * float(Ws @ dp))


def film_force_aligned(mesh: Mesh, p_rel: np.ndarray) -> tuple[float, float]:
    """(F_r, F_t) on the whole journal from the half-film nodal pressure p - p_s (uniform p_s has no net force)."""
    return -2.0 * float(mesh.Wc @ p_rel), -2.0 * float(mesh.Ws @ p_rel)


def rotate_in(dx: float, dy: float, dvx: float, dvy: float) -> tuple[float, float, float, float, float]:
    """(e, cos phi, sin phi, v_r, v_t): the eccentricity frame (phi = 0 for a centred journal)."""
    e = math.hypot(dx, dy)
    if e > 0.0:
        c, s = dx / e, dy / e
    else:
        c, s = 1.0, 0.0
    return e, c, s, c * dvx + s * dvy, -s * dvx + c * dvy


def fe_film_eval(mesh: Mesh, clearance: float, dx: float, dy: float, dvx: float, dvy: float, mu: float,
                 floor: float, cavitation: bool, out: np.ndarray, eps_max: float = EPS_FILM_MAX) -> np.ndarray:
    """Direct FE film force and its exact derivatives in the housing axes: out[0:2] = F, out[2:6] = dF/dd,
    out[6:10] = dF/dw (row-major), at relative position d and velocity w; floor = p_cav - p_s. One assembly,
    one factorisation, four solves (plus the centred fields, cached, near the centre). Beyond eps_max the
    film is evaluated at eps_max in the direction of d (see frame for the chain rule)."""
    e, c, s = frame(dx, dy)
    eps = e / clearance
    saturated = eps > eps_max
    vr, vt = c * dvx + s * dvy, -s * dvx + c * dvy
    a, b = mu * vr, mu * vt
    r = aligned_force(mesh, _fields(mesh, clearance, min(eps, eps_max)), a, b, floor, cavitation)
    Fr, Ft, Jra, Jrb, Jta, Jtb, dr, dt = r
    if saturated:
        dr = dt = 0.0
    gr, gt = gphi(*r[:6], a, b)
    e_div = e
    if eps < EPS_NEAR_CENTRE:
        g0 = gphi(*aligned_force(mesh, _centred_fields(mesh, clearance), a, b, floor, cavitation)[:6], a, b)
        if e == 0.0:
            fields = _fields(mesh, clearance, EPS_DIFF)
            gr, gt = gphi(*aligned_force(mesh, fields, a, b, floor, cavitation)[:6], a, b)
            e_div = EPS_DIFF * clearance
        gr, gt = gr - g0[0], gt - g0[1]
    to_housing_axes(c, s, e_div, clearance, mu, Fr, Ft, Jra, Jrb, Jta, Jtb, dr, dt, gr, gt, out)
    return out


def _centred_fields(mesh: Mesh, clearance: float):
    return _fields(mesh, clearance, 0.0)


def _fields(mesh: Mesh, clearance: float, eps: float):
    """unit_fields with derivatives, remembered for the last few (geometry, eps): the fields do not depend on
    the velocities or the viscosity, so calls at the same position (the centred fields, a CLI sweep over
    velocities) solve once."""
    return _fields_of(mesh.radius, 2.0 * mesh.half_length, mesh.n_theta, mesh.n_z, clearance, eps)


@lru_cache(maxsize=6)
def _fields_of(radius, length, n_theta, n_z, clearance, eps):
    return unit_fields(build_mesh(radius, length, n_theta, n_z), clearance, eps, derivative=True)


def fe_film_force(mesh: Mesh, clearance: float, dx: float, dy: float, dvx: float, dvy: float, mu: float,
                  supply_pressure: float, cavitation_pressure: float, cavitation: bool,
                  return_field: bool = False):
    """Direct FE film force (Fx, Fy) on the journal at position (dx, dy) and velocity (dvx, dvy) relative to
    the housing: one assembly + factorisation + solve, Guembel clipping after the solve when ``cavitation``."""
    from .cavitation import guembel

    e, c, s, vr, vt = rotate_in(dx, dy, dvx, dvy)
    Pr, Pt = unit_fields(mesh, clearance, e / clearance)
    p_rel = mu * (vr * Pr + vt * Pt)
    if cavitation:
        p_rel = guembel(p_rel, supply_pressure, cavitation_pressure)
    Fr, Ft = film_force_aligned(mesh, p_rel)
    F = (c * Fr - s * Ft, s * Fr + c * Ft)
    return (F, p_rel) if return_field else F
