"""Divergence is caught at the step that produced it, naming the component, the port and the time."""
import numpy as np
import pytest

from rotorcosim.components.contract import Component, Variable
from rotorcosim.components.registry import create
from rotorcosim.master.core.algorithm import SimulationDiverged
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation
from rotorcosim.master.core.system import Connection, System


class Source(Component):
    """A force that turns non-finite at ``t_bad`` (NaN or inf, as ``bad`` says)."""

    variables = (Variable("t_bad", "parameter", unit="s", start=1.0),
                 Variable("bad", "parameter", start=0.0),
                 Variable("F", "output", unit="N"), Variable("aux", "output", unit="1", size=3))

    def do_step(self, t, h):
        self.time = t + h
        self.y["F"] = np.array([self.p["bad"] if self.time >= self.p["t_bad"] - 1e-12 else 1.0])


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("order", [["src", "m"], ["m", "src"]])
def test_named_at_the_producing_step(bad, order):
    src = Source("src", {"t_bad": 0.0123})
    src.p["bad"] = bad
    m = create("testing.mass", "m", {"k": 4.0})
    sim = Simulation(System({"src": src, "m": m}, [Connection("src.F", "m.F")]), order=order)
    with pytest.raises(SimulationDiverged) as info:
        sim.run(Timeline([Interval("TM", 1.0, 1e-4)]))
    msg = str(info.value)
    # the producer, its port and the step's end time; not the consumer, not 64 steps later
    assert msg.startswith("src.F is not finite at t = 0.0123 s (after src's step from t = 0.0122 s)"), msg


def test_huge_but_finite_values_are_not_divergence():
    src = Source("src", {"t_bad": 0.005})
    src.p["bad"] = 1e300
    m = create("testing.mass", "m", {"m": 1e300, "k": 4.0})
    sim = Simulation(System({"src": src, "m": m}, [Connection("src.F", "m.F")]))
    sim.run(Timeline([Interval("TM", 0.01, 1e-3)]))
    assert sim.t == pytest.approx(0.01)


def test_overflow_ends_in_the_divergence_message_only(tmp_path, capsys):
    """C = R = 1e308 overflows inside the thermal node (numpy scalars): the engine's finiteness check names the
    port; numpy's RuntimeWarning must not come first (a stray line of source text on the command line). Made an
    error here, so that a warning would change the outcome."""
    import warnings

    from rotorcosim.master.cli import main

    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        rc = main(["run", "toy_thermomechanical", "--set", "node.C=1e308", "--set", "node.R=1e308",
                   "--duration", "0.01", "--out", str(tmp_path / "o"), "--quiet"])
    err = capsys.readouterr().err
    assert rc == 1 and err.count("\n") == 1, err
    assert "node.T is not finite at t = 0.002 s" in err and "Warning" not in err, err
    assert err.count("the simulation diverged") == 1, err   # said first, not again at the message's end
    assert (tmp_path / "o" / "summary.json").exists() and (tmp_path / "o" / "timeseries.h5").exists()


@pytest.mark.parametrize("engine", ["compiled", "python"])
def test_a_bearing_whose_state_blows_up_is_a_divergence(tmp_path, capsys, engine):
    """A blade-loss force of 1e12 N on new-engine's rotor blows the ball bearing's state up: the run stopped as
    'a component failed' (ComponentFailed), not as the divergence it is; it keeps what it recorded."""
    import json

    from rotorcosim.master.cli import main

    assert main(["new-engine", str(tmp_path / "X")]) == 0
    capsys.readouterr()
    out = tmp_path / "o"
    rc = main(["run", str(tmp_path / "X" / "blade_loss.toml"), "--set", "rotor.F_unbalance=1e12", "--duration",
               "0.02", "--engine", engine, "--quiet", "--no-figures", "--out", str(out)])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert rc == 1 and len(err) == 1 and err[0].startswith(
        "rotorcosim run: the simulation diverged: bearing0 failed in do_step at t = 0.009995 s: bearing0: the bearing "
        "state became non-finite at t = 0.01 s"), err
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "failed" and summary["error"].startswith("SimulationDiverged: bearing0")
    assert (out / "timeseries.h5").is_file()
