"""What a blade-loss run's outputs say they are: the whirl absolute and relative to the housing, the peaks over the
whole run beside the end values, and the events the end values do not show (a transient rub, a contact stress
above the plastic-flow limit).

The peaks are computed online (cases/blade_loss/results.py ``Peaks``: no series kept); they are checked here
against an independent reading of the run's own time series file, recorded at every base step, and the compiled
loop against the generic one."""
from __future__ import annotations

import h5py
import numpy as np
import pytest

import rotorcosim
from rotorcosim.cases.blade_loss import results

#: the blade loss at 0.01 s, the #0 stress above 3200 MPa from ~0.0109 s and the rub from ~0.0112 s at 8551 N
DURATION = 0.02
IDS = ("0", "5")
RECORD = [f"{p}{k}" for k in IDS for p in ("rotor.X_brg", "rotor.X_housing")] + \
         [f"{c}{k}.{p}" for k in IDS for c, p in (("damper", "F_journal"), ("bearing", "sigma_max_step"),
                                                   ("bearing", "Q_max_step"))] + \
         [f"rubring{k}.P_rub" for k in IDS]


def _run(tmp_path, engine: str):
    sc = rotorcosim.load_scenario("blade_loss_8551")
    sc.outputs["record_step"] = float(sc.schedule.get("step", 1e-5))   # every base step: the file sees what Peaks saw
    return rotorcosim.simulate(sc, duration=DURATION, schedule="monolithic", out=tmp_path / engine, record=RECORD,
                               figures=False, engine=engine)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("peaks")
    return {e: _run(tmp, e) for e in ("compiled", "python")}, tmp


def test_peaks_equal_the_maxima_of_the_written_file(runs):
    res, tmp = runs
    assert res["compiled"].summary["engine"] == "compiled"
    b = res["compiled"].summary["bearings"]
    with h5py.File(tmp / "compiled" / "timeseries.h5") as f:
        t = f["time"][:]
        for k in IDS:
            x, h = f[f"rotor.X_brg{k}"][:, :2], f[f"rotor.X_housing{k}"][:]
            sig, q = f[f"bearing{k}.sigma_max_step"][:], f[f"bearing{k}.Q_max_step"][:]
            force, rub = f[f"damper{k}.F_journal"][:], f[f"rubring{k}.P_rub"][:, 0]
            r = b[k]
            assert r["whirl_amplitude_absolute_peak_mm"] == pytest.approx(1e3 * np.hypot(*x.T).max(), rel=1e-12)
            assert r["whirl_amplitude_relative_peak_mm"] == pytest.approx(1e3 * np.hypot(*(x - h).T).max(), rel=1e-12)
            assert r["transmitted_force_peak_N"] == pytest.approx(np.hypot(*force.T).max(), rel=1e-12)
            assert r["rub_power_peak_W"] == pytest.approx(rub.max(), rel=1e-12, abs=1e-12)
            assert r["max_contact_stress_peak_MPa"] == pytest.approx(1e-6 * sig[:, 0].max(), rel=1e-12)
            assert r["max_contact_stress_outer_peak_MPa"] == pytest.approx(1e-6 * sig[:, 1].max(), rel=1e-12)
            assert r["max_contact_load_peak_N"] == pytest.approx(q.max(), rel=1e-12)
            above = np.flatnonzero(sig.max(axis=1) > results.PLASTIC_FLOW_PA)
            assert r["plastic_flow_first_time_s"] == (pytest.approx(t[above[0]], abs=1e-12) if len(above) else None)
            on = np.flatnonzero(rub > 0.0)
            assert r["rub_first_time_s"] == (pytest.approx(t[on[0]], abs=1e-12) if len(on) else None)
            # the Table 4 whirl is the absolute one, named so beside it
            assert r["whirl_amplitude_absolute_mm"] == r["whirl_amplitude_mm"]
            assert r["whirl_amplitude_relative_mm"] > 0.0
    # the case at 8551 N: bearing #0 rubs and passes the plastic-flow limit at the blade loss, #5 does neither
    assert 0.0105 < b["0"]["plastic_flow_first_time_s"] < 0.012 and b["0"]["rub_first_time_s"] > 0.0105
    assert b["5"]["plastic_flow_first_time_s"] is None and b["5"]["rub_first_time_s"] is None
    assert b["0"]["max_contact_stress_peak_MPa"] > results.PLASTIC_FLOW_MPA


def test_the_compiled_loop_gives_the_generic_loops_peaks(runs):
    res, _ = runs
    assert res["python"].summary["engine"] == "python"
    a, b = (res[e].summary["bearings"] for e in ("compiled", "python"))
    for k in IDS:
        for key, v in a[k].items():
            if isinstance(v, float):
                assert b[k][key] == pytest.approx(v, rel=1e-9, abs=1e-12), (k, key)
            else:
                assert b[k][key] == v, (k, key)


def test_plastic_flow_is_an_event(runs):
    res, _ = runs
    ev = res["compiled"].summary["events"]
    assert [(e["kind"], e["bearing"]) for e in ev] == [("plastic_flow", "0")]
    assert ev[0]["limit"] == 3200.0 and ev[0]["peak"] > 3200.0 and ev[0]["unit"] == "MPa"


def _bearing(**changes):
    r = {"rub_first_time_s": None, "rub_power_W": 0.0, "rub_power_peak_W": None, "plastic_flow_first_time_s": None,
         "max_contact_stress_peak_MPa": 2000.0, "max_contact_stress_outer_peak_MPa": 1900.0}
    r.update(changes)
    return r


def test_a_transient_rub_is_an_event_and_a_lasting_one_is_in_the_end_values():
    transient = _bearing(rub_first_time_s=0.0112, rub_power_peak_W=45e3)
    lasting = _bearing(rub_first_time_s=0.0112, rub_power_peak_W=45e3, rub_power_W=1.2e4)
    ev = results.events({"0": transient, "5": lasting, "7": _bearing()})
    assert [(e["kind"], e["bearing"]) for e in ev] == [("rub", "0")]
    assert "from t = 0.0112 s" in ev[0]["message"] and "45000 W" in ev[0]["message"]
    # plastic flow on the outer race counts (either race), its peak the larger race's
    ev = results.events({"1": _bearing(plastic_flow_first_time_s=0.5, max_contact_stress_outer_peak_MPa=3300.0)})
    assert ev[0]["kind"] == "plastic_flow" and ev[0]["peak"] == 3300.0


def test_the_warning_line_is_printed_once_per_event(tmp_path, capsys):
    sc = rotorcosim.load_scenario("blade_loss_8551")
    rotorcosim.simulate(sc, duration=0.012, schedule="monolithic", out=tmp_path / "o", figures=False)
    err = capsys.readouterr().err.splitlines()
    lines = [x for x in err if "plastic flow" in x]
    assert len(lines) == 1 and lines[0].startswith(f"{sc.name}: warning: bearing 0: a ball contact stress above "
                                                   "the 3200 MPa of incipient plastic flow from t = 0.0109")
