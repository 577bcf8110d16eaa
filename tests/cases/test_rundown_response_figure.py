"""The rundown's response figure draws the settled response: a TM restart's transient (the rotor resumes the orbit
it was frozen on at a higher speed and rings down to the new one) is left out, so that the curve against speed
has no step at each restart of the windmilling."""
from __future__ import annotations

import numpy as np
import pytest

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
    # shorter than skip: its last revolution (after 0.5 of its 1.5)
    assert keep[34:].tolist() == [False, False, True, True]


def test_revolutions_are_counted_at_the_stretch_s_speed():
    """Revolutions are the speed's integral: at 120 rev/min (2 per second) 3 revolutions pass in 1.5 s."""
    phase = np.array([1] * 2 + [0] * 8)
    t = 0.5 * np.arange(10)
    w = np.full(10, 120.0)
    keep = settled(t, w, phase, skip=3.0)
    assert keep[2:].tolist() == [False, False, False, True, True, True, True, True]


def _track_after_a_hold(seconds: float, skip: float = 3.0):
    """A response track of one spool at 1 revolution per second: a held interval, then a TM interval of
    ``seconds`` from t = 1 s (steps of 1 ms)."""
    from types import SimpleNamespace

    from rotorcosim.cases.rundown.results import RundownTrack
    from rotorcosim.components.contract import COUPLED, HELD

    tr = RundownTrack(["sp"], skip=skip)
    tr.cols = []                       # no locations: time and speed columns only
    sim = SimpleNamespace(t=0.0)
    tr.interval_start(sim, HELD, 0.1)
    tr.interval_end(sim, None)
    sim.t = 1.0
    tr.interval_start(sim, COUPLED, 1e-3)
    n = int(round(seconds / 1e-3))
    ts = 1.0 + 1e-3 * np.arange(1, n + 1)
    for part in np.array_split(np.arange(n), 7):            # in chunks, as the compiled loop hands them over
        tr.step_block(sim, part, ts[part], {"sp.Omega": np.full((len(part), 1), 2.0 * np.pi)})
    tr.interval_end(sim, None)
    return tr.table()


def test_the_response_track_leaves_out_a_restart_s_first_revolutions():
    """The summary's crossings read the track: after a held interval its first ``skip`` revolutions (the rotor
    ringing down from the orbit it was frozen on) are not in it; an interval that ends before keeps its last
    revolution."""
    t = _track_after_a_hold(4.0)[:, 0]
    assert t.min() > 4.0 - 1e-9 and t.max() == pytest.approx(5.0)       # from 3 revolutions after the restart
    t = _track_after_a_hold(2.0)[:, 0]
    assert t.min() > 2.0 - 1e-9 and t.max() == pytest.approx(3.0)       # 2 revolutions: the last one
    t = _track_after_a_hold(2.0, skip=0.0)[:, 0]
    assert t.min() < 1.01                                                 # no skip: all of it
