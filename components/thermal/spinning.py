"""The bearing thermal network at a varying speed (``thermal.network_spinning``): the shaft speed is an input.

The same network as component.ThermalNetwork, with ``Omega`` [rad/s] (the spool's speed, components/spool) as an
input instead of the constant ``omega``: the network's speed terms (the shaft-end convection of R_sa, the oil
convection coefficients, the rub heat's partition between the ring and the shaft, geometry.py) are rebuilt at the
input speed whenever it has left the one they were built for by more than ``speed_tolerance`` (relative; the
kernel hands that step to Python, status PYTHON). A stopped shaft keeps the speed terms of the last speed above
1 % of ``omega`` (the correlations have no zero-speed limit). At Omega = omega every number is the constant-speed
network's, bit for bit.
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..contract import ContractError, Variable
from ..kernels import PYTHON, port_tuple
from ..numba_internals import kernel_jit
from .component import ThermalNetwork
from .kernel import tm_step
from .geometry import build_network

SpinThermalParams = namedtuple("SpinThermalParams", "base spin")
_IN = port_tuple("ThermalNetwork", "Inputs", ("P_drag", "P_sfd", "P_rub"))
_OUT = port_tuple("ThermalNetwork", "Outputs", ("eps", "T_oil", "T_sfd_oil", "T_inner_race", "T_ball",
                                                 "T_outer_race", "T_nodes"))


@kernel_jit
def spinning_step(s, p, u, y, t, h):
    """PYTHON when the speed left the network's by more than the tolerance; else the network's step."""
    w = u.Omega[0]
    if not math.isfinite(w):
        return 2
    if abs(w - p.spin[0]) > p.spin[1] * abs(p.spin[0]) and abs(w) > p.spin[2]:
        return PYTHON
    return tm_step(s, p.base, _IN(u.P_drag, u.P_sfd, u.P_rub),
                   _OUT(y.eps, y.T_oil, y.T_sfd_oil, y.T_inner_race, y.T_ball, y.T_outer_race, y.T_nodes), t, h)


class SpinningThermalNetwork(ThermalNetwork):
    """The thermal network with the shaft speed as an input (module docstring)."""

    description = ThermalNetwork.description + " (shaft speed as an input)"
    #: the speed is the Omega input; omega is only the reference of the speed terms' tables, free to differ
    fixed_speed = None
    variables = ThermalNetwork.variables + (
        Variable("speed_tolerance", "parameter", unit="1", start=0.02,
                 description="relative speed change that rebuilds the network's speed terms"),
        Variable("Omega", "input", 1, "rad/s", "shaft (spool) speed"),
    )

    def setup(self, t0=0.0):
        if not (math.isfinite(self.p["speed_tolerance"]) and self.p["speed_tolerance"] > 0.0):
            raise ContractError(f"{self.name}.speed_tolerance must be > 0, got {self.p['speed_tolerance']}")
        super().setup(t0)
        p = self.p
        self._spin = np.array([float(p["omega"]), float(p["speed_tolerance"]), 0.01 * abs(float(p["omega"]))])

    def _rebuild(self, w):
        p = self.p
        try:
            self.network = build_network(
                self._bearing, w, p["T_ambient"], p["T_supply"], p["drag_inner_fraction"],
                p["contact_race_fraction"], p["rub_shaft_fraction"], p["bearing_oil_flow"], p["sfd_oil_flow"],
                p["rub_ring_housing_fraction"])
        except ValueError as exc:
            raise ContractError(f"{self.name}: {exc}") from None
        self._spin[0] = w
        self._kernel_h = None

    STEP = staticmethod(spinning_step)

    def kernel_params(self):
        return SpinThermalParams(self._kernel_p, self._spin)

    def kernel_status(self, status, t, h):
        if status == PYTHON:
            self._rebuild(float(self.u["Omega"][0]))
            self.kernel_prepare(h)
            status = self.STEP(*self.kernel_args(), t, h)
            if status == 0:
                return
        if not np.all(np.isfinite(self.u["Omega"])):
            raise ContractError(f"{self.name}: non-finite input Omega at t = {t + h:.9g} s")
        super().kernel_status(status, t, h)
