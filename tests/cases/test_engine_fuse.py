"""A support fuse in an engine file ([fuse.ID], docs/reference/engine-format.md): the linear engine with the fuse
intact and broken against the same engine without a fuse (a stiff, light fused housing is the unfused engine; a
broken fuse under a light housing is a spring in series with the damper's centering spring), the bad inputs as
one-line errors naming the key, and a co-simulation whose fuse breaks."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from rotorcosim.cases.blade_loss.critical_speeds import fuse_states, linearised_supports
from rotorcosim.cases.blade_loss.new_engine import new_engine
from rotorcosim.components.rotor import critical
from rotorcosim.components.rotor import model as fem

FUSE = """
[fuse.0]
housing_mass_kg = {mass}
k_intact = {k}
damping = 2000.0
break_load_N = {load}
k_broken = {kb}
"""


@pytest.fixture(scope="module")
def engine_folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("engine")
    new_engine(folder)
    return folder


def _forward(path, stage=0):
    """The three lowest forward synchronous critical speeds [rev/min] of the engine file at ``path``, its fuses at
    ``stage`` (critical_speeds' own linearisation, without its damped scan)."""
    m = fem.load(path)
    return critical.synchronous_critical_speeds(m, linearised_supports(m, None, None, stage),
                                                n=3, max_rpm=30000.0)["forward_synchronous_rpm"]


def _engine(folder, name, text):
    path = folder / name
    path.write_text((folder / "engine.toml").read_text() + text)
    return str(path)


def test_intact_and_broken_critical_speeds_against_the_engine_without_a_fuse(engine_folder):
    """A fused housing of 1 g on a fuse of 1e12 N/m is the engine without a fuse: its critical speeds within
    0.01 %. Broken (1e7 N/m), the fuse under that housing is a spring in series with damper #0's centering spring
    (5.254e6 N/m): the engine without a fuse whose [damper.0] k_spring is 1 / (1 / 5.254e6 + 1 / 1e7) has the
    fused engine's broken critical speeds within 0.01 % (the lowest falls from 4 349 to 3 707 rev/min). Each
    reported under fuse_states with its label and stiffness."""
    plain = _forward(engine_folder / "engine.toml")
    path = _engine(engine_folder, "fused.toml", FUSE.format(mass=1e-3, k=1e12, load=3000.0, kb=1e7))
    assert _forward(path) == pytest.approx(plain, rel=1e-4)
    (broken,) = fuse_states(fem.load(path), 3, 30000.0)
    assert broken["label"] == "fuse broken" and broken["fuse_stiffness_N_per_m"] == {"0": 1e7}
    series = 1.0 / (1.0 / 5.254e6 + 1.0 / 1e7)
    text = (engine_folder / "engine.toml").read_text().replace("k_spring = 5.254e6", f"k_spring = {series!r}", 1)
    assert text != (engine_folder / "engine.toml").read_text()
    soft = engine_folder / "soft.toml"
    soft.write_text(text)
    expect = _forward(soft)
    assert broken["forward_synchronous_rpm"] == pytest.approx(expect, rel=1e-4)
    assert broken["forward_synchronous_rpm"][0] < 0.9 * plain[0]


def test_the_combinations_of_fuse_stages_and_a_run_s_configurations_per_fuse():
    """linear_engine.fuse_combinations: every combination of the fuses' stages but the all-intact one, the first
    fuse's stage varying slowest (one fuse: its stages in turn); modes.fuse_breaks: after each break of a run, each
    fuse at the stage its own breaks reached (the other fuses as they were)."""
    from types import SimpleNamespace

    from rotorcosim.cases.blade_loss.linear_engine import fuse_combinations
    from rotorcosim.cases.rundown.modes import fuse_breaks

    assert fuse_combinations({"fuse": {"0": {"stages": 2}}}) == [{"0": 1}, {"0": 2}]
    assert fuse_combinations({"fuse": {"0": {}, "5": {"stages": 2}}}) == [
        {"0": 0, "5": 1}, {"0": 0, "5": 2}, {"0": 1, "5": 0}, {"0": 1, "5": 1}, {"0": 1, "5": 2}]
    assert fuse_combinations({}) == []
    fuse = SimpleNamespace(p={"k_intact": 1e9})
    events = [{"component": "fuse5", "kind": "break", "t_s": 0.011, "values": {}},
              {"component": "spool_pt", "kind": "time", "t_s": 0.012},
              {"component": "fuse0", "kind": "break", "t_s": 0.013, "values": {"stage": 1}},
              {"component": "fuse5", "kind": "break", "t_s": 0.014, "values": {"stage": 2}}]
    comps = {"fuse0": fuse, "fuse5": fuse, "spool_pt": SimpleNamespace(p={})}
    assert [(t, st) for t, st, _ in fuse_breaks(events, comps)] == [
        (0.011, {"5": 1}), (0.013, {"5": 1, "0": 1}), (0.014, {"5": 2, "0": 1})]


def test_two_fuses_are_reported_in_each_combination_of_their_stages(engine_folder):
    """Fuses under both bearings' housings (#0 and #5, each 1 g on 1e12 N/m, 1e7 N/m broken): fuse_states lists
    the three combinations of their stages (#5 broken alone, #0 broken alone, both), each as the engine without
    fuses whose broken bearings' damper springs are in series with 1e7 N/m (critical speeds within 0.01 %)."""
    fuse5 = FUSE.replace("[fuse.0]", "[fuse.5]").format(mass=1e-3, k=1e12, load=3000.0, kb=1e7)
    path = _engine(engine_folder, "two.toml", FUSE.format(mass=1e-3, k=1e12, load=3000.0, kb=1e7) + fuse5)
    states = fuse_states(fem.load(path), 3, 30000.0)
    assert [st["stages"] for st in states] == [{"0": 0, "5": 1}, {"0": 1, "5": 0}, {"0": 1, "5": 1}]
    assert [st["label"] for st in states] == ["fuse 0 intact, fuse 5 broken", "fuse 0 broken, fuse 5 intact",
                                              "fuse 0 broken, fuse 5 broken"]
    base = (engine_folder / "engine.toml").read_text()
    series = 1.0 / (1.0 / 5.254e6 + 1.0 / 1e7)
    for st in states:
        parts = base.split("[damper.")
        for i, part in enumerate(parts[1:], 1):
            if st["stages"][part.split("]", 1)[0]]:
                parts[i] = part.replace("k_spring = 5.254e6", f"k_spring = {series!r}", 1)
        soft = engine_folder / "soft_two.toml"
        soft.write_text("[damper.".join(parts))
        assert st["forward_synchronous_rpm"] == pytest.approx(_forward(soft), rel=1e-4), st["label"]


@pytest.mark.parametrize("text, message", [
    ("\n[fuse.7]\nhousing_mass_kg = 1.0\nk_intact = 1e9\nbreak_load_N = 1000.0\n",
     "[fuse.7]: [attach] has no bearing7"),
    (FUSE.format(mass=1.5, k=1e9, load=0.0, kb=1e7), "[fuse.0] break_load_N: must be > 0"),
    (FUSE.format(mass=1.5, k=1e9, load="nan", kb=1e7), "[fuse.0] break_load_N: must be a finite number"),
    (FUSE.format(mass=1.5, k=1e9, load=1000.0, kb=2e9), "[fuse.0] k_broken: must be at most k_intact"),
    (FUSE.format(mass=1.5, k=1e9, load=1000.0, kb=1e7) + "bumper_clearance_mm = -0.1\n",
     "[fuse.0] bumper_clearance_mm: must be >= 0"),
    (FUSE.format(mass=1.5, k=1e9, load=1000.0, kb=1e7) + "stiffness = 1.0\n", "[fuse.0] stiffness: unknown key"),
    # the critical speeds of each combination of stages would be asked of a third stage the format has not
    (FUSE.format(mass=1.5, k=1e9, load=1000.0, kb=1e7) + "stages = 3\n", "[fuse.0] stages: must be 1 or 2, got 3"),
    # a required key left out: named as missing, in the user's file (it read "got None", or named the paper's
    # engine file: components/rotor/data/engine.toml)
    ("\n[fuse.0]\nk_intact = 1e9\nbreak_load_N = 600.0\n", "[fuse.0] housing_mass_kg: missing (mass of the"),
    ("\n[fuse.0]\nhousing_mass_kg = 1.5\nbreak_load_N = 600.0\n", "[fuse.0] k_intact: missing (intact radial"),
    ("\n[fuse.0]\nhousing_mass_kg = 1.5\nk_intact = 1e9\n", "[fuse.0] break_load_N: missing (radial elastic"),
])
def test_bad_fuse_in_an_engine_file_is_one_line(engine_folder, tmp_path, text, message):
    path = _engine(engine_folder, "bad.toml", text)
    r = subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", "check-engine", path],
                       capture_output=True, text=True)
    assert r.returncode == 2, r.stdout + r.stderr
    lines = [line for line in (r.stdout + r.stderr).splitlines() if line.strip()]
    assert any(message in line for line in lines), lines
    assert "Traceback" not in r.stderr and "None" not in r.stdout + r.stderr
    assert "components/rotor/data/engine.toml" not in r.stdout + r.stderr


