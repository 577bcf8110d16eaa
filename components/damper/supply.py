"""The loss of a squeeze film damper's oil supply on a condition: the journal's eccentricity ratio reaching a value.

The damper's ``oil_loss_eccentricity`` (e_loss, > 0; 0: never) is an event indicator (master/core/events.py):

    g = |X_journal - X_housing| / c - e_loss,

c the radial clearance. When g reaches zero the journal is within (1 - e_loss) c of the land: the end seals, the
feed holes and the film's pressure no longer hold the oil, and the supply is lost as at ``oil_loss_time`` (the film
goes, the journal runs on the land, wall.dry_land). The step in which g reaches zero loses the oil at its end (so a
damper run without the master's event location, an FMU in another tool, loses it at the communication point after
the condition was met); the master locates the zero within ``event_tolerance`` and hands it to the damper
(``update_discrete``), which marks it ``reported``: from then on, or once the oil is lost at ``oil_loss_time``, the
indicator is out. Only the upward crossing is an event (the oil once lost stays lost).
"""
from __future__ import annotations

import math

from ..kernels import EVENT, OK
from ..numba_internals import kernel_jit


@kernel_jit(inline="always")
def condition(lost, reported, g, e_loss, clearance, dx, dy):
    """The indicator g (module docstring) at the relative displacement (dx, dy) [m] into ``g[0]``; the oil lost
    (``lost[0]`` = 1) when g >= 0. Returns EVENT when g reached zero over the step (from below), else OK; nothing
    is evaluated without a condition (``e_loss`` <= 0) or once the loss is ``reported``."""
    if e_loss <= 0.0 or reported[0] != 0.0:
        return OK
    gi = math.hypot(dx, dy) / clearance - e_loss
    crossed = gi >= 0.0 and g[0] < 0.0
    g[0] = gi
    if gi >= 0.0:
        lost[0] = 1.0
    return EVENT if crossed else OK
