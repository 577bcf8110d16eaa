"""The validity observer (master/observer/validity.py): a run's summary.json carries the checks it left (empty
when all held), with one warning line each at the end, through the compiled and the generic loop alike."""
import json

import pytest

import rotorcosim
from rotorcosim.master.run import checkpoint

# the bearing oil of thermal0 started and supplied past the fit's flash-point limit (500 K, components/oil_fit.py)
HOT = {f"thermal0.{k}": 510.0 for k in ("T_initial", "T_supply", "T_ambient")}


def test_a_short_blade_loss_run_holds_and_says_nothing(tmp_path, capfd):
    res = rotorcosim.simulate("blade_loss_2850", duration=0.05, out=tmp_path / "r", figures=False)
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["validity"] == [] and res.summary["validity"] == []
    assert ": warning: " not in capfd.readouterr().err


@pytest.mark.parametrize("engine", ["compiled", "python"])
def test_a_run_past_an_envelope_says_when_and_how_far(tmp_path, capfd, engine):
    sc = rotorcosim.load_scenario("blade_loss_2850").set(HOT)
    duration = 0.01 if engine == "compiled" else 0.002   # the generic loop: one thermal step (1 ms) and a bit
    res = rotorcosim.simulate(sc, duration=duration, out=tmp_path / "r", figures=False, engine=engine)
    assert res.summary["engine"] == engine
    entries = json.loads((tmp_path / "r" / "summary.json").read_text())["validity"]
    assert [(e["component"], e["quantity"], e["bound"]) for e in entries] == [
        ("thermal0", "bearing oil temperature", "max"), ("thermal0", "squeeze-film oil temperature", "max")]
    for e in entries:
        assert e["limit"] == 500.0 and e["unit"] == "K" and e["time_s"] == 0.0 and e["value"] >= 510.0
        assert "ASTM D341" in e["source"]
    lines = [line for line in capfd.readouterr().err.splitlines() if ": warning: " in line]
    # besides the envelope's two lines, the run says its blade loss (t = 0.01 s) never happens in so short a run
    envelope = [line for line in lines if "t_blade_loss" not in line]
    assert len(lines) == 3 and len(envelope) == 2
    assert all(line.startswith("blade_loss_2850: warning: ") for line in lines)


def test_components_that_declare_nothing_give_an_empty_list():
    res = rotorcosim.simulate("toy_thermomechanical", duration=0.01, figures=False)
    assert res.summary["validity"] == []


def test_a_resumed_run_keeps_what_the_interrupted_one_found(tmp_path, sigint_at):
    """Interrupted (a real SIGINT) after the oil was found past its limit at t = 0, then resumed: the resumed
    run's entries keep the first time, 0, not the time it resumed at."""
    fired = sigint_at(0.015)
    sc = rotorcosim.load_scenario("blade_loss_2850").set(HOT)
    out = tmp_path / "r"
    with pytest.raises(checkpoint.RunInterrupted):
        rotorcosim.simulate(sc, duration=0.04, out=out, figures=False)
    assert fired and json.loads((out / "summary.json").read_text())["status"] == "interrupted"
    res = rotorcosim.simulate(sc, duration=0.04, out=out, figures=False, resume=True)
    assert 0.0 < res.summary["resumed_from_t_s"] < 0.04 and res.summary["t_end_s"] == pytest.approx(0.04)
    assert [e["time_s"] for e in res.summary["validity"]] == [0.0, 0.0]