def test_a_part_table_without_a_required_key_is_a_problem_of_the_user_s_file(engine_folder):
    """A [bearing.0] without its balls: check-engine lists it by key (it stopped at the linearised engine, naming
    the paper's engine file components/rotor/data/engine.toml as the file that lacked it)."""
    from rotorcosim.components.rotor import engine_check

    data, _ = fem.load_data(engine_folder / "engine.toml")
    del data["bearing"]["0"]["balls"]
    (line,) = engine_check.problems(data)
    assert line.startswith("[bearing.0] balls: missing (number of balls"), line


def test_a_fuse_with_no_soft_path_lists_its_broken_state_as_not_computed(engine_folder):
    """k_broken's default 0 (nothing holds the housing after the break but a bumper): the engine after the break
    has a rigid-body motion; check-engine reports the intact engine and says why the broken one has no critical
    speeds (it stopped with 'spool rotor moves freely, held by no spring')."""
    path = _engine(engine_folder, "no_soft_path.toml",
                   "\n[fuse.0]\nhousing_mass_kg = 1.5\nk_intact = 1e9\nbreak_load_N = 600.0\n")
    (st,) = fuse_states(fem.load(path), 3, 30000.0)
    assert st["forward_synchronous_rpm"] == [] and st["fuse_stiffness_N_per_m"] == {"0": 0.0}
    assert st["note"].startswith("not computed: fuse #0 has stiffness 0 after this break"), st["note"]


