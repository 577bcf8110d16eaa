"""The airframe's step (components/kernels.py contract): its modes under the engine's motion at the mounts.

With q the modal coordinates of the reduced airframe (mass-normalised, modal.py), B the rows of the interface
points' shapes along the mount springs' axes (one row per spring s: Phi_I(s)[:, dir_s], plus
Phi_I(s)[:, 3:6] (r_s x e_s) for a spring ending at r_s off its point), K_s, C_s the springs'
stiffness and damping (diagonal) and x_e, v_e the engine's displacement and velocity at the springs (the rotor's
``X_mount_NAME``, ``V_mount_NAME``), the springs' forces on the airframe give

    q'' + (D + B^T C_s B) q' + (W^2 + B^T K_s B) q = B^T (K_s x_e + C_s v_e),     D = diag(2 zeta_j w_j),
                                                                                  W = diag(w_j),

stepped by Newmark's average acceleration (beta 1/4, gamma 1/2: unconditionally stable, the mount stiffness
inside the implicit step) with x_e, v_e the inputs of the step (the engine's state at its end, Gauss-Seidel after
the rotor), s = [q, q', q''], u = [x_e, v_e]: the new displacements are one product with the displacement rows of
the step's linear map (newmark.step_operator: q_1 = T_q s + B_q u, T_q and B_q the first rows of T and B B_u), the
velocities and accelerations follow from them (Bathe, Finite Element Procedures, 9.2.4):

    q''_1 = 4 / h^2 (q_1 - q) - 4 / h q' - q'',        q'_1 = q' + h / 2 (q'' + q''_1),

a third of the work of the whole map (the same step, to rounding). Every output is linear in [s_new, u]:

* ``F_engine_NAME`` (per spring): the airframe's motion's force on the engine, k_s B_s q^ + c_s B_s q^' (the
  engine model holds -k_s x_e - c_s v_e itself: components/rotor/mounts.py) at the end of the COMING step,
  s^ = T s_new + B_u u (the airframe stepped once more with the engine's motion held). The rotor steps first and
  holds its inputs over its step, which Newmark's equilibrium takes as the forces at the step's end: handed the
  airframe's force of the step's start instead, it would see the airframe one step late, a first-order lag that
  on the stiff mount springs shifts the interface loads by 1-6 % at 5 us steps (halved at 2.5 us). s^ lacks
  only the response to the engine's motion over the coming step, of second order in the step, and the loads
  match the installed linear engine's within 0.3 % (tests/cases/test_installed_linear.py);
* ``F_NAME`` / ``M_NAME``: the mount's load on the airframe, sum over its springs along their axes of
  f_s = k_s (x_e,s - B_s q) + c_s (v_e,s - B_s q'), and r_s x f_s e_s in ``M_NAME`` for a spring off its point;
* ``a_POINT``: a response point's acceleration Phi_P^T q'' (x y z).

So one product y = O [s_new, u] gives them all (O made per step size by component.py).
"""
from __future__ import annotations

import math
from collections import namedtuple

from ..numba_internals import kernel_jit

AirframeState = namedtuple("AirframeState", "s")
#: TB = [T_q B_q] (Fortran order: the displacement rows of the step's map over [s, u]), O the output rows over
#: [s_new, u], nm = [4 / h^2, 4 / h, h / 2] of the step they were made for; w: the work vector [s, u] then
#: [s_new, u]; in_off / out_off: where input port j enters u, where output port j starts in the output vector y_all
AirframeParams = namedtuple("AirframeParams", "TB O nm w y_all in_off out_off")


@kernel_jit
def tm_step(s, p, u, y, t, h):
    """One step from t to t + h; status 2: a non-finite input."""
    st = s.s
    w = p.w
    n3 = st.shape[0]
    acc = 0.0
    for j in range(len(u)):          # a homogeneous tuple of contiguous arrays (component.Airframe.kernel_io)
        k = n3 + p.in_off[j]
        a = u[j]
        for i in range(a.shape[0]):
            w[k + i] = a[i]
            acc += a[i] * a[i]
    if not math.isfinite(acc):
        return 2
    for i in range(n3):
        w[i] = st[i]
    TB = p.TB
    n = TB.shape[0]
    for i in range(n):
        st[i] = 0.0
    for j in range(w.shape[0]):
        c = w[j]
        for i in range(n):
            st[i] += TB[i, j] * c
    c0, c1, hh = p.nm[0], p.nm[1], p.nm[2]
    for i in range(n):
        a1 = c0 * (st[i] - w[i]) - c1 * w[n + i] - w[2 * n + i]
        st[2 * n + i] = a1
        st[n + i] = w[n + i] + hh * (w[2 * n + i] + a1)
    for i in range(n3):
        w[i] = st[i]
    O = p.O
    ya = p.y_all
    for i in range(ya.shape[0]):
        ya[i] = 0.0
    for j in range(w.shape[0]):
        c = w[j]
        for i in range(ya.shape[0]):
            ya[i] += O[i, j] * c
    for j in range(len(y)):
        k = p.out_off[j]
        a = y[j]
        for i in range(a.shape[0]):
            a[i] = ya[k + i]
    return 0
