"""The up-front estimate of a run's cost (master/schedule/budget.py): what it prices against what the run does,
the progress bar's first time left on a fresh machine, and the warnings a run gives before it starts.

The estimate is the run's base steps times a price per step of each phase (plus set-up). Its prices are measured
by ``bench/bench_estimate.py`` (part 3 compares the estimate with the CPU time of the runs below: within a factor
2 on a quiet machine); a test here asserts no time, since a loaded machine decides that and nothing else would.
What the suite checks is what the estimate can get wrong whatever the machine: the steps it prices are the steps
the run takes, and the loop it prices is the loop the run took. The cases are those the estimate used to get
wrong: the FE damper (``--swap damper0=damper.fe``, its cost growing with its mesh), FMUs in process and out of
process, an SSP archive, the monolithic schedule, the staggered one (the main job's timeline, cut), the compiled
and the Python loop.
"""
import json
import threading

import pytest

import rotorcosim
from rotorcosim.components.contract import COUPLED
from rotorcosim.master.core.phases import Phases
from rotorcosim.master.observer.progress import Progress
from rotorcosim.master.schedule import budget
from rotorcosim.master.schedule.timeline import Interval, Timeline

@pytest.fixture(scope="module")
def toy_fmus(tmp_path_factory):
    """The toy scenario's two components as FMUs, and the toy scenario as an SSP archive of them."""
    from tests.helpers.fmus import export_toy
    from rotorcosim.master.cli import main

    d = tmp_path_factory.mktemp("estimate_fmus")
    fmus = export_toy(d / "toy")
    assert main(["export-ssp", "toy_thermomechanical", "--out", str(d / "toy.ssp")]) == 0
    return {"osc": fmus["osc"], "node": fmus["node"], "ssp": d / "toy.ssp"}


CASES = {
    "staggered, compiled (main job's timeline)": ["blade_loss_2850", "--duration", "24.2"],
    "monolithic, compiled": ["blade_loss_2850", "--schedule", "monolithic", "--duration", "0.05"],
    "monolithic, Python loop": ["blade_loss_2850", "--schedule", "monolithic", "--duration", "0.005",
                                "--engine", "python"],
    "FE damper": ["blade_loss_2850", "--swap", "damper0=damper.fe", "--set", "damper0.n_theta=64",
                  "--set", "damper0.n_z=32", "--schedule", "monolithic", "--duration", "0.001"],
    "FMUs": ["toy_thermomechanical", "--swap", "osc={osc}", "--swap", "node={node}", "--schedule", "monolithic",
             "--duration", "5"],
    "FMUs out of process": ["toy_thermomechanical", "--swap", "osc={osc}", "--fmu-process", "--schedule",
                            "monolithic", "--duration", "2"],
    "SSP archive, staggered": ["{ssp}", "--duration", "30"],
}