@pytest.fixture(scope="module")
def fused_scenario(engine_folder):
    """The textbook engine's blade-loss scenario with bearing #0's housing on a fuse (1.5 kg, 1e9 N/m, break at
    600 N, 1e7 N/m after)."""
    _engine(engine_folder, "engine_fused.toml", FUSE.format(mass=1.5, k=1e9, load=600.0, kb=1e7))
    sc = engine_folder / "fused_blade_loss.toml"
    sc.write_text('[scenario]\nextends = "blade_loss.toml"\nname = "fused"\nengine = "engine_fused.toml"\n'
                  '[templates]\nbearing = ["0", "5"]\nrubring = ["0", "5"]\nfuse = ["0"]\n'
                  '[algorithm]\norder = ["rotor", "bearing{bearing}", "damper{bearing}", "rubring{rubring}", '
                  '"fuse{fuse}", "thermal{bearing}"]\n'
                  '[outputs]\nrecord = ["fuse0.F_support", "fuse0.F_rotor", "fuse0.broken"]\n')
    return str(sc)


def test_a_fused_engine_breaks_its_fuse_in_a_run(fused_scenario):
    """1 500 N of blade loss at 0.01 s on the fused textbook engine: the fuse breaks once, at its load, soon after
    the blade loss; the force it passes to the hub is the opposite of the force on the housing."""
    from rotorcosim.master.api import simulate

    res = simulate(fused_scenario, duration=0.015, figures=False, progress=False)
    (ev,) = res.summary["events"]
    assert ev["component"] == "fuse0" and ev["kind"] == "break" and 0.01 < ev["t_s"] < 0.012
    assert ev["values"]["F_elastic_N"] == pytest.approx(600.0, rel=1e-3)
    f, g = res["fuse0.F_support"], res["fuse0.F_rotor"]
    assert np.array_equal(f, -g[:, :2])
    assert np.asarray(res["fuse0.broken"]).reshape(-1)[-1] == 1.0


@pytest.mark.slow
def test_the_paper_engine_with_its_fuse_intact_is_the_paper_engine():
    """(~15 s of CPU: the paper engine's casing model built and solved twice, slow.) components/rotor/data/engine_fuse.toml (the paper's engine extended by a fuse under bearing #0's housing,
    half of hub h0's mass on it): intact, its two lowest forward critical speeds within 0.05 % of the paper
    engine's (8 497 / 10 199 against 8 500 / 10 200 rev/min); broken (2.0e6 N/m), the mode of bearing #0 at
    5 581 rev/min, below the running speed (the values its comments and the scenario give)."""
    root = fem.DEFAULT_FILE.parent
    paper = _forward(root / "engine.toml")
    fused = _forward(root / "engine_fuse.toml")
    assert fused[:2] == pytest.approx(paper[:2], rel=5e-4)
    (broken,) = fuse_states(fem.load(root / "engine_fuse.toml"), 3, 30000.0)
    assert broken["forward_synchronous_rpm"][0] == pytest.approx(5581.0, abs=1.0)


