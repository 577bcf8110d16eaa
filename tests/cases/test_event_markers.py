"""Every time-history figure marks the run's located events (master/core/events.py; the time series' ``events``
attribute): the blade-loss figures (cases/blade_loss/figures.py) on each time axis, not on the orbit, drawn from a
small time series written here with one event in it."""
from __future__ import annotations

import json

import h5py
import numpy as np

import rotorcosim
from rotorcosim.cases.blade_loss import figures as fb
from rotorcosim.master.observer.series import SeriesFile


def test_blade_loss_figures_mark_an_event_on_their_time_axes(tmp_path):
    t = np.linspace(0.0, 0.05, 501)
    x = 1e-4 * np.column_stack([np.cos(1675.5 * t), np.sin(1675.5 * t), 0.0 * t])
    event = {"t_s": 0.0123, "component": "fuse", "kind": "break"}
    with h5py.File(tmp_path / "timeseries.h5", "w") as f:
        f["time"], f["phase"] = t, np.zeros(len(t), dtype=np.int8)
        f["rotor.X_brg0"] = x
        f.attrs["events"] = json.dumps([event])
    sc = rotorcosim.load_scenario("blade_loss_2850")
    figs: list = []
    names = fb.draw("fig09", SeriesFile(tmp_path / "timeseries.h5"), tmp_path, fb.context(sc, 2850.0, 16000.0),
                    keep=figs)
    assert names == ["fig09_response_bearing0.png"]
    (fig,) = figs
    marked = {a.get_xlabel(): [ln.get_xdata()[0] for ln in a.lines if ln.get_gid() == "event-fuse-break"]
              for a in fig.axes}
    import matplotlib.pyplot as plt

    plt.close(fig)
    assert marked["time [s]"] == [0.0123]                       # the transient's time axis
    assert all(not v for k, v in marked.items() if not k.startswith("time"))   # the orbit has no time
