"""``check-engine``: every synchronous critical speed up to 1.5 x each spool's operating speed with its whirl and
its separation margin, and one warning line each for a critical speed nearer than the margin API 684 asks for its
mode's amplification factor (tests/components/test_separation_margin.py), a
bearing bore that does not fit the shaft at its node, dimensions implausible for mm, a spool turning a bearing
beyond its model's speed range, and a whirl mode that cross-coupled supports make unstable."""
from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest

from rotorcosim.cases.blade_loss import new_engine
from rotorcosim.cases.blade_loss.check_engine import check_engine
from rotorcosim.components.rotor import critical, model as fem
from rotorcosim.interop.engine_toml import dumps
from rotorcosim.master.cli import main

DATA = Path(__file__).parents[1] / "interop" / "data"


@pytest.fixture(autouse=True)
def _one_blas_thread():
    """One BLAS thread, as every entry point of the program computes (master/core/threads.py): the eigen-solves of
    small matrices only lose by threads, on a loaded machine many times over."""
    from rotorcosim.master.core.threads import one_thread

    with one_thread():
        yield


@pytest.fixture(scope="module")
def textbook(tmp_path_factory):
    d = tmp_path_factory.mktemp("e")
    new_engine.new_engine(d / "X")
    return d / "X" / "engine.toml", d / "X" / "blade_loss.toml"


def _variant(tmp_path, engine: Path, change) -> Path:
    data = tomllib.loads(engine.read_text())
    change(data)
    p = tmp_path / "engine.toml"
    p.write_text(dumps(data))
    return p


def test_every_critical_up_to_1_5x_with_whirl_and_margin(textbook, capsys):
    engine, scenario = textbook
    rc = main(["check-engine", str(engine), "--scenario", str(scenario), "--json", "--campbell",
               str(engine.parent / "c.png")])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["problems"] == []
    rows = out["separation"]
    # the same list as the critical speeds' own eigenproblem solved for many modes, split by whirl
    ref = out["critical_speeds"]
    from rotorcosim.cases.blade_loss import critical_speeds as cs
    from rotorcosim.master.api import load_scenario

    m = fem.load(engine)
    full = critical.synchronous_critical_speeds(m, cs.linearised_supports(m, None, load_scenario(scenario)), n=40,
                                                max_rpm=24000.0)
    for whirl in ("forward", "backward"):
        assert [r["rpm"] for r in rows if r["whirl"] == whirl] == pytest.approx(full[f"{whirl}_synchronous_rpm"],
                                                                                rel=1e-9)
    assert max(r["rpm"] for r in rows) <= 24000.0 and len(rows) >= 6
    from rotorcosim.components.rotor import engine_check

    for r in rows:
        af = r["amplification_factor"]
        assert r["damping_ratio"] > 0 and af == pytest.approx(1 / (2 * r["damping_ratio"]))
        margin = 100 * (r["rpm"] / 16000.0 - 1)
        assert r["margins"] == [{"operating_rpm": 16000.0, "margin_percent": pytest.approx(margin),
                                 "required_percent": pytest.approx(
                                     100 * engine_check.required_margin(af, above=margin > 0))}]
    near = [r for r in rows if abs(r["margins"][0]["margin_percent"]) < r["margins"][0]["required_percent"]]
    sep = [w for w in out["warnings"] if "separation margin" in w]
    assert len(sep) == len(near)
    # its backward critical 1.7 % above its speed is well damped by the films (AF < 2.5): API 684 asks no margin
    close = [r for r in rows if abs(r["margins"][0]["margin_percent"]) < 15.0]
    assert close and all(r["amplification_factor"] < 2.5 and r not in near for r in close)
    assert all("API 684 asks a separation margin of" in w and "amplification factor" in w and "\n" not in w
               for w in sep)
    assert ref["forward_synchronous_rpm"][0] == pytest.approx(rows[[r["whirl"] for r in rows].index("forward")]["rpm"])


def test_rosss_coaxial_rotor_forward_critical_2_7_percent_below_is_warned(tmp_path, capsys):
    out = tmp_path / "coax.toml"
    assert main(["import-ross", str(DATA / "coaxrotor_example.toml"), "--out", str(out), "--speed", "16000"]) == 0
    capsys.readouterr()
    rep = check_engine(str(out))
    w = [x for x in rep["warnings"] if "forward critical speed 1556" in x]
    assert w and "2.7 % below the operating speed 16000 rev/min" in w[0]


def test_a_bore_that_does_not_fit_the_shaft(tmp_path, textbook):
    engine, scenario = textbook

    def thick(d):
        d["spool"]["rotor"]["d_out_mm"][1] = 60.0          # bearing0 (50.8 mm bore) at node 2
        d["spool"]["rotor"]["d_out_mm"][2] = 60.0
    rep = check_engine(str(_variant(tmp_path, engine, thick)), str(scenario))
    bore = [w for w in rep["warnings"] if "bore" in w]
    assert bore == ["attach.bearing0: its bore 50.8 mm does not fit the shaft at node ['rotor', 2] (outer diameter "
                    "60 / 60 mm; within 2% expected)"]
    assert not [w for w in check_engine(str(engine), str(scenario))["warnings"] if "bore" in w]