@pytest.mark.slow
def test_blade_loss_fuse_breaks_in_the_release_transient():
    """blade_loss_fuse over its first 12 ms (~8 s of CPU, most in the generic loop, slow): the 14 252 N release at
    0.01 s breaks the fuse within a millisecond (0.0105 s measured), at its 5 000 N."""
    from rotorcosim.master.api import simulate

    res = simulate("blade_loss_fuse", duration=0.012, figures=False, progress=False)
    (ev,) = [e for e in res.summary["events"] if e.get("component") == "fuse0"]
    assert ev["kind"] == "break" and 0.01 < ev["t_s"] < 0.011
    assert ev["values"]["F_elastic_N"] == pytest.approx(5000.0, rel=1e-3)
    # the comparison without the fuse, run over the same 12 ms: both sides of every quantity at #0 and #5, the
    # force into the casing at #0 with the fuse the fuse's own (the largest it carried, at least its break load)
    fc = res.summary["fuse_comparison"]
    assert fc["without_fuse_scenario"] == "blade_loss_rundown" and fc["duration_s"] == pytest.approx(0.012)
    for b in ("0", "5"):
        for q in ("casing_force_peak_N", "max_contact_load_peak_N", "max_contact_stress_peak_MPa"):
            assert fc["bearings"][b][q]["with_fuse"] > 0.0 and fc["bearings"][b][q]["without_fuse"] > 0.0
    assert fc["bearings"]["0"]["casing_force_peak_N"]["with_fuse"] == res.summary["casing_force_peak_N"]["0"]
    assert res.summary["casing_force_peak_N"]["0"] >= 5000.0


@pytest.mark.parametrize("value, message", [
    ("fuse0.break_load=0", "fuse0.break_load must be a finite number > 0 (N), got 0"),
    ("fuse0.k_broken=2e9", "fuse0.k_broken must be within [0, k_intact"),
    ("fuse0.bumper_clearance=-1e-3", "fuse0.bumper_clearance must be >= 0"),
    ("fuse0.event_tolerance=1e-4", "fuse0.event_tolerance: 0.0001 s must be within (0, 5e-06 s]"),
    # its bisection never ended: the bracket stops shrinking at a float64 step's last bits
    ("fuse0.event_tolerance=1e-300", "fuse0.event_tolerance: 1e-300 s is below 1.78e-20 s, the step 5e-06 s bisected"),
])
def test_bad_fuse_values_of_an_engine_run_are_one_line(fused_scenario, tmp_path, value, message):
    """The engine route's bad inputs, set on the run: one line naming the key, exit 2, nothing written."""
    out = tmp_path / "o"
    r = subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", "run", fused_scenario, "--set", value,
                        "--set", "rotor.t_blade_loss=0.0005", "--duration", "0.001", "--quiet", "--no-figures", "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert message in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not out.exists() or not any(out.iterdir())


def test_an_engine_file_extends_another(tmp_path):
    """[engine] extends: the base's data with the file's tables laid over it, key by key (engine_fuse.toml keeps
    engine.toml's spools and hub h0's z_mm, changes h0's mass and adds [fuse.0]); the digest differs from the
    base's; a base that does not exist, and a chain that loops, are one-line errors naming the file."""
    root = fem.DEFAULT_FILE.parent
    base, d0 = fem.load_data(root / "engine.toml")
    data, d1 = fem.load_data(root / "engine_fuse.toml")
    assert data["spool"] == base["spool"] and d1 != d0 and d1 == fem.file_digest(root / "engine_fuse.toml")
    assert data["casing"]["hubs"]["h0"] == {"z_mm": 90, "mass": 1.5}
    assert "extends" not in data["engine"] and data["fuse"]["0"]["break_load_N"] == 5000.0
    (tmp_path / "a.toml").write_text('[engine]\nformat = 1\nextends = "missing.toml"\n')
    with pytest.raises(FileNotFoundError, match="missing.toml"):
        fem.load_data(tmp_path / "a.toml")
    # a loop is said as one (it was "extends chain longer than 8 files")
    (tmp_path / "b.toml").write_text('[engine]\nformat = 1\nextends = "b.toml"\n')
    b = (tmp_path / "b.toml").resolve()
    with pytest.raises(ValueError) as err:
        fem.load_data(tmp_path / "b.toml")
    assert str(err.value) == f"rotor model file {tmp_path / 'b.toml'}: [engine] extends loops back on itself ({b} -> {b})"
    for i in range(10):   # a chain of 10 files: the 9th may extend no further
        (tmp_path / f"c{i}.toml").write_text(f'[engine]\nformat = 1\nextends = "c{i + 1}.toml"\n')
    with pytest.raises(ValueError, match=r"c8\.toml: \[engine\] extends chain longer than 8 files"):
        fem.load_data(tmp_path / "c0.toml")


