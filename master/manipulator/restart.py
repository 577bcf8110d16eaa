"""A hand-back's restart: how the values the thermal networks hand back to the mechanics enter the next
thermo-mechanical interval after a thermal-only one (the thermal-only hold, hold.py, sets one per hand-back).

* The restart (TO -> TM): the hand-backs are the connections from a thermal component to a mechanical one (the
  thermal growths, the oil temperatures). Over a TO interval they moved while the mechanical state stayed frozen
  on the old ones; stepping them into the frozen mechanics at once is a sudden load (a growth of micrometres is an
  axial force step on a preloaded support) that rings the lightly damped modes it meets. In a monolithic run they
  change over seconds, so the mechanics follow them quasi-statically. The restart does the same on a short
  scale: each hand-back enters the next TM interval as its value at the end of the previous TM interval and goes
  over to its present (live) value along a half cosine over ``restart_cycles`` cycles (:class:`Restart`; the
  link adds its offset with master/core/links.add_restart, in both loops). A mode of frequency f then keeps
  about 1 / ((2 f T)^2 - 1) of the step's response (T the ramp length: 0.02 for f = 480 Hz over 7.5 ms).
  ``restart_cycles = 0``: a step.
"""
from __future__ import annotations

import numpy as np

from rotorcosim.master.core import links

#: cycles over which the hand-backs go from their pre-TO to their present values at a TM restart (Restart):
#: long against the mechanical modes they would ring, short against the TM intervals whose last ``hold_cycles``
#: cycles give the results and the hand-off windows
RESTART_CYCLES = 2.0


class Restart:
    """A hand-back's offset at a TM restart: ``delta`` (its value at the end of the previous TM interval minus its
    value at the restart) at t0, fading along a half cosine to nothing at t0 + length (links.add_restart, which
    both loops add to the link's value). A class, not a closure: checkpoints pickle the links."""

    def __init__(self, delta: np.ndarray, t0: float, length: float):
        self.delta, self.t0, self.length = np.array(delta, dtype=float), float(t0), float(length)

    def offset(self, t: float) -> np.ndarray:
        """The offset at time ``t`` [s] (in the hand-back's unit): ``delta`` before t0, 0 after t0 + length."""
        out = np.zeros_like(self.delta)
        links.add_restart(out, 0, self.delta, 0, self.delta.shape[0], t, self.t0, self.length)
        return out
