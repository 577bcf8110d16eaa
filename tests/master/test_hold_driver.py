"""The hold's group driver (master/hold.py _Driver): a hand-off whose cycle means follow the temperature of
ANOTHER producer of the same thermal component's hand-offs (the bearing's drag following the SFD oil through the
orbit) gets that temperature, with its ln-slope, as the driver of its TO law."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

from rotorcosim.master.hold import DRIVER_MIN_SPREAD_K, HandOff, _Driver


class _Var(SimpleNamespace):
    pass


def _handoff(name, port, unit="K"):
    src = SimpleNamespace(u={port: np.array([300.0])},
                          variable=lambda p, unit=unit: _Var(size=1, unit=unit, type="Real"))
    con = SimpleNamespace(src_component=name, dst_component="th", src=f"{name}.P", dst="th.P")
    return HandOff(SimpleNamespace(src=src, con=con, sport="P"), "mean", [port])


def _record(ho, temps, means):
    ho.cycles = [(np.array([t]), m) for t, m in zip(temps, means)]
    ho.history.append(ho.cycles)


def _group(t_a, t_b, slope=-0.02):
    a, b = _handoff("a", "Ta"), _handoff("b", "Tb")
    y_a = 100.0 * np.exp(slope * (t_b - 300.0))     # a's power follows b's temperature
    _record(a, t_a, y_a)
    _record(b, t_b, 50.0 + 0.0 * t_b)
    return a, b


def test_driver_is_the_group_temperature_that_tracks_the_means():
    n = 40
    rng = np.random.default_rng(1)
    t_a = 300.0 + 2.0 * rng.random(n)               # a's own input moves (2 K) but does not explain its means
    t_b = np.linspace(300.0, 310.0, n)
    a, b = _group(t_a, t_b)
    d = _Driver.choose(a, [a, b], cycles=5)
    assert d is not None and d.owner is b and d.port == "Tb"
    assert d.b == pytest.approx(-0.02, rel=1e-9)
    assert d.w == pytest.approx(np.mean(t_b[-5:]))
    b.link.src.u["Tb"] = np.array([d.w + 30.0])        # the TO interval warms b's input by 30 K
    assert d.factor() == pytest.approx(math.exp(-0.6))


def test_no_driver_when_no_group_temperature_moves():
    n = 40
    t = 300.0 + 0.5 * DRIVER_MIN_SPREAD_K * np.linspace(0.0, 1.0, n)
    a, b = _group(t, t)
    assert _Driver.choose(a, [a, b], cycles=5) is None


def test_only_temperatures_drive():
    n = 40
    a, b = _handoff("a", "Ta"), _handoff("b", "eps", unit="m")
    _record(a, np.full(n, 300.0), 100.0 * np.exp(np.linspace(0.0, 0.3, n)))
    _record(b, np.linspace(0.0, 5.0, n), np.full(n, 1.0))   # moves, but is a length
    assert _Driver.choose(a, [a, b], cycles=5) is None