@pytest.mark.slow
def test_check_engine_lists_the_broken_fuse_critical_speeds(engine_folder, tmp_path):
    """(~10 s of CPU: the critical speeds, damped peaks and Campbell diagram of both states; slow.) check-engine of an engine with a fuse: its report lists the forward critical speeds with the fuse broken
    (and --json holds them under critical_speeds.fuse_states), next to the intact engine's."""
    import json

    path = _engine(engine_folder, "listed.toml", FUSE.format(mass=1.5, k=1e9, load=600.0, kb=1e7))
    r = subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", "check-engine", path, "--json",
                        "--campbell", str(tmp_path / "c.png")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    (st,) = json.loads(r.stdout)["critical_speeds"]["fuse_states"]
    assert st["label"] == "fuse broken" and st["forward_synchronous_rpm"][0] == pytest.approx(3707.0, abs=2.0)
    assert (tmp_path / "c.png").stat().st_size > 0


@pytest.mark.slow
def test_blade_loss_fuse_staggered_against_monolithic_over_60_s(tmp_path):
    """blade_loss_fuse (without its comparison run) staggered and monolithic over its first 60 s (the release,
    the break, 15 s at full speed, the fuel cut and the rundown through both post-fuse crossings; ~310 s of CPU,
    271 of them the monolithic run: slow): every Table 4 result (0.18 % measured) and every crossing's peak values
    (0.43 %) within 2 %, the break at the same time within one coupled step of 5 us (the same time, measured),
    every crossing's peak speed within 1 % (the post-fuse one, a broad peak passed slowly through held
    intervals: 5 820 rev/min staggered against 5 792 monolithic, 0.48 %, measured; 3.5 % while the response
    track read a restart's first revolutions, the orbit the rotor was frozen on, at the restart's speed)."""
    import json

    from rotorcosim.cases.rundown import compare as rc
    from rotorcosim.master.api import load_scenario

    sc = load_scenario("blade_loss_fuse")
    for key in ("without_fuse", "without_fuse_set"):
        sc.extra["results"].pop(key)
    t = rc.compare_rundown(sc, 60.0, tmp_path / "c", figures=False)
    assert t["within_2pct"]["results"], t["largest_error_pct"]
    assert t["within_2pct"]["crossing_peaks"], t["largest_error_pct"]
    assert t["largest_error_pct"]["crossing_speeds"] < 1.0, t["largest_error_pct"]
    breaks = []
    for run in ("staggered", "monolithic"):
        s = json.loads((tmp_path / "c" / run / "summary.json").read_text())
        (ev,) = [e for e in s["events"] if e.get("component") == "fuse0"]
        breaks.append(ev["t_s"])
    assert abs(breaks[0] - breaks[1]) <= 5e-6


def test_a_fuse_template_id_the_engine_does_not_describe_is_named(tmp_path):
    """``[templates] fuse = ["7"]`` on an engine whose only fuse is [fuse.0]: one line saying the engine has no
    [fuse.7] and which fuses it has (it said "[fuse.7] k_intact missing", as if a key of a fuse it had were
    left out), exit 2, nothing written."""
    f = tmp_path / "s.toml"
    f.write_text('[scenario]\nextends = "blade_loss_fuse"\nname = "f7"\n\n[templates]\nfuse = ["7"]\n')
    out = tmp_path / "o"
    r = subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", "run", str(f), "--duration", "0.001",
                        "--quiet", "--no-figures", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    assert "no [fuse.7] (the fuse ids it has: 0)" in r.stderr and "missing" not in r.stderr, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not out.exists()


def test_a_run_of_a_fuse_without_its_housing_mass_names_the_key_missing(engine_folder):
    """A run (not check-engine) of an engine whose [fuse.0] leaves out housing_mass_kg: one line naming the key
    as missing (it read 'must be a finite number > 0, got None')."""
    path = _engine(engine_folder, "no_mass.toml", "\n[fuse.0]\nk_intact = 1e9\nbreak_load_N = 600.0\n")
    with pytest.raises(ValueError, match=r"\[fuse\.0\] housing_mass_kg missing \(a finite number > 0"):
        fem.load(path)
