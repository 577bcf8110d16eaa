"""An independent integration of the Jeffcott rotor's equations through a prescribed speed ramp (scipy's
solve_ivp, RK45 at tight tolerances), written from the textbook equations, not from the rotor component:

    m x'' + c x' + k x = u (W^2 cos th + W' sin th),   m y'' + c y' + k y = u (W^2 sin th - W' cos th)

with W(t) = W0 + a t, th(t) = W0 t + a t^2 / 2: the unbalance u = m_u e at the angle th, whose position
e e^(i th) accelerates at e (i th'' - th'^2) e^(i th), pushes the shaft with u (W^2 - i W') e^(i th) (Genta, Dynamics
of Rotating Systems, sec. 4.2): its tangential part u W' is 90 deg behind the radial one when W' > 0 (a run-up),
ahead of it in a rundown. The run starts on the synchronous steady state at W0:
x + i y = u W0^2 / (k - m W0^2 + i c W0) e^(i W0 t)."""
from __future__ import annotations

import math

import numpy as np


def rundown(m, k, zeta, u, rpm0, rpm1, duration, samples=200_001):
    """(t, speed [rev/min], orbit radius [m]) of the Jeffcott rotor along the linear ramp rpm0 -> rpm1 (a rundown or
    a run-up)."""
    c = 2.0 * zeta * math.sqrt(k * m)
    w0, w1 = rpm0 * math.pi / 30.0, rpm1 * math.pi / 30.0
    a = (w1 - w0) / duration

    def rhs(t, s):
        x, y, vx, vy = s
        w = w0 + a * t
        th = w0 * t + 0.5 * a * t * t
        fx = u * (w * w * math.cos(th) + a * math.sin(th))
        fy = u * (w * w * math.sin(th) - a * math.cos(th))
        return [vx, vy, (fx - c * vx - k * x) / m, (fy - c * vy - k * y) / m]

    z = u * w0 * w0 / (k - m * w0 * w0 + 1j * c * w0)
    s0 = [z.real, z.imag, (1j * w0 * z).real, (1j * w0 * z).imag]
    t = np.linspace(0.0, duration, samples)
    from scipy.integrate import solve_ivp   # at the first call, not when the suite is collected

    sol = solve_ivp(rhs, (0.0, duration), s0, t_eval=t, method="DOP853", rtol=1e-10, atol=1e-14)
    return t, (w0 + a * t) * 30.0 / math.pi, np.hypot(sol.y[0], sol.y[1])
