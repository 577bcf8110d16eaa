"""The rundown's response figure draws the settled response: a TM restart's transient (the rotor resumes the orbit
it was frozen on at a higher speed and rings down to the new one) is left out, so that the curve against speed
has no step at each restart of the windmilling."""
from __future__ import annotations

import numpy as np

from rotorcosim.cases.rundown.figures import settled


def test_a_restart_s_first_revolutions_are_left_out():
    # 60 rev/min: one revolution per second, two samples per revolution; coupled, held, coupled (4.5 revolutions),
    # held, coupled (1.5 revolutions)
    phase = np.array([0] * 10 + [1] * 10 + [0] * 10 + [1] * 4 + [0] * 4)
    t = 0.5 * np.arange(len(phase))
    w = np.full(len(phase), 60.0)
    keep = settled(t, w, phase, skip=3.0)
    assert keep[:10].all()                        # no held interval before it: all of it
    assert not keep[10:20].any() and not keep[30:34].any()    # held: never
    # after a hold: from 3 revolutions on (samples at 0, 0.5, ..., 4.5 revolutions)
    assert keep[20:30].tolist() == [False] * 6 + [True] * 4
    # shorter than skip + 1 revolutions: its last revolution (0.5 ... 1.5)
    assert keep[34:].tolist() == [False, True, True, True]


def test_revolutions_are_counted_at_the_stretch_s_speed():
    """Revolutions are the speed's integral: at 120 rev/min (2 per second) 3 revolutions pass in 1.5 s."""
    phase = np.array([1] * 2 + [0] * 8)
    t = 0.5 * np.arange(10)
    w = np.full(10, 120.0)
    keep = settled(t, w, phase, skip=3.0)
    assert keep[2:].tolist() == [False, False, False, True, True, True, True, True]
