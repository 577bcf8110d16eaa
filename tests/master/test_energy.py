"""The power-bond energy residual: zero for an exact coupling, O(h) for held inputs."""
from rotorcosim.master.observer.energy import EnergyResidual
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation

from tests.helpers.systems import two_masses


def residual(h):
    s = two_masses()
    obs = EnergyResidual([("m1.F", "m1.v")])
    Simulation(s, order=["m1", "m2"], observers=[obs]).run(Timeline([Interval("TM", 1.0, h)]))
    return abs(obs.relative()["m1.F / m1.v"])


def test_energy_residual_first_order():
    """Gauss-Seidel with held inputs on two masses: the residual of the spring bond halves with the step."""
    r1, r2, r3 = residual(2e-3), residual(1e-3), residual(5e-4)
    assert r1 > 0
    assert 1.7 < r1 / r2 < 2.3 and 1.7 < r2 / r3 < 2.3
