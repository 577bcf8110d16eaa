"""The components' validity envelopes (components/validity.py): each check fires outside its limit, with the
limit and its source, and stays silent at the paper's conditions; the commands report them in their JSON output
and with one line each on stderr."""
import json

import numpy as np
import pytest

from rotorcosim.components.bearing.cli import evaluate as bearing_static
from rotorcosim.components.bearing.component import ELASTIC_LIMIT_PA
from rotorcosim.components.damper.cli import evaluate as damper_force
from rotorcosim.components.damper.component import LAMINAR_FILM_RE, FastDamper
from rotorcosim.components.rubring.component import LINEAR_CONTACT_N, RubRing
from rotorcosim.components.thermal.cli import steady
from rotorcosim.components.validity import Check, Tracker, once, warning_line
from rotorcosim.master.cli import main

CLEARANCE = 0.635e-3   # Table 3, both dampers


def call(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def warnings_of(err: str) -> list[str]:
    return [line for line in err.splitlines() if ": warning: " in line]


# -- the tracker ------------------------------------------------------------------------------------------
def test_tracker_keeps_the_first_time_and_the_worst_value():
    hi = Check("q", ("y",), lambda y: y["y"][:, 0], 1.0, "1", "src")
    lo = Check("q low", ("y",), lambda y: y["y"][:, 0], -1.0, "1", "src", bound="min")
    tr = Tracker({"c": (hi, lo)})
    tr.update(np.array([0.0, 0.1, 0.2]), {"c.y": np.array([[0.5], [1.5], [1.2]])})
    tr.update(np.array([0.3, 0.4]), {"c.y": np.array([[3.0], [-2.0]])})
    tr.update(np.array([0.5]), {"c.y": np.array([[2.0]])})
    (a, b) = tr.entries()
    assert (a["quantity"], a["value"], a["time_s"], a["limit"], a["bound"]) == ("q", 3.0, 0.1, 1.0, "max")
    assert (b["quantity"], b["value"], b["time_s"], b["bound"]) == ("q low", -2.0, 0.4, "min")
    # only= leaves the other components' checks alone; NaN (an input not known on that row) is not judged
    tr2 = Tracker({"c": (hi,), "d": (hi,)})
    tr2.update(np.array([0.0]), {"c.y": np.array([[5.0]]), "d.y": np.array([[5.0]])}, only={"d"})
    tr2.update(np.array([0.0]), {"c.y": np.array([[np.nan]]), "d.y": np.array([[0.0]])})
    assert [e["component"] for e in tr2.entries()] == ["d"]


def test_warning_line_names_value_limit_time_and_source():
    e = {"component": "bearing0", "quantity": "contact stress", "value": 4402.47, "limit": 4200.0, "unit": "MPa",
         "bound": "max", "time_s": 0.0109, "source": "ISO 76"}
    line = warning_line("run", e)
    assert line == ("run: warning: contact stress of bearing0 4402.5 MPa is above 4200 MPa (first at t = 0.0109 s), "
                    "outside the model's validity: ISO 76")
    assert "\n" not in line


# -- the bearing: elastic Hertz contact (ISO 76) ----------------------------------------------------------
def test_bearing_static_far_beyond_the_elastic_range_says_so(capsys):
    rc, out, err = call(capsys, "bearing-static", "--bearing", "0", "--radial-load", "1e6", "--json")
    (entry,) = json.loads(out)["validity"]
    assert rc == 0 and entry["component"] == "bearing0" and entry["quantity"] == "contact stress"
    assert entry["limit"] == 4200.0 and entry["unit"] == "MPa" and entry["value"] > 14000.0
    assert "ISO 76" in entry["source"] and entry["time_s"] is None
    (line,) = warnings_of(err)
    assert line.startswith("rotorcosim bearing-static: warning: contact stress") and "above 4200 MPa" in line


def test_bearing_stress_near_the_papers_3200_mpa_is_no_warning():
    # 9 kN radial on #0: ~3230 MPa, the paper's largest cases (its damage criterion is 3200 MPa)
    d = bearing_static(0, 9000.0)
    assert 3200.0 < d["max_contact_stress_MPa"] < 4200.0
    assert d["validity"] == [] and d["within_elastic_range"] is True
    assert ELASTIC_LIMIT_PA == 4200e6


# -- the damper: journal eccentricity, laminar film -------------------------------------------------------
def test_damper_force_near_the_wall_says_so(capsys):
    rc, out, err = call(capsys, "damper-force", "--damper", "0", "--position", str(0.995 * CLEARANCE), "0",
                        "--velocity", "0", "0.1", "--temperature", "80", "--json")
    (entry,) = json.loads(out)["validity"]
    assert rc == 0 and entry["quantity"] == "journal eccentricity ratio" and entry["limit"] == 0.99
    assert entry["value"] == pytest.approx(0.995)
    (line,) = warnings_of(err)
    assert "journal eccentricity ratio of damper0 0.995 is above 0.99" in line


@pytest.mark.parametrize("eps", [0.0, 0.5, 0.9, 0.98])
def test_damper_force_inside_the_film_model_is_quiet(eps):
    d = damper_force(0, (eps * CLEARANCE, 0.0), (0.0, 0.17), 80.0)
    assert d["validity"] == []


def test_damper_turbulent_film_is_flagged():
    d = FastDamper("damper0", {"damper": 0})
    d.setup(0.0)
    d.set_inputs({"V_journal": [5.0, 0.0], "T_oil": [373.15]})
    d.do_step(0.0, 1e-5)
    y = {**d.u, **d.y}
    # rho |V| c / mu = 843 * 5 * 0.635e-3 / 0.011 = 243: laminar; 25 m/s: above 1000
    assert once(d.validity(), y, "damper0") == []
    y["V_journal"] = np.array([25.0, 0.0])
    (entry,) = once(d.validity(), y, "damper0")
    assert entry["quantity"] == "film Reynolds number" and entry["limit"] == LAMINAR_FILM_RE
    assert entry["value"] == pytest.approx(1217, rel=0.01)


def test_damper_without_spring_declares_no_eccentricity():
    d = FastDamper("damper0", {"damper": 0, "k_spring": 0.0})
    d.setup(0.0)
    assert [c.quantity for c in d.validity()] == ["film Reynolds number"]


# -- the rub ring: the contact stiffness's range ----------------------------------------------------------
def test_rub_force_beyond_the_stiffness_law_is_flagged():
    r = RubRing("rubring0", {"bearing": 0})
    r.setup(0.0)
    (check,) = r.validity()
    assert check.limit == LINEAR_CONTACT_N == 50e3
    assert once(r.validity(), {"F_normal": [27e3]}, "rubring0") == []   # 14 252 N's largest, measured
    (entry,) = once(r.validity(), {"F_normal": [6e4]}, "rubring0")
    assert entry["unit"] == "N" and entry["value"] == 6e4
    other = RubRing("rubring0", {"bearing": 0, "stiffness": 1e9})
    other.setup(0.0)
    assert other.validity() == ()


# -- the thermal network: the oil inside the viscosity fit's range ------------------------------------------
def test_thermal_steady_past_the_flash_point_says_so(capsys):
    rc, out, err = call(capsys, "thermal-steady", "--bearing", "0", "--drag-power", "700", "--sfd-power", "100",
                        "--json")
    d = json.loads(out)
    (entry,) = d["validity"]
    assert rc == 0 and entry["quantity"] == "bearing oil temperature" and entry["limit"] == 500.0
    assert entry["unit"] == "K" and entry["value"] == pytest.approx(d["bearing_oil_C"] + 273.15)
    (line,) = warnings_of(err)
    assert "bearing oil temperature of thermal0" in line and "above 500 K" in line


def test_thermal_steady_at_the_papers_powers_is_quiet(capsys):
    # Table 5's largest drag and film powers at #0 (~400 W, ~130 W): oil well inside the fit
    d = steady(0, 400.0, 130.0)
    assert d["validity"] == []
    rc, _, err = call(capsys, "thermal-steady", "--bearing", "5", "--drag-power", "730", "--sfd-power", "20")
    assert rc == 0 and warnings_of(err) == []
