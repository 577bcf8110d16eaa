"""The blade-loss figures (cases/blade_loss/figures.py) on synthetic series: which panels, which titles, which axes."""
from pathlib import Path

import numpy as np
import pytest

import rotorcosim
from rotorcosim.cases.blade_loss.figures import _absolute_time, _panels, figures, is_paper_case, tm_blocks, to_spans
from rotorcosim.master.run.outputs import FIGURE_DPI

W = 16000 * 2 * np.pi / 60  # rad/s


def synthetic(two_tm: bool) -> dict:
    """TM 0-0.25 s (record step 5e-5 s), then with ``two_tm`` a TO stretch to 119.9 s and TM 119.9-120 s."""
    parts = [(np.arange(0, 0.25 + 1e-12, 5e-5), 0)]
    if two_tm:
        parts += [(np.linspace(0.35, 119.8, 40), 1), (np.arange(119.9, 120 + 1e-12, 5e-5), 0)]
    t = np.concatenate([p[0] for p in parts])
    phase = np.concatenate([np.full(len(p[0]), p[1], dtype=np.int8) for p in parts])
    d = {"time": t, "phase": phase}
    for k, r in ((0, 1.5e-4), (5, 7e-6)):
        d[f"rotor.X_brg{k}"] = np.column_stack([r * np.cos(W * t), r * np.sin(W * t), 0 * t])
        d[f"rotor.X_rub{k}"] = d[f"rotor.X_brg{k}"][:, :2]
        d[f"rotor.X_housing{k}"] = 0 * d[f"rotor.X_rub{k}"]
        d[f"damper{k}.F_journal"] = np.column_stack([1e3 * np.cos(W * t), 1e3 * np.sin(W * t)])
        d[f"bearing{k}.sigma_max"] = np.column_stack([1.7e9 + 0 * t, 1.6e9 + 0 * t])
        d[f"thermal{k}.T_nodes"] = 303.15 + np.outer(t, np.ones(9))
    return d


def test_tm_blocks_and_to_spans():
    d = synthetic(True)
    blocks = tm_blocks(d["phase"])
    assert len(blocks) == 2 and d["time"][blocks[1][0]] == pytest.approx(119.9)
    (a, b), = to_spans(d["time"], d["phase"])
    assert a == pytest.approx(0.25) and b == pytest.approx(119.8)


def test_one_tm_interval_gets_one_panel_not_the_same_data_twice():
    assert [title for _, title in _panels([(0, 10)])] == ["thermo-mechanical interval"]
    assert [title[:3] for _, title in _panels([(0, 10), (20, 30)])] == ["(a)", "(b)"]


def test_time_axis_is_absolute_without_offset():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([119.9, 119.95, 120.0], [0, 1, 0])
    _absolute_time(ax)
    fig.canvas.draw()
    fmt = ax.xaxis.get_major_formatter()
    assert fmt.get_offset() == ""
    labels = [t.get_text() for t in ax.get_xticklabels() if t.get_text()]
    assert any(lab.startswith("119.9") for lab in labels), labels
    plt.close(fig)


@pytest.mark.parametrize("two_tm, width", [(False, 2 * 5.2), (True, 3 * 5.2)])
def test_figures_are_written_with_one_or_two_time_panels(tmp_path, two_tm, width):
    import matplotlib.pyplot as plt

    sc = rotorcosim.load_scenario("blade_loss_2850")
    names = figures(sc, synthetic(two_tm), tmp_path, 2850.0, 16000.0)
    assert names == ["fig09_response_bearing0.png", "fig10_response_bearing5.png", "fig11_transmissibility.png",
                     "fig12_contact_stress.png", "fig13_temperatures.png", "fig14_temperatures.png"]
    img = plt.imread(tmp_path / names[0])
    assert img.shape[1] == pytest.approx(width * FIGURE_DPI, abs=2)  # Fig. 9: time panels + the orbit


def test_paper_figure_numbers_only_on_the_papers_cases(tmp_path):
    sc = rotorcosim.load_scenario("blade_loss_2850")
    assert is_paper_case(sc, 2850.0)
    assert not is_paper_case(sc, 3000.0)  # not a Table 5 level
    assert not is_paper_case(sc.set({"rotor.F_unbalance": 2850.0}), 2850.0)  # changed through the API
    assert not is_paper_case(sc.swap("damper0", "damper.fe"), 2850.0)
    example = rotorcosim.load_scenario(Path(__file__).resolve().parents[2] / "docs/examples/linear_damper/linear_damper.toml")
    assert not is_paper_case(example, 2850.0)


def test_envelope_keeps_each_buckets_extremes_in_time_order():
    from rotorcosim.cases.blade_loss.figures import envelope

    t = np.linspace(0.0, 120.0, 1_200_001)  # a 2-minute monolithic run at the 1e-4 s record step
    y = np.sin(W * t) * (1 + t / 120)
    te, ye = envelope(t, y, 4000)
    assert len(te) <= 4000 and np.all(np.diff(te) >= 0)
    assert ye.max() == y.max() and ye.min() == y.min()
    # every sample lies within the envelope of its bucket: max of |y| per 1 % of the run is kept
    for part in np.array_split(np.arange(len(t)), 100):
        inside = (te >= t[part[0]]) & (te <= t[part[-1]])
        assert ye[inside].max() >= y[part].max() - 1e-3 and ye[inside].min() <= y[part].min() + 1e-3
    short = np.arange(10.0)
    assert envelope(short, short, 4000)[0] is short  # short series drawn as they are


def test_figures_drawn_in_worker_processes_equal_those_drawn_here(tmp_path, monkeypatch):
    """The pool's workers (fresh interpreters: python -m rotorcosim.master.run.figure_worker) draw from the HDF5
    file; the same series drawn in this process gives the same PNG bytes. The pool is made usable whatever the
    machine (on one core a run would not start it, but the workers must still draw the same figures)."""
    import h5py

    from rotorcosim.cases.blade_loss import figures as fb
    from rotorcosim.master.run import figure_pool
    from rotorcosim.master.run.figure_pool import FigurePool

    monkeypatch.setattr(figure_pool, "_cores", lambda: 2)
    monkeypatch.delenv("ROTORCOSIM_FIGURE_WORKER", raising=False)
    from rotorcosim.master.observer.series import SeriesFile

    d = synthetic(True)
    path = tmp_path / "timeseries.h5"
    with h5py.File(path, "w") as f:
        for k, v in d.items():
            f[k] = v
    sc = rotorcosim.load_scenario("blade_loss_2850")
    ctx = fb.context(sc, 2850.0, 16000.0)
    (tmp_path / "here").mkdir()
    (tmp_path / "pool").mkdir()
    here = fb.figures(sc, SeriesFile(path), tmp_path / "here", 2850.0, 16000.0)
    pool = FigurePool()
    try:
        assert pool.usable
        drawn = pool.draw(fb, fb.JOBS, path, tmp_path / "pool", ctx)
    finally:
        pool.close()
    assert pool.by_workers == sorted(fb.JOBS)  # the workers drew them all: no fallback to this process
    assert drawn == here and len(here) == 6
    for name in here:
        assert (tmp_path / "pool" / name).read_bytes() == (tmp_path / "here" / name).read_bytes(), name
    assert not list((tmp_path / "pool").glob("*.part"))
