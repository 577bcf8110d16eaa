"""The installed engine's critical speeds (the paper's engine on the example pylon, engine_on_pylon.toml): which
mode the rundown's bearing #0 peak near 10 000 rev/min belongs to, and where the engine's second mode went.

On the ground the paper's engine has two forward critical speeds below its running speed, 8 500 and 10 200
rev/min, and bearing #0's unbalance response peaks twice (damped critical speeds 9 102 and 11 401 rev/min).
Installed, the list has 3 955 (the engine rocking on the pylon), 8 636 (an airframe mode the rotors take part in),
8 722 and then 17 005 rev/min, and bearing #0's response peaks once, at 10 052 rev/min. That peak is the first
rotor mode's (8 722), lifted by the films' damping, not the second's: with the films' damping scaled down the
peak returns to the undamped critical speed, as an almost undamped system's does (0.02 x: 8 721 rev/min), and it
moves up continuously with the damping (0.1 x 8 736, 0.4 x 8 897, 0.7 x 9 257, 1 x 10 052; a mode of damping ratio
0.31 there, whose response to an unbalance growing with the speed squared peaks above its natural frequency).
The second ground mode pair (10 066 backward, 10 200 forward) veers through the airframe's modes as the pylon
softens (an airframe stiffness scaled from 1e4 x down to 1 x): installed, its forward root is at 9 762 rev/min
with 3.6 % of its kinetic energy in the rotors' lateral motion and 33 % in the airframe, below the 5 % share that
makes a root a rotor's critical speed (components/rotor/critical.py), and bearing #5 alone shows it, a damped
peak at 9 773 rev/min of 0.011 mm (against bearing #0's 0.29 mm at 10 052).
"""
from __future__ import annotations

import copy

import pytest

from rotorcosim.cases.blade_loss import response_peaks
from rotorcosim.cases.blade_loss.critical_speeds import linearised_supports
from rotorcosim.components.airframe.installed import installed_model
from rotorcosim.components.rotor import critical
from rotorcosim.components.rotor.model import DEFAULT_FILE

PYLON = str(DEFAULT_FILE.with_name("engine_on_pylon.toml"))


def _peaks_0(m, sup, film_scale: float) -> list[float]:
    """Bearing #0's damped critical speeds [rev/min] over 7 000-13 000 with the films' damping scaled."""
    sup = copy.deepcopy(sup)
    for s in sup.values():
        s["c_film"] *= film_scale
    return response_peaks.damped_critical_speeds(m, sup, 7000.0, 13000.0, 16000.0)["0"]


@pytest.mark.slow   # 41 s of CPU (the installed engine's eigen-solves and response scans)
def test_bearing0_peak_near_10000_is_the_first_rotor_mode_not_the_second():
    m = installed_model(PYLON)
    sup = linearised_supports(m, None)
    fwd = critical.synchronous_critical_speeds(m, sup, n=6, max_rpm=20000.0)["forward_synchronous_rpm"]
    first = min(f for f in fwd if f > 8700.0)
    assert first == pytest.approx(8722.3, abs=1.0)
    assert not any(9000.0 < f < 17000.0 for f in fwd)          # the second ground mode is not listed
    # bearing #0's one peak, and with the films' damping scaled down it goes back to the first mode's undamped
    # critical speed
    track = [_peaks_0(m, sup, s) for s in (0.02, 0.1, 0.4, 1.0)]
    assert all(len(p) == 1 for p in track)
    assert track[-1][0] == pytest.approx(10052.0, abs=2.0)
    assert track[0][0] == pytest.approx(first, rel=2e-3)
    assert track[0][0] < track[1][0] < track[2][0] < track[3][0]
    # the second ground mode installed: one forward root above the first rotor mode, under the 5 % share
    low = critical.synchronous_critical_speeds(m, sup, n=12, max_rpm=12000.0, min_share=0.03)
    extra = [f for f in low["forward_synchronous_rpm"] if f not in fwd and f > 9000.0]
    assert len(extra) == 1 and extra[0] == pytest.approx(9762.0, abs=2.0)