@pytest.mark.parametrize("case", list(CASES))
def test_estimate_prices_the_steps_and_the_loop_of_the_run(case, toy_fmus, tmp_path):
    from rotorcosim.master.cli import main

    args = [a.format(**toy_fmus) for a in CASES[case]]
    out = tmp_path / "run"
    assert main(["run", *args, "--no-figures", "--quiet", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["estimate"]["steps"] == sum(iv["steps"] for iv in s["timeline"]) > 0, case
    assert s["estimate"]["engine"] == s["engine"], case
    # the price of a base step of each phase the run held
    assert set(s["estimate"]["step_cost_us"]) == {iv["phase"] for iv in s["timeline"]}, case


def test_fe_damper_cost_follows_its_mesh():
    """The paper's 128 x 64 film mesh costs (8192 / 2048)^1.5 = 8 times the 64 x 32 one per step (the sparse
    solve's growth; bench/bench_estimate.py measured 21 ms at 128 x 64), and the swap takes the run off the
    compiled loop."""
    sc = rotorcosim.load_scenario("blade_loss_2850").swap("damper0", "damper.fe")
    tl = Timeline([Interval("TM", 0.01, 5e-6)])
    fine = budget.estimate(sc, tl)
    coarse = budget.estimate(sc.set({"damper0.n_theta": 64, "damper0.n_z": 32}), tl)
    assert fine["engine"] == "python" and budget.estimate(rotorcosim.load_scenario("blade_loss_2850"),
                                                          tl)["engine"] == "compiled"
    assert fine["step_cost_us"]["TM"] > 7 * coarse["step_cost_us"]["TM"]
    assert fine["step_cost_us"]["TM"] == pytest.approx(21e3, rel=0.2)


class _Clock:
    def __init__(self):
        self.now = 0.0

    def __call__(self):
        return self.now


class _Sim:
    """What Progress reads of a simulation: its clock, phases (the default names) and first compilations."""

    def __init__(self):
        self.t = 0.0
        self.first_compiled = threading.Event()
        self.phases = Phases()
        self.phase, self.phase_name = COUPLED, "TM"


class _Used:
    def __init__(self, phase, steps):
        self.phase, self.steps = phase, steps


def test_first_time_left_of_a_cold_run_excludes_the_compilation():
    """A fresh machine: the first TM interval's first steps wait 20 s for numba, then every TM step costs 10 us
    and every TO step 100 us. The time left shown once the compilations end is within a factor 2 of the true
    time left (the prior from the estimate until 0.5 s are measured, then the measured cost), where a rate
    measured over the compilation was 100 times too long."""
    plan = Timeline([Interval("TM", 0.5, 5e-6), Interval("TO", 23.85, 0.1), Interval("TM", 0.1, 5e-6)])
    true_tm, true_to = 10e-6, 100e-6
    sim, clock = _Sim(), _Clock()
    p = Progress(plan.duration, disable=True, prior={"TM": 14e-6, "TO": 60e-6})
    p.start(sim, plan)
    p._clock = clock
    p.interval_start(sim, "TM", 5e-6)
    clock.now += 20.0  # compiling
    sim.first_compiled.set()
    sim.t = 256 * 5e-6
    clock.now += 256 * true_tm
    p.step(sim, sim.t)  # the first block of steps after the compilations
    truth = (100_000 - 256) * true_tm + 239 * true_to + 20_000 * true_tm
    shown = p.remaining(sim.t)
    assert 0.5 <= shown / truth <= 2.0, (shown, truth)
    # later in the interval, measured (more than SETTLE_S of steps): the measured price
    n = 80_000
    sim.t += n * 5e-6
    clock.now += n * true_tm
    shown = p.remaining(sim.t)
    # the TM steps at their measured price, the TO ones (not measured yet) at the prior
    truth = (100_000 - 256 - n) * true_tm + 239 * 60e-6 + 20_000 * true_tm
    assert shown == pytest.approx(truth, rel=0.02)
    p.interval_end(sim, _Used("TM", 100_000))
    assert p.cost_wall["TM"] < 1.0  # the 20 s of compilation are no part of the TM price


def test_simulate_from_python_says_what_it_estimates(capsys, monkeypatch):
    """A long run does not start silently from Python either (the command line's line, on stderr)."""
    monkeypatch.setattr(budget, "WARN_S", 0.0)
    rotorcosim.simulate("toy_thermomechanical", duration=0.05, figures=False)
    err = capsys.readouterr().err
    assert "toy_thermomechanical: 50 steps, estimated" in err and "of wall time (python engine)" in err
    # the automatic schedule is priced as all coupled steps: a bound, said so (a diversion's 200 s: "20 min",
    # 54 s taken)
    rotorcosim.simulate("toy_thermomechanical", duration=0.05, schedule="auto", figures=False)
    err = capsys.readouterr().err
    assert "toy_thermomechanical: 50 steps, at most" in err and "estimated" not in err


def test_a_parameter_off_by_a_unit_factor_is_named_with_its_range(capsys):
    """The paper's O-ring, 5254 N/mm, given as 5254 N/m: one line naming the parameter, its plausible range and
    the likely slip; the shipped value draws no warning."""
    sc = rotorcosim.load_scenario("blade_loss_2850")
    rotorcosim.simulate(sc.set({"damper0.k_spring": 5254.0}), duration=0.002, figures=False)
    lines = [ln for ln in capsys.readouterr().err.splitlines() if "plausible" in ln]
    assert lines == ["blade_loss_2850: warning: damper0.k_spring = 5254 N/m is outside its plausible range 1e+05 "
                     "to 1e+08 N/m: 1000 times too small? (a value in N/mm where N/m is meant)"]
    rotorcosim.simulate(sc, duration=0.002, figures=False)
    assert "plausible" not in capsys.readouterr().err


def test_a_rub_ring_radius_in_mm_is_warned(tmp_path, capsys):
    """An engine's [rubring.0] radius_mm = 3000 (3 m on a 60 mm shaft: metres written as mm twice over) ran
    without a word; the rub ring and the thermal network that takes its heat now warn, naming the slip."""
    from rotorcosim.master.cli import main

    assert main(["new-engine", str(tmp_path / "X")]) == 0
    f = tmp_path / "X" / "engine.toml"
    f.write_text(f.read_text().replace("radius_mm = 30.0", "radius_mm = 3000.0"))
    capsys.readouterr()
    assert main(["run", str(tmp_path / "X" / "blade_loss.toml"), "--duration", "0.02", "--quiet", "--no-figures",
                 "--out", str(tmp_path / "o")]) == 0
    lines = [ln for ln in capsys.readouterr().err.splitlines() if "plausible" in ln]
    assert lines == [f"my_engine_blade_loss: warning: {c}.{p} = 3 m is outside its plausible range 0.002 to 1 m: 1000 "
                     "times too large? (a value in mm where m is meant)"
                     for c, p in (("thermal0", "rub_radius"), ("rubring0", "radius"))], lines


def test_engine_compiled_is_refused_before_any_run_output(capsys, monkeypatch, tmp_path):
    """--engine compiled with a component that has no kernel (the FE damper) is refused before the estimate's
    line, the build and the output folder: it was refused only at the first thermo-mechanical interval."""
    from rotorcosim.master.compiled.choice import CompiledUnavailable

    monkeypatch.setattr(budget, "WARN_S", 0.0)
    sc = rotorcosim.load_scenario("blade_loss_2850").swap("damper0", "damper.fe")
    with pytest.raises(CompiledUnavailable, match="component damper0 .FEDamper. has no compiled kernel"):
        rotorcosim.simulate(sc, duration=0.02, engine="compiled", out=tmp_path / "o")
    assert capsys.readouterr().err == ""
    assert not (tmp_path / "o").exists()
    rotorcosim.simulate("toy_thermomechanical", duration=0.05, figures=False, engine="python")  # not refused
