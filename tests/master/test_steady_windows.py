"""SteadyWindows (master/observer/steady_windows.py): the compiled loop's blocks (step_block, copied by slices) keep exactly the
window the generic loop's step() calls keep, whatever the block boundaries, the stride, the window's length against
the blocks and the interval's, and whether the interval's length is known (the rows before the window skipped)."""
from types import SimpleNamespace

import numpy as np
import pytest

from rotorcosim.master.observer.steady_windows import SteadyWindows


class _Comp:
    def __init__(self, y):
        self.y = y


def _sim(steps_known, nsteps):
    comps = {"a": _Comp({"x": np.zeros(2)}), "b": _Comp({"p": np.zeros(1)})}
    return SimpleNamespace(system=SimpleNamespace(components=comps), phase="TM",
                           interval_steps=nsteps if steps_known else None,
                           value=lambda ref: comps[ref.split(".")[0]].y[ref.split(".")[1]])


@pytest.mark.parametrize("stride_step", [None, 3e-3])
@pytest.mark.parametrize("steps_known", [True, False])
@pytest.mark.parametrize("nsteps, cycles", [(700, 0.05), (700, 0.3), (40, 0.3), (1000, 0.999)])
def test_blocks_keep_the_generic_window(stride_step, steps_known, nsteps, cycles):
    h = 1e-3
    rng = np.random.default_rng(nsteps)
    x, p = rng.normal(size=(nsteps + 1, 2)), rng.normal(size=(nsteps + 1, 1))
    out = []
    for blocks in (False, True):
        sim = _sim(steps_known, nsteps)
        obs = SteadyWindows(["a.x", "b.p"], cycle=1.0, cycles=cycles, sample_step=stride_step)
        for interval in range(2):  # a second interval: the ring starts anew
            obs.interval_start(sim, "TM", h)
            t0 = interval * 10.0
            k = 0
            while k < nsteps:
                if blocks:
                    k1 = min(nsteps, k + int(rng.integers(1, 300)))
                    ks = np.arange(k + 1, k1 + 1)
                    obs.step_block(sim, ks, t0 + ks * h, {"a.x": x[k + 1:k1 + 1], "b.p": p[k + 1:k1 + 1]})
                    k = k1
                else:
                    k += 1
                    sim.system.components["a"].y["x"] = x[k].copy()
                    sim.system.components["b"].y["p"] = p[k].copy()
                    if k % obs.stride == 0:
                        obs.step(sim, t0 + k * h)
            obs.interval_end(sim, SimpleNamespace(t_start=t0, t_end=t0 + nsteps * h))
        out.append(obs.windows)
    generic, blocked = out
    assert len(generic) == len(blocked) == 2
    for g, b in zip(generic, blocked):
        assert set(g) == set(b)
        assert len(g["t"]) == min(nsteps // (3 if stride_step else 1), int(np.ceil(cycles / ((3 if stride_step else 1) * h))) + 1)
        for key in g:
            assert np.array_equal(g[key], b[key]), key


def test_keep_holds_the_last_windows_only():
    """``keep``: the last windows, the same as those of an observer that keeps every one (a run of hours would
    otherwise hold hundreds of them in memory and in every checkpoint)."""
    h, nsteps = 1e-3, 50
    every, last = SteadyWindows(["a.x"], cycle=1.0, cycles=0.02), SteadyWindows(["a.x"], cycle=1.0, cycles=0.02,
                                                                                  keep=2)
    sim = _sim(True, nsteps)
    for interval in range(5):
        for obs in (every, last):
            obs.interval_start(sim, "TM", h)
            for k in range(1, nsteps + 1):
                sim.system.components["a"].y["x"] = np.array([interval, k], dtype=float)
                obs.step(sim, interval * 10.0 + k * h)
            obs.interval_end(sim, SimpleNamespace(t_start=interval * 10.0, t_end=interval * 10.0 + nsteps * h))
    assert len(every.windows) == 5 and len(last.windows) == 2
    for g, b in zip(every.windows[-2:], last.windows):
        assert g.keys() == b.keys() and all(np.array_equal(g[k], b[k]) for k in g)
    assert last.windows[-1]["a.x"][-1].tolist() == [4.0, float(nsteps)]
