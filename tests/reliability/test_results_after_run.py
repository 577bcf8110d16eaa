"""A failure after the steps (the case's results, its figures) ends the run as "failed", like a diverged run:
the time series is kept, summary.json says why, no figure of the failed step is left (not a partial one, not
some of the set), one line says which step failed, and the last line lists the files the run did write."""
import json

import h5py
import pytest

from rotorcosim.cases.blade_loss import figures as blade_figures
from rotorcosim.cases.blade_loss import results as blade_results
from rotorcosim.master.cli import main

RUN = ["run", "blade_loss_2850", "--duration", "0.02", "--quiet"]


@pytest.fixture(autouse=True)
def figures_here(monkeypatch):
    """The figures drawn in this process, where the test's failure is injected (a worker is a fresh
    interpreter)."""
    monkeypatch.setenv("ROTORCOSIM_FIGURE_WORKER", "1")


def _fail_at_fig11(monkeypatch):
    def boom(self, *args, **kwargs):
        raise ValueError("boom in a figure")
    monkeypatch.setattr(blade_figures._Figures, "per_bearing", boom)
    return "drawing the figures failed after the simulation ended: ValueError: boom in a figure"


def _fail_in_savefig(monkeypatch):
    import matplotlib.figure

    def half_written(self, fname, *args, **kwargs):
        with open(fname, "wb") as f:
            f.write(b"\x89PNG half")
        raise OSError(28, "No space left on device", str(fname))
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", half_written)
    return "drawing the figures failed after the simulation ended: OSError: [Errno 28] No space left on device"


def _fail_in_extraction(monkeypatch):
    def boom(*args, **kwargs):
        raise KeyError("boom in the results")
    monkeypatch.setattr(blade_results, "extract", boom)
    return "extracting the results failed after the simulation ended: KeyError: 'boom in the results'"


@pytest.mark.parametrize("inject", [_fail_at_fig11, _fail_in_savefig, _fail_in_extraction],
                         ids=["figure", "savefig", "extract"])
def test_a_failure_after_the_steps_leaves_a_failed_run_not_a_mixed_folder(tmp_path, monkeypatch, capsys, inject):
    said = inject(monkeypatch)
    out = tmp_path / "o"
    assert main([*RUN, "--out", str(out)]) == 1
    cap = capsys.readouterr()
    err = [line for line in cap.err.splitlines() if line.strip()]
    assert len(err) == 1 and err[0].startswith(f"rotorcosim run: {said}"), cap.err
    assert f"the time series is kept in {out}" in err[0]
    assert cap.out.splitlines()[-1] == f"written: {out / 'summary.json'}, {out / 'timeseries.h5'}"
    assert sorted(p.name for p in out.iterdir()) == ["summary.json", "timeseries.h5"]
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "failed" and s["error"].startswith(f"ResultsFailed: {said}")
    assert "figures" not in s and s["checkpoint"] is None and s["t_end_s"] == pytest.approx(0.02)
    if inject is _fail_in_extraction:
        assert "bearings" not in s   # none of a half-made extraction
    with h5py.File(out / "timeseries.h5") as f:   # the steps' record, whole
        assert f["time"][-1] == pytest.approx(0.02)


def test_a_sweep_reports_such_a_case_failed(tmp_path, monkeypatch):
    from rotorcosim.master.cli.sweep import sweep

    _fail_at_fig11(monkeypatch)
    res = sweep([2850.0], tmp_path / "s", "blade_loss_2850", duration=0.02, serial=True)
    (case,) = res["case_status"]
    assert res["case_status"][case] == "failed" and "drawing the figures failed" in res["errors"][case]
    folder = tmp_path / "s" / case
    assert sorted(p.name for p in folder.iterdir()) == ["summary.json", "timeseries.h5"]
    assert json.loads((folder / "summary.json").read_text())["status"] == "failed"


def test_figures_drawn_later_fail_whole_and_leave_the_complete_run(tmp_path, monkeypatch):
    """compare draws its runs' figures after both (api.draw_figures): a failure there leaves each run complete,
    without figures, drawn again by its --resume."""
    from rotorcosim.master.api import ResultsFailed, draw_figures, simulate

    out = tmp_path / "o"
    simulate("blade_loss_2850", duration=0.02, out=out, figures=False)
    before = (out / "summary.json").read_text()
    _fail_in_savefig(monkeypatch)
    with pytest.raises(ResultsFailed, match="drawing the figures failed"):
        draw_figures("blade_loss_2850", out)
    assert sorted(p.name for p in out.iterdir()) == ["summary.json", "timeseries.h5"]
    assert (out / "summary.json").read_text() == before
