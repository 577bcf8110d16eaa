"""The O-ring centering spring and the journal-housing wall contact, in parallel with the film.

Spring (paper Table 3, 5254 N/mm): F_spring = -k_spring d, d = X_journal - X_housing.

Wall contact: when the journal has used up the radial clearance c (e = |d| >= c, eccentricity ratio >= 1),
it touches the housing bore. The film model no longer applies there (h_min -> 0); a stiff radial penalty
spring acts instead, F_contact = -k_wall (e - c) d / e, frictionless (the damper journal does not spin: it is
held by anti-rotation pins, so sliding is only the slow whirl). Between the film model's limit eps_max and
the wall the film is held at its eps_max value (reynolds_fe.EPS_FILM_MAX). With k_wall = 0 touching the
wall is an error instead. A penetration larger than the clearance itself (e >= 2 c) is not a contact but a
diverged simulation and is an error in any case.

After the loss of the oil supply (the damper's ``oil_loss_time``) the film is gone and the journal runs on the
damper land: the same radial contact, with Coulomb friction against its whirl (:func:`land_friction`),

    F_friction = -mu F_n w_t / sqrt(|w_t|^2 + v_reg^2),    F_n = k_wall (e - c),

``w_t = w - (w . n) n`` the journal's sliding (tangential) velocity against the housing, ``mu`` the damper's
``land_friction``, ``v_reg`` = :data:`V_REG` (Coulomb friction regularised below it, as the support fuse's bumper).
"""
from __future__ import annotations

import math

from ..numba_internals import kernel_jit

#: e / c at which the wall penetration is taken as a diverged simulation
EPS_DIVERGED = 2.0

#: the sliding speed [m/s] below which the land's Coulomb friction is regularised (module docstring)
V_REG = 1e-4

#: status codes of :func:`spring_and_wall`
OK, NOT_FINITE, WALL_ERROR, DIVERGED = 0, 1, 2, 3


@kernel_jit(inline="always")
def spring_and_wall(dx, dy, clearance, k_spring, k_wall, out):
    """Spring and contact forces into out[10:14], their stiffness added to out[2:6] (row-major dF/dd),
    F_journal = film + spring + contact into out[14:16]. Returns a status code."""
    e = math.sqrt(dx * dx + dy * dy)
    eps = e / clearance
    out[17] = eps
    out[10] = -k_spring * dx
    out[11] = -k_spring * dy
    out[2] -= k_spring
    out[5] -= k_spring
    out[12] = 0.0
    out[13] = 0.0
    if eps >= EPS_DIVERGED:
        return DIVERGED
    if eps >= 1.0:
        if k_wall <= 0.0:
            return WALL_ERROR
        cx = dx / e
        cy = dy / e
        pen = e - clearance
        out[12] = -k_wall * pen * cx
        out[13] = -k_wall * pen * cy
        # d(-k (e - c) n)/dd = -k [n n^T + (1 - c/e)(I - n n^T)]
        t = 1.0 - clearance / e
        out[2] -= k_wall * (cx * cx + t * (1.0 - cx * cx))
        out[3] -= k_wall * (cx * cy - t * cx * cy)
        out[4] -= k_wall * (cx * cy - t * cx * cy)
        out[5] -= k_wall * (cy * cy + t * (1.0 - cy * cy))
    out[14] = out[0] + out[10] + out[12]
    out[15] = out[1] + out[11] + out[13]
    return OK


@kernel_jit(inline="always")
def land_friction(dx, dy, dvx, dvy, clearance, k_wall, mu, out):
    """The land's friction (module docstring) added to the contact force out[12:14], its derivative along the
    velocity to out[6:10] (row-major dF/dw), F_journal = film + spring + contact again into out[14:16]; nothing out
    of contact. Returns the friction's power [W] (>= 0)."""
    e = math.sqrt(dx * dx + dy * dy)
    if e <= clearance or mu <= 0.0:
        return 0.0
    nx, ny = dx / e, dy / e
    fn = k_wall * (e - clearance)
    vn = dvx * nx + dvy * ny
    tx, ty = dvx - vn * nx, dvy - vn * ny
    s = math.sqrt(tx * tx + ty * ty + V_REG * V_REG)
    g = mu * fn / s
    out[12] -= g * tx
    out[13] -= g * ty
    # d(-g P w)/dw with P = I - n n^T and g = mu F_n / s: -g (P - (P w)(P w)^T / s^2)
    pxx, pxy, pyy = 1.0 - nx * nx, -nx * ny, 1.0 - ny * ny
    out[6] -= g * (pxx - tx * tx / (s * s))
    out[7] -= g * (pxy - tx * ty / (s * s))
    out[8] -= g * (pxy - tx * ty / (s * s))
    out[9] -= g * (pyy - ty * ty / (s * s))
    out[14] = out[0] + out[10] + out[12]
    out[15] = out[1] + out[11] + out[13]
    return g * (tx * tx + ty * ty)


@kernel_jit(inline="always")
def dry_land(dx, dy, dvx, dvy, clearance, k_spring, k_wall, mu, out):
    """The damper without its oil supply: no film (out[0:10] and the film power out[16] zero), the centering
    spring, the wall contact and the land's friction. Returns a status code of :func:`spring_and_wall`."""
    for k in range(out.shape[0]):
        out[k] = 0.0
    if not math.isfinite(dx + dy + dvx + dvy):
        return NOT_FINITE
    status = spring_and_wall(dx, dy, clearance, k_spring, k_wall, out)
    if status == OK:
        land_friction(dx, dy, dvx, dvy, clearance, k_wall, mu, out)
    return status
