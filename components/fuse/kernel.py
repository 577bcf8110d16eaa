"""The support fuse's force law: the intact element, the soft path after the break, the bumper.

With ``x``, ``v`` the supported point's radial displacement and velocity (x, y) against the structure, the force
the fuse carries (transmitted to the structure) is

    F_support = k x + c v + F_bumper

with ``k`` the intact stiffness ``k_intact`` before the break and the post-fuse stiffness ``k_broken`` after it,
and the damping ``c`` in both states. The bumper (``bumper_stiffness`` > 0) is a radial stop at the clearance
``bumper_clearance``: with r = |x| and n = x / r, for r > clearance

    F_bumper = k_b (r - clearance) n + mu k_b (r - clearance) t,    t = v_t / sqrt(|v_t|^2 + v_reg^2),

``v_t = v - (v . n) n`` the tangential (whirl) velocity of the point against the bumper, ``mu`` the friction
coefficient, ``v_reg`` = :data:`V_REG` (Coulomb friction regularised below it, so that a point at rest on the
bumper carries no spurious friction). The force on the supported body is ``-F_support``.

The break, in one or two stages: stage ``s`` (0 intact, 1 after the first break, 2 after the second) carries the
stiffness ``k_s`` (``k_intact``, ``k_broken``, ``k_broken_2``), and breaks into stage ``s + 1`` when the magnitude
of its elastic force ``k_s |x|`` reaches the next break load ``L_(s+1)`` (``break_load``, ``break_load_2``). Its
event indicator is ``k_s |x| - L_(s+1)`` (negative below the load); none after the last stage (nothing left to
break). A two-stage fuse is the Rolls-Royce arrangement of US 9863274 B2: a first fuse that cuts the stiff load
path, a second one in the softer path left, which cuts it again at a further load. At a break the strain energy
``(k_s - k_(s+1)) |x|^2 / 2`` of the broken share leaves the system (the softer element no longer stores it).

The step (:func:`step`, components/kernels.py contract) breaks the fuse at its end through every stage whose load
the displacement reaches there (a fuse without the master's event location, an FMU in another tool, breaks at that
communication point), keeps the indicator's last value in its state ``g`` (``1`` for a stage broken and not yet
located by the master, ``reported``) and returns ``EVENT`` when the indicator changed sign over the step.
"""
from __future__ import annotations

import math
from collections import namedtuple

from ..kernels import EVENT, OK
from ..numba_internals import kernel_jit

#: the kernel's containers: ``broken`` (the stages broken), ``reported``, ``g`` (arrays of one value); the
#: stiffness of each stage ``k`` (intact first, one more than the loads) and the loads that break them ``loads``,
#: the damping and the bumper
FuseState = namedtuple("FuseState", "broken reported g")
FuseParams = namedtuple("FuseParams", "k loads damping k_b clearance mu")

#: the sliding speed [m/s] below which the bumper's Coulomb friction is regularised (kernel docstring)
V_REG = 1e-4


def support_force(x: float, y: float, vx: float, vy: float, k: float, c: float, k_b: float, clearance: float,
                  mu: float) -> tuple[float, float]:
    """F_support (x, y) [N] of the module docstring's law at the displacement (x, y) [m] and velocity (vx, vy)
    [m/s] with the element's present stiffness ``k`` [N/m], damping ``c`` [N s/m] and the bumper's stiffness
    ``k_b`` [N/m] (0: none), clearance [m] and friction coefficient ``mu``."""
    fx = k * x + c * vx
    fy = k * y + c * vy
    if k_b > 0.0:
        r = math.hypot(x, y)
        if r > clearance and r > 0.0:
            nx, ny = x / r, y / r
            fn = k_b * (r - clearance)
            vn = vx * nx + vy * ny
            tx, ty = vx - vn * nx, vy - vn * ny
            s = mu * fn / math.sqrt(tx * tx + ty * ty + V_REG * V_REG)
            fx += fn * nx + s * tx
            fy += fn * ny + s * ty
    return fx, fy


def break_indicator(x: float, y: float, k: float, break_load: float) -> float:
    """A stage's event indicator [N]: ``k |x| - break_load`` with ``k`` the stage's stiffness and ``break_load`` the
    load that breaks it (the break at its zero)."""
    return k * math.hypot(x, y) - break_load


_force = kernel_jit(support_force, inline="always")
_indicator = kernel_jit(break_indicator, inline="always")


@kernel_jit(inline="always")
def relative(u):
    """The supported point's displacement and velocity (x, y) against the structure's."""
    x, v, xs, vs = u.X, u.V, u.X_structure, u.V_structure
    return x[0] - xs[0], x[1] - xs[1], v[0] - vs[0], v[1] - vs[1]


@kernel_jit(inline="always")
def indicator_of(s, p, u):
    """(has, value): whether the fuse has an indicator in its present state, and its value: 1 for a stage broken
    and not yet located (``broken > reported``), the present stage's ``k_s |x| - L_(s+1)`` while one is left to
    break, none after the last."""
    n = int(s.broken[0])
    if s.broken[0] > s.reported[0]:
        return True, 1.0
    if n < p.loads.shape[0]:
        dx, dy, _, _ = relative(u)
        return True, _indicator(dx, dy, p.k[n], p.loads[n])
    return False, 0.0


@kernel_jit
def step(s, p, u, y, t, h):
    """The fuse over a step with the inputs of its end (module docstring): every stage whose load is reached breaks
    at the step's end, the force law of the stage after it; status EVENT when the indicator changed sign."""
    dx, dy, _, _ = relative(u)
    had = s.broken[0] > s.reported[0] or s.broken[0] < p.loads.shape[0]
    while s.broken[0] < p.loads.shape[0]:
        n = int(s.broken[0])
        if _indicator(dx, dy, p.k[n], p.loads[n]) < 0.0:
            break
        s.broken[0] += 1.0
    has, g = indicator_of(s, p, u)
    status = OK
    if has:
        if had and (g < 0.0) != (s.g[0] < 0.0):
            status = EVENT
        s.g[0] = g
    publish(s, p, u, y)
    return status


@kernel_jit(inline="always")
def publish(s, p, u, y):
    """The outputs of the present state: F_support, F_rotor = -F_support (axial 0), broken."""
    dx, dy, dvx, dvy = relative(u)
    fx, fy = _force(dx, dy, dvx, dvy, p.k[int(s.broken[0])], p.damping, p.k_b, p.clearance, p.mu)
    y.F_support[0] = fx
    y.F_support[1] = fy
    y.F_rotor[0] = -fx
    y.F_rotor[1] = -fy
    y.F_rotor[2] = 0.0
    y.broken[0] = s.broken[0]
