"""The damped critical speeds' search at many film temperatures (cases/blade_loss/response_peaks.py): the grid's
whirl from one solve per speed and a low-rank update for the films (FilmScan) against the direct solve of the
engine with those films at every speed (the independent reference: a dense solve of the whole system), and the
nearest peak refined alone (DampedPeaks.nearest) against every peak refined and the nearest picked."""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from threadpoolctl import threadpool_limits

from rotorcosim.cases.blade_loss import response_peaks as rp
from rotorcosim.cases.blade_loss.critical_speeds import linearised_supports
from rotorcosim.components.airframe.installed import installed_model

REF_RPM = 16000.0


@pytest.fixture(scope="module")
def engine():
    m = installed_model("")
    return m, linearised_supports(m, None)


@pytest.fixture(autouse=True)
def one_blas_thread():
    """As a run computes (master/core/threads.py): the engine's small solves gain nothing from threads."""
    with threadpool_limits(limits=1):
        yield


def _films(sup, scale0, scale5):
    out = copy.deepcopy(sup)
    out["h0"]["c_film"] *= scale0
    out["h5"]["c_film"] *= scale5
    return out


def test_film_update_equals_the_direct_solve_and_other_changes_are_refused(engine):
    m, sup = engine
    grid = rp.speed_grid(8500.0, 11500.0)
    scan = rp.FilmScan(m, sup, grid, REF_RPM)
    warm = _films(sup, 0.55, 0.6)        # the films' damping of oil some 10 C warmer
    got = scan.table(warm)
    want = rp.direct_table(grid, rp.Whirl(m, warm, REF_RPM))
    for b in want:
        assert np.max(np.abs(got[b] - want[b]) / want[b]) < 1e-9, b
    # a change of anything but the films' damping: not an update of the scan
    stiff = copy.deepcopy(sup)
    stiff["h0"]["k_spring"] *= 2.0
    assert scan.table(stiff) is None
    # the peaks it finds are the direct solve's, and the nearest one alone is refined to the same speed
    whirl = rp.Whirl(m, warm, REF_RPM)
    every = rp.DampedPeaks(grid, want, whirl).all()
    lazy = rp.DampedPeaks(grid, got, whirl)
    assert lazy.peaks == rp.DampedPeaks(grid, want, whirl).peaks and every["0"]
    for b, speeds in every.items():
        for rpm in (8600.0, 9000.0, 9800.0, 10500.0, 11400.0):
            nearest = min(speeds, key=lambda d: abs(math.log(rpm / d))) if speeds else None
            assert lazy.nearest(b, rpm) == nearest
