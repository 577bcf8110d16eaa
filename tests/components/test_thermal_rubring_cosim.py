"""The rub ring and the thermal network in the master (TM/TO staggered timeline): the rub power of a prescribed
circular orbit reaches the network with its energy intact."""
import math

import numpy as np
import pytest

from rotorcosim.components.contract import Component, Variable
from rotorcosim.components.registry import register
from rotorcosim.components.thermal.component import ThermalNetwork
from rotorcosim.master.scenario.build import build_simulation, parse, schedule_of

OMEGA = 16000 * 2 * math.pi / 60
ORBIT = 0.6e-3


@register("testing.circular_orbit")
class CircularOrbit(Component):
    """Rotor node on a prescribed forward circular orbit at the spin speed; housing at rest."""

    variables = (
        Variable("X_rotor", "output", 2, "m"), Variable("V_rotor", "output", 2, "m/s"),
        Variable("X_housing", "output", 2, "m"), Variable("V_housing", "output", 2, "m/s"),
    )
    preferred_step = 1e-5

    def setup(self, t0=0.0):
        super().setup(t0)
        self._put(t0)

    def _put(self, t):
        c, s = math.cos(OMEGA * t), math.sin(OMEGA * t)
        self.y["X_rotor"] = np.array([ORBIT * c, ORBIT * s])
        self.y["V_rotor"] = np.array([-ORBIT * OMEGA * s, ORBIT * OMEGA * c])

    def do_step(self, t, h):
        self._put(t + h)
        self.time = t + h


def test_rub_power_of_a_circular_orbit_heats_the_network_like_the_held_power():
    """By hand (rub ring k = 2.2e7 N/m set here, defaults mu = 0.2, R = 25.4 mm, c = 0.508 mm): F_n = 2.2e7 * 0.092e-3 =
    2024 N, P_rub = 0.2 * 2024 * OMEGA (0.0254 + 0.0006) = 17 634 W, constant on the orbit. Through the master
    (TM 20 ms at 1e-5 s, thermal at 1 ms with mean averaging; TO 5 s at 0.1 s with the RMS hold; TM 20 ms) the
    network must end where a stand-alone network under the same constant powers ends after 5.04 s (1e-9 relative
    in the temperature rises)."""
    p_hand = 0.2 * 2.2e7 * (ORBIT - 0.508e-3) * OMEGA * (0.0254 + ORBIT)
    data = {
        "scenario": {"name": "rub_thermal"},
        "components": {
            "orbit": {"implementation": "testing.circular_orbit"},
            "rubring0": {"implementation": "rubring.contact", "parameters": {"bearing": 0, "stiffness": 2.2e7}},
            "thermal0": {"implementation": "thermal.network", "parameters": {"bearing": 0}, "step": 1e-3},
        },
        "connections": [
            {"from": f"orbit.{p}", "to": f"rubring0.{p}"} for p in ("X_rotor", "V_rotor", "X_housing", "V_housing")
        ] + [{"from": "rubring0.P_rub", "to": "thermal0.P_rub"}],
        "inputs": {"thermal0.P_drag": 350.0, "thermal0.P_sfd": 600.0},
        "algorithm": {"kind": "gauss-seidel", "order": ["orbit", "rubring0", "thermal0"]},
        "schedule": {"kind": "timeline", "step": 1e-5, "thermal_step": 0.1, "speed_rpm": 16000.0, "hold": "rms",
                     "hold_cycles": 5, "intervals": [{"phase": "TM", "duration": 0.02}, {"phase": "TO", "duration": 5.0},
                                                     {"phase": "TM", "duration": 0.02}]},
    }
    sc = parse(data)
    sim = build_simulation(sc)
    report = sim.run(schedule_of(sc))
    assert report.t_end == pytest.approx(5.04)
    rub = sim.system.components["rubring0"]
    assert rub.y["P_rub"][0] == pytest.approx(p_hand, rel=1e-12)
    net = sim.system.components["thermal0"]

    alone = ThermalNetwork("alone", {"bearing": 0})
    alone.setup(0.0)
    alone.set_inputs({"P_drag": [350.0], "P_sfd": [600.0], "P_rub": [p_hand]})
    alone.do_step(0.0, 5.04)
    rise_cosim = net.y["T_nodes"] - 303.15
    rise_alone = alone.y["T_nodes"] - 303.15
    assert np.max(np.abs(rise_cosim - rise_alone) / rise_alone) < 1e-9