def test_an_engine_written_in_metres_or_micrometres(tmp_path, textbook):
    engine, scenario = textbook

    def metres(d):
        r = d["spool"]["rotor"]
        for k in ("z_mm", "d_out_mm", "d_in_mm"):
            r[k] = [v / 1000.0 for v in r[k]]
    rep = check_engine(str(_variant(tmp_path, engine, metres)), str(scenario))
    assert any(w.startswith("spool.rotor.d_out_mm[0] = 0.06 mm: a shaft thinner than 5 mm") for w in rep["warnings"])

    def micrometres(d):
        d["spool"]["rotor"]["z_mm"] = [v * 1000.0 for v in d["spool"]["rotor"]["z_mm"]]
    rep = check_engine(str(_variant(tmp_path, engine, micrometres)), str(scenario))
    assert any(w.startswith("spool.rotor.z_mm: a spool 960 m long") for w in rep["warnings"])


def test_a_spool_beyond_its_bearings_speed_range(tmp_path, textbook, capsys):
    engine, scenario = textbook

    def fast(d):
        d["spool"]["rotor"]["speed_rpm"] = 31000.0         # bearing5 (83.8 mm bore): 29 833 rev/min at most
    p = _variant(tmp_path, engine, fast)
    rc = main(["check-engine", str(p), "--scenario", str(scenario), "--campbell", str(tmp_path / "c.png")])
    out = capsys.readouterr().out
    assert rc == 0
    lines = [line for line in out.splitlines() if "speed limit" in line]
    assert lines == ["  warning: attach.bearing5: the bearing turns with spool rotor at 31000 rev/min, above the ball "
                     "bearing model's speed limit 29833 rev/min (bore 83.8 mm, bore x speed <= 2.5e+06 mm rev/min)"]


def _rigid_rotor(tmp_path, q: float) -> Path:
    """A stiff 100 mm shaft 200 mm long with a 50 kg disk at its middle on two like supports (k = 5e6 N/m,
    c = 1000 N s/m and cross-coupled kxy = -kyx = q each), 3 000 rev/min."""
    e = {"engine": {"format": fem.FORMAT, "name": "rigid rotor on cross-coupled supports"},
         "material": {"rotor": {"E": 2.1e11, "rho": 7850.0, "nu": 0.3}},
         "damping": {"zeta": 0.0, "f1_Hz": 1.0, "f2_Hz": 2.0},
         "spool": {"s": {"speed_rpm": 3000.0, "z_mm": [0.0, 100.0, 200.0], "d_out_mm": [100.0, 100.0],
                         "d_in_mm": [0.0, 0.0], "drive_node": 0, "axial_node": 0,
                         "disks": [{"node": 1, "name": "disk", "mass": 50.0, "Ip": 0.05, "Id": 0.5}]}},
         "support": [{"name": f"seal {n}", "a": ["s", n], "b": "ground", "k": 5e6, "c": 1000.0, "kxy": q,
                      "kyx": -q} for n in (0, 2)]}
    p = tmp_path / "rigid.toml"
    p.write_text(dumps(e))
    return p


def test_a_whirl_fed_by_cross_coupled_supports_is_named_past_its_threshold(tmp_path):
    """The analytic threshold of cross-coupled stiffness: a rigid rotor of mass m on supports of total stiffness k,
    damping c and cross-coupled stiffness q whirls unstably forward at its natural frequency w_n = sqrt(k / m)
    once q > c w_n (m z'' + c z' + (k - i q) z = 0, z = x + i y: at lambda = i w_n
    the real part gives k = m w_n^2, the imaginary one q = c w_n). Here m = 62.3 kg (disk and shaft), k = 1e7 N/m,
    c = 2000 N s/m: q* = 8.01e5 N/m. At 0.9 q* the least damped mode is damped, at 1.1 q* it is the forward
    cylindrical mode at w_n, of negative damping, and check-engine says so in one line."""
    import math

    m_total = 50.0 + 7850.0 * math.pi * 0.05 ** 2 * 0.2
    wn = math.sqrt(1e7 / m_total)
    q_star = 2000.0 * wn
    for ratio, unstable in ((0.9, False), (1.1, True)):
        out = check_engine(str(_rigid_rotor(tmp_path, 0.5 * ratio * q_star)), max_rpm=6000.0)
        st = out["stability"]
        assert st["cross_coupled_supports"] == ["seal 0", "seal 2"]
        least = min(st["modes"], key=lambda r: r["damping_ratio"])
        assert least["frequency_Hz"] == pytest.approx(wn / (2 * math.pi), rel=5e-3)
        lines = [w for w in out["warnings"] if w.startswith("unstable")]
        if unstable:
            assert least["whirl"] == "forward" and least["damping_ratio"] < 0.0
            assert len(lines) == 1 and "forward whirl mode at" in lines[0]
        else:
            assert least["damping_ratio"] > 0.0 and not lines
    # without cross-coupling nothing is solved for: the linear engine cannot grow
    assert check_engine(str(_rigid_rotor(tmp_path, 0.0)), max_rpm=6000.0)["stability"] is None
