"""The blade-loss figures of a short real run (cases/blade_loss/figures.py), checked as a reviewer reads them.

A staggered run of ``blade_loss_5700`` (the paper's first rubbing level: its Fig. 9 orbit touches the ring) cut to
48.15 s of the paper's timeline (three thermo-mechanical intervals, two thermal-only ones) with ``--dpi 160``, run
through the command line. Each figure is drawn again from the run's time series, kept open, and measured with
matplotlib's own text extents: no two texts overlap (tick labels, axis labels, titles, the legend), every text is
inside the figure, no legend covers a panel, every interval of the run's timeline (summary.json) is shaded in the
whole-run figures, the transmissibility (a ratio) is drawn from zero, and the orbit is the rotor's motion
relative to the housing at the ring against the clearance circle.
"""
import json
from itertools import combinations

import numpy as np
import pytest

import rotorcosim
from rotorcosim.cases.blade_loss import figures as fb
from rotorcosim.master.cli import main
from rotorcosim.master.observer.series import SeriesFile

DPI = 160
DURATION = 48.15  # the paper's timeline cut after its third TM interval: TM 0.25, TO 23.85, TM 0.1, TO 23.85, TM 0.1


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("fig5700") / "run"
    assert main(["run", "blade_loss_5700", "--duration", str(DURATION), "--dpi", str(DPI), "--quiet",
                 "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    sc = rotorcosim.load_scenario("blade_loss_5700")
    ctx = fb.context(sc, 5700.0, 16000.0, DPI)
    figs, names = [], []
    redrawn = out / "redrawn"
    redrawn.mkdir()
    data = SeriesFile(out / "timeseries.h5")
    for job in fb.JOBS:
        names += fb.draw(job, data, redrawn, ctx, keep=figs)
    for f in figs:  # measured in the pixels of the files written
        f.set_dpi(DPI)
    yield {"out": out, "summary": summary, "figs": dict(zip(names, figs)), "data": data}
    import matplotlib.pyplot as plt

    for f in figs:
        plt.close(f)


def _texts(fig):
    """Every visible, non-empty text of the figure with its window extent, and the legends' extents."""
    fig.canvas.draw()  # laid out at the figure's dpi, as fig.bbox is (savefig's renderer may be another's)
    r = fig.canvas.get_renderer()
    out = []
    for ax in fig.axes:
        for axis, along in ((ax.xaxis, 0), (ax.yaxis, 1)):
            lo, hi = sorted(axis.get_view_interval())
            for lab in axis.get_ticklabels():
                if lab.get_visible() and lab.get_text() and lo - 1e-12 <= lab.get_position()[along] <= hi + 1e-12:
                    out.append((f"{ax.get_title()!r} tick {lab.get_text()!r}", lab.get_window_extent(r)))
            if axis.label.get_text():
                out.append((f"{ax.get_title()!r} label {axis.label.get_text()!r}", axis.label.get_window_extent(r)))
            off = axis.get_offset_text()
            if off.get_visible() and off.get_text():
                out.append((f"{ax.get_title()!r} offset", off.get_window_extent(r)))
        if ax.get_title():
            out.append((f"title {ax.get_title()!r}", ax.title.get_window_extent(r)))
    if fig._suptitle is not None:
        out.append(("suptitle", fig._suptitle.get_window_extent(r)))
    for leg in fig.legends:
        out.append(("legend", leg.get_window_extent(r)))
    return out


def _overlap(a, b) -> float:
    """Area [px^2] the two boxes share."""
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return max(w, 0.0) * max(h, 0.0)


def test_the_run_wrote_every_figure_at_the_dpi_asked(run):
    import matplotlib.pyplot as plt

    assert sorted(run["summary"]["figures"]) == sorted(run["figs"])
    for name, fig in run["figs"].items():
        img = plt.imread(run["out"] / name)  # the run's own file
        w, h = fig.get_size_inches()
        assert img.shape[:2] == (round(h * DPI), round(w * DPI)), name


@pytest.mark.parametrize("name", [f"fig{n}" for n in ("09", "10", "11", "12", "13", "14")])
def test_no_text_overlaps_another_and_every_text_is_inside_the_figure(run, name):
    (fname, fig), = [(n, f) for n, f in run["figs"].items() if n.startswith(name)]
    texts = _texts(fig)
    assert sum(1 for what, _ in texts if " tick " in what) >= 4 * len(fig.axes)  # the ticks were found
    frame = fig.bbox
    for what, box in texts:
        assert box.x0 >= frame.x0 - 0.5 and box.x1 <= frame.x1 + 0.5 and box.y0 >= frame.y0 - 0.5 \
            and box.y1 <= frame.y1 + 0.5, f"{fname}: {what} runs past the figure"
    clashes = [(a, b, round(_overlap(ba, bb), 1)) for (a, ba), (b, bb) in combinations(texts, 2)
               if _overlap(ba, bb) > 0.5]
    assert not clashes, f"{fname}: overlapping texts {clashes[:5]}"
    r = fig.canvas.get_renderer()
    for leg in fig.legends + [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]:
        for ax in fig.axes:
            assert _overlap(leg.get_window_extent(r), ax.get_window_extent(r)) == 0, f"{fname}: a legend covers a panel"


@pytest.mark.parametrize("name", ["fig13_temperatures.png", "fig14_temperatures.png"])
def test_every_interval_of_the_timeline_is_shaded_and_visible(run, name):
    timeline = run["summary"]["timeline"]
    assert [u["phase"] for u in timeline] == ["TM", "TO", "TM", "TO", "TM"]
    fig = run["figs"][name]
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    for ax in fig.axes:
        spans = sorted((p for p in ax.patches if (p.get_gid() or "").startswith("span-")),
                       key=lambda p: p.get_window_extent(r).x0)
        assert [p.get_gid()[5:] for p in spans] == [u["phase"] for u in timeline]
        lo, hi = ax.get_xlim()
        axes_box = ax.get_window_extent(r)
        for p, u in zip(spans, timeline):
            box = p.get_window_extent(r)
            assert box.width >= 2.0, f"{name}: the {u['phase']} interval at {u['t_start']} s is {box.width:.2f} px wide"
            # drawn where the interval is (its middle inside the patch) and inside the panel
            mid = ax.transData.transform((0.5 * (u["t_start"] + u["t_end"]), 0))[0]
            assert box.x0 - 1 <= mid <= box.x1 + 1
            assert box.x0 >= axes_box.x0 + 1 and box.x1 <= axes_box.x1 - 1


def test_transmissibility_is_drawn_from_zero(run):
    fig = run["figs"]["fig11_transmissibility.png"]
    for ax in fig.axes:
        lo, hi = ax.get_ylim()
        ymax = max(np.nanmax(line.get_ydata()) for line in ax.get_lines())
        assert lo == 0.0 and ymax <= hi <= 1.2 * ymax


def test_orbit_is_relative_to_the_housing_against_the_ring(run):
    """Fig. 9(c) at 5700 N: the line drawn is X_rub0 - X_housing0 over the last 5 rotor cycles (recomputed here
    from the time series), and the clearance circle of 0.508 mm is drawn beside it."""
    d = run["data"]
    fig = run["figs"]["fig09_response_bearing0.png"]
    orbit_ax = fig.axes[-1]
    lines = {line.get_label(): line for line in orbit_ax.get_lines()}
    rel = lines["rotor at the rub ring, relative to the housing"]
    t = np.asarray(d["time"])
    n = len(rel.get_xdata())
    expect = 1e3 * (np.asarray(d["rotor.X_rub0"])[-n:, :2] - np.asarray(d["rotor.X_housing0"])[-n:, :2])
    assert t[-n] == pytest.approx(t[-1] - 5 * 60 / 16000, abs=2 * (t[1] - t[0]))
    np.testing.assert_allclose(rel.get_xdata(), expect[:, 0])
    np.testing.assert_allclose(rel.get_ydata(), expect[:, 1])
    circle = lines["rub-ring clearance 0.508 mm"]
    assert np.hypot(circle.get_xdata(), circle.get_ydata()) == pytest.approx(0.508)


@pytest.mark.parametrize("dpi", ["5", "1e9", "nan"])
def test_a_dpi_no_figure_can_be_written_at_is_refused_before_the_run(tmp_path, capsys, dpi):
    out = tmp_path / "run"
    assert main(["run", "toy_thermomechanical", "--dpi", dpi, "--duration", "0.01", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--dpi must be a number of dots per inch from 50 to 1200" in err[0]
    assert not out.exists()
