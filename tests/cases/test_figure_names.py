"""The figures name what the run simulated: the engine file's own spool names and the run's own rub-ring
clearance, per bearing id (cases/blade_loss/engine_names.py); the paper's own figures keep their look."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import rotorcosim
from rotorcosim.cases.blade_loss import engine_names
from rotorcosim.cases.blade_loss import figures as fb
from rotorcosim.cases.rundown import figures as rf

THREE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "three_bearings" / "blade_loss.toml"


def _orbit_data(k: str, n: int = 400) -> dict:
    """A circular whirl of 0.2 mm at bearing ``k`` and its rub ring, the housing at rest (the clearance circle is
    drawn: within 4 radii)."""
    t = np.linspace(0.0, 0.02, n)
    th = 2 * np.pi * 266.7 * t
    ring = 2e-4 * np.column_stack([np.cos(th), np.sin(th)])
    return {"time": t, "phase": np.zeros(n, int), f"rotor.X_brg{k}": np.column_stack([ring, np.zeros(n)]),
            f"rotor.X_housing{k}": np.zeros((n, 2)), f"rotor.X_rub{k}": ring}


def _texts(fig) -> list[str]:
    out = [fig._suptitle.get_text()] if fig._suptitle is not None else []
    out += [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    return out


def _draw(ctx, k, tmp_path) -> list[str]:
    figs = []
    job = "fig09" if ctx.bearings[0] == k else "fig10"
    assert fb.draw(job, _orbit_data(k), tmp_path, ctx, keep=figs)
    import matplotlib.pyplot as plt

    texts = _texts(figs[0])
    for f in figs:
        plt.close(f)
    return texts


def test_a_users_engine_is_titled_by_its_spool_and_its_clearance(tmp_path):
    ctx = fb.Context("my_engine", 5000.0, 22000.0, False, 100, ("A",), (("A", "fan shaft"),), (("A", 0.12),))
    texts = _draw(ctx, "A", tmp_path)
    assert texts[0] == "Fan shaft at bearing #A, F_u = 5000 N [my_engine]"
    assert "rub-ring clearance 0.12 mm" in texts and not any("0.508" in t or "Power turbine" in t for t in texts)


def test_the_papers_figure_keeps_its_look(tmp_path):
    sc = rotorcosim.load_scenario("blade_loss_2850")
    ctx = fb.context(sc, 2850.0, 16000.0, 100)
    assert ctx.paper and dict(ctx.spools) == {"0": "power turbine", "5": "power turbine"}
    texts = _draw(ctx, "0", tmp_path)
    assert texts[0] == "Power turbine at bearing #0, F_u = 2850 N (paper Fig. 9)"
    assert "rub-ring clearance 0.508 mm" in texts


def test_the_clearance_is_the_runs_own(tmp_path):
    """A --set clearance reaches the figure through the run's provenance (summary.json), not the paper's value."""
    sc = rotorcosim.load_scenario("blade_loss_2850").set({"rubring0.clearance": 1.2e-4})
    out = tmp_path / "run"
    rotorcosim.simulate(sc, duration=0.002, schedule="monolithic", out=out, figures=False)
    ran = json.loads((out / "summary.json").read_text())["provenance"]["parameters"]["rubring0"]["parameters"]
    assert ran["clearance"] == 1.2e-4
    assert engine_names.rub_clearances_mm(sc, ("0", "5"), out) == {"0": pytest.approx(0.12), "5": 0.508}
    ctx = fb.context(sc, 2850.0, 16000.0, 100, out)
    assert not ctx.paper and "rub-ring clearance 0.12 mm" in _draw(ctx, "0", tmp_path)


def test_an_engine_with_other_bearing_ids_names_its_own_spool():
    sc = rotorcosim.load_scenario(str(THREE))
    ctx = fb.context(sc, 2850.0, 16000.0)
    assert ctx.bearings == ("1", "2", "3")
    data, _ = __import__("rotorcosim.components.rotor.model", fromlist=["load_data"]).load_data(
        sc.components["rotor"].parameters["model_file"])
    spool = data["attach"]["bearing1"]["node"][0]
    assert dict(ctx.spools)["1"] == data["spool"][spool].get("name", spool)
    # a bearing without a rub ring has no clearance to state
    assert dict(ctx.rub_clearances_mm)["2"] is None


def test_the_rundown_names_the_engines_spools():
    sc = rotorcosim.load_scenario("blade_loss_rundown")
    assert engine_names.spool_name(sc, "spool_pt") == "power turbine"
    assert engine_names.spool_name(sc, "spool_gg") == "gas generator"
    assert rf._label(sc, "spool_pt") == "power turbine (spool_pt)"
    assert list(rf._locations(sc, {"damper0.F_journal": np.zeros((2, 2)), "rotor.X_brg0": np.zeros((2, 3)),
                                   "damper5.F_journal": np.zeros((2, 2)), "rotor.X_brg5": np.zeros((2, 3))})) \
        == ["bearing #0", "bearing #5"]


@pytest.mark.slow   # ~44 s of CPU time (measured): a rundown run and its figures
def test_the_rundown_figures_are_drawn_per_bearing_id(tmp_path):
    """The four rundown figures of a made-up rundown of the shipped engine (16 000 -> 4 000 rev/min): one
    temperature panel per bearing id, the spools by the engine's names."""
    sc = rotorcosim.load_scenario("blade_loss_rundown")
    n = 3000
    t = np.linspace(0.0, 30.0, n)
    w = (16000.0 - 400.0 * t) / rf.RPM
    data = {"time": t, "phase": np.zeros(n, int), "spool_pt.Omega": w[:, None], "spool_gg.Omega": 0.9 * w[:, None]}
    for k in ("0", "5"):
        th = np.cumsum(w) * (t[1] - t[0])
        data[f"rotor.X_brg{k}"] = 1e-4 * np.column_stack([np.cos(th), np.sin(th), np.zeros(n)])
        data[f"damper{k}.F_journal"] = 1e3 * np.column_stack([np.cos(th), np.sin(th)])
        data[f"thermal{k}.T_nodes"] = np.full((n, 9), 330.0)
    names = rf.figures(sc, data, tmp_path, dpi=60)
    assert names == ["rundown_speed.png", "rundown_response.png", "rundown_campbell.png",
                     "rundown_temperatures.png"]
    assert all((tmp_path / name).stat().st_size > 1000 for name in names)
