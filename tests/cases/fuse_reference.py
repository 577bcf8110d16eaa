"""An independent integration of the jeffcott_fuse check case (scipy's solve_ivp, DOP853 at tight tolerances, with
its own event location), written from the equations of a disk on a breaking support, not from the components:

    m x'' + c x' + k(s) x = F_u(t),   k = k_intact while intact, k_broken after the break,

the break (s: intact -> broken) at the first time the elastic force k_intact |x| reaches the break load, located by
solve_ivp's event function (root of the dense output to machine precision) and the integration restarted from
there on the soft path; with a second stage, the soft path breaks in the same way when k_broken |x| reaches the
second load, and the integration goes on at k_broken_2. The unbalance: a residual u_r from t = 0 and the blade loss u_b added at the same angle
from t_b, each pushing the disk with u (W^2 - i W') e^(i th) (tests/cases/jeffcott_reference.py); the speed W(t)
held at W0 until t_ramp, then linear to W1 at t_ramp + T. The start: the synchronous steady state of the intact
support under u_r, u_r W0^2 / (k_intact - m W0^2 + i c W0) e^(i W0 t)."""
from __future__ import annotations

import math

import numpy as np


def fuse_run(m, k_intact, c, break_load, k_broken, u_r, u_b, t_b, rpm0, rpm1, t_ramp, ramp, t_end, samples,
             break_load_2=None, k_broken_2=None):
    """(t, speed [rev/min], x, y, vx, vy, breaks): the disk's motion sampled at ``samples`` times over [0, t_end],
    and the break times [s] (one per stage broken; ``break_load_2``, ``k_broken_2``: a second stage)."""
    from scipy.integrate import solve_ivp   # at the first call, not when the suite is collected

    w0, w1 = rpm0 * math.pi / 30.0, rpm1 * math.pi / 30.0
    a = (w1 - w0) / ramp

    def speed(t):
        if t <= t_ramp:
            return w0, w0 * t, 0.0
        s = min(t, t_ramp + ramp) - t_ramp
        th = w0 * t_ramp + w0 * s + 0.5 * a * s * s + w1 * max(0.0, t - t_ramp - ramp)
        return (w0 + a * s, th, a) if t < t_ramp + ramp else (w1, th, 0.0)

    def rhs_of(k):
        def rhs(t, s):
            x, y, vx, vy = s
            w, th, dw = speed(t)
            u = u_r + (u_b if t >= t_b else 0.0)
            fx = u * (w * w * math.cos(th) + dw * math.sin(th))
            fy = u * (w * w * math.sin(th) - dw * math.cos(th))
            return [vx, vy, (fx - c * vx - k * x) / m, (fy - c * vy - k * y) / m]
        return rhs

    ks = [k_intact, k_broken] + ([] if break_load_2 is None else [k_broken_2])
    loads = [break_load] + ([] if break_load_2 is None else [break_load_2])

    def breaks_of(stage):
        def breaks(t, s):
            return ks[stage] * math.hypot(s[0], s[1]) - loads[stage]
        breaks.terminal, breaks.direction = True, 1.0
        return breaks

    z = u_r * w0 * w0 / (k_intact - m * w0 * w0 + 1j * c * w0)
    s0 = [z.real, z.imag, (1j * w0 * z).real, (1j * w0 * z).imag]
    t = np.linspace(0.0, t_end, samples)
    # steps of at most 0.1 ms (a tenth of the intact support's period): the event function is checked at each
    # step, and a crossing up and back within one long step would go unseen
    opts = dict(method="DOP853", rtol=1e-10, atol=1e-14, max_step=1e-4)
    # the piecewise forcing (the blade loss at t_b, the ramp's corners) integrated piece by piece
    cuts = sorted({0.0, t_b, t_ramp, t_ramp + ramp, t_end})
    cuts = [x for x in cuts if x <= t_end]
    out, stage, t_breaks, state = [], 0, [], s0
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        while True:
            live = stage < len(loads)
            sol = solve_ivp(rhs_of(ks[stage]), (lo, hi), state, events=breaks_of(stage) if live else None,
                            dense_output=True, **opts)
            end = hi
            if live and sol.t_events[0].size:
                # a break: the integration stopped there (terminal event); on from it on the next, softer path
                end = float(sol.t_events[0][0])
                t_breaks.append(end)
            sel = t[(t >= lo) & (t < end)] if end < hi else t[(t >= lo) & (t <= hi)]
            if sel.size:
                out.append(np.vstack([sel, sol.sol(sel)]))
            state = sol.y[:, -1]    # at the segment's end, or the break's (t_eval unused: the last step's end)
            if end < hi:
                stage, lo = stage + 1, end
                continue
            break
    data = np.hstack(out)
    _, idx = np.unique(data[0], return_index=True)
    data = data[:, idx]
    rpm = np.array([speed(x)[0] for x in data[0]]) * 30.0 / math.pi
    return data[0], rpm, data[1], data[2], data[3], data[4], t_breaks
