"""The bearing thermal network component (paper section 2.3: Fig. 5, Table 1, eqs. (12)-(15)).

Nine lumped nodes per bearing (``T_nodes`` order: shaft, inner_race, lub_inner, ball, lub_outer, outer_race,
journal, sfd_oil, housing; the journal sleeve's inner radial shells are further state nodes, geometry.py), eq. (12)
at each, the Table 1 resistances and the heat masses from the geometry (geometry.py), heat sources from the three
power inputs, and the growths of eqs. (13)-(15) (growth.py).

Geometry, as parameters (the component reads no other component's): the bearing's ``bore``,
``outside_diameter``, ``width``, ``balls``, ``ball_diameter``, ``contact_angle``, the damper's ``damper_radius``,
``damper_length``, ``damper_clearance`` and the rub ring's ``rub_radius``; ``bearing = 0 | 5`` gives the defaults
of the paper's Table 3 and each one set replaces its default. What Table 3 does not give (``shaft_length``,
``housing_wall``, ``housing_length`` = 2 ``damper_length``, ``rub_radius`` = ``bore``/2) follows data/thermal.toml
[defaults] (sources: docs/explanation/paper-components.md). A scenario gives a thermal network the values it gives
the bearing, damper and rub ring whose heat it takes (the blade-loss case checks that before a run).

Added to the paper's network (geometry.py, data/thermal.toml): the oil-wetted convection between the races / balls
and the bearing lubricant (Harris's film coefficient), the renewal of the lubricant by the oil jet and of the damper
oil by its feed (rho c_p Q to the supply), the oil-wetted bearing-chamber cooling of the housing, and the Blok
partition of the rub heat between the rotor and the ring/housing.

Inputs (W), each the mean over the step (so the heat of a step is input x h, energy-preserving):
``P_drag`` the bearing drag-torque power, split between the inner and outer ball/race contacts (half each by
default) and at each contact between race and ball (half each); ``P_sfd`` the damper film's viscous power, into the
squeeze-film oil; ``P_rub`` the rub friction power of eq. (11), ``rub_shaft_fraction`` of it into the shaft node (the
rotor at the ring; default the Blok partition, ~1-2 %) and the rest into the housing node (which carries the ring).

Outputs: ``eps`` = [eps_i, eps_e, eps_b] (m), the radial growths of the inner raceway, the outer raceway and the
ball radius, positive = expansion, from the temperature rise over ``T_initial`` (eqs. 14, 13, 15; see growth.py);
``T_oil``, the bearing oil temperature for the drag-torque viscosity = the mean of the two lubricant nodes
(lub_inner, lub_outer): the oil in the bearing, which (well mixed) is also the temperature at which the jet oil
leaves it; ``T_sfd_oil`` the squeeze-film oil node; ``T_inner_race``, ``T_ball``, ``T_outer_race``;
``T_nodes`` all nine (K).

Integration: the exact solution for inputs held over the step (network.py, "exact", the default), with the step
matrices cached per step size, so that 1 ms thermo-mechanical steps and 0.1 s thermal-only steps are both stable
and exact for the held powers; ``method = "backward-euler"`` is available for comparison.
"""
from __future__ import annotations

import math

import numpy as np

from ..contract import ContractError, Variable
from ..kernels import KernelComponent
# ``bearing`` = NO_RECORD: no record of the paper's Table 3; the geometry is given (the start values: bearing
# #0's record, its defaults filled in)
from ..records import NO_RECORD, check_selection
from ..oil_fit import SOURCE, T_FLASH_K, T_POUR_K, check_oil_temperature
from ..speeds import PT_OMEGA
from ..validity import Check
from .geometry import (BEARINGS, BALL, IR, JOURNAL, LE, LI, NODES, OR, REQUIRED, SFD, SHAFT, THERMAL_DATA, bearing_data,
                       build_network, default_sources, radii)
from .growth import growths
from .kernel import ThermalParams, ThermalState, tm_step
from .network import METHODS

_SRC = default_sources()
_LMIN = 1e-3 / 60.0



def _port(name):
    return lambda y: y[name][:, 0]


#: the envelope (ThermalNetwork.validity): both oils inside the viscosity fit's range (components/oil_fit.py), which
#: the bearing's drag and the damper's film take these temperatures through
CHECKS = tuple(Check(f"{what} temperature", (port,), _port(port), limit, "K", SOURCE, bound=bound)
               for port, what in (("T_oil", "bearing oil"), ("T_sfd_oil", "squeeze-film oil"))
               for limit, bound in ((T_FLASH_K, "max"), (T_POUR_K, "min")))

#: the geometry parameters: (parameter, data-file key, SI per file unit)
GEOMETRY = (("bore", "bore_diameter_mm", 1e-3), ("outside_diameter", "outside_diameter_mm", 1e-3),
            ("width", "width_mm", 1e-3), ("balls", "n_balls", 1), ("ball_diameter", "ball_diameter_mm", 1e-3),
            ("contact_angle", "contact_angle_deg", math.pi / 180.0),
            ("damper_radius", "damper_radius_mm", 1e-3), ("damper_length", "damper_length_mm", 1e-3),
            ("damper_clearance", "damper_clearance_mm", 1e-3), ("shaft_length", "shaft_length_mm", 1e-3),
            ("housing_wall", "housing_wall_mm", 1e-3), ("housing_length", "housing_length_mm", 1e-3),
            ("rub_radius", "rub_ring_radius_mm", 1e-3))
_REC0 = bearing_data(0)
_DFLT = THERMAL_DATA["defaults"]
_DOC = "docs/explanation/paper-components.md"


def _table3(what: str) -> str:
    return f"{what} (default: the Table 3 record of `bearing`; set it for another bearing)"


class ThermalNetwork(KernelComponent):
    """Bearing thermal network of bearing #0 or #5 (nine nodes, eqs. 12-15)."""

    description = "Bearing thermal network (9 lumped nodes, Table 1 resistances) and thermal growths eqs. (13)-(15)"
    variables = (
        Variable("bearing", "parameter", unit="1", start=NO_RECORD, type="Integer",
                 description="which bearing of the paper's Table 3 (0 or 5) gives the geometry parameters' "
                             "defaults; -1 (default): none, the bearing's, damper's and rub ring's geometry is given "
                             "(a scenario takes it from its engine file)"),
        Variable("T_ambient", "parameter", unit="K", start=303.15, description="ambient temperature (30 C)"),
        Variable("T_initial", "parameter", unit="K", start=303.15,
                 description="initial temperature of all nodes, and the zero-growth reference of eqs. (13)-(15)"),
        Variable("T_supply", "parameter", unit="K", start=303.15,
                 description="temperature of the oil supplied to the bearing and the damper"),
        Variable("omega", "parameter", unit="rad/s", start=PT_OMEGA,
                 description="shaft speed, for the shaft-end convection of R_sa"),
        Variable("drag_inner_fraction", "parameter", unit="1", start=_SRC["drag_inner_fraction"],
                 description="share of the drag power at the inner ball/race contacts (rest at the outer ones)"),
        Variable("contact_race_fraction", "parameter", unit="1", start=_SRC["contact_race_fraction"],
                 description="share of a contact's heat entering the race (rest into the ball)"),
        Variable("rub_shaft_fraction", "parameter", unit="1", start=_SRC["rub_shaft_fraction"],
                 description="share of the rub power entering the shaft (rest into the housing carrying the ring);"
                             " < 0: the Blok partition of the data file (~1-2 %)"),
        Variable("rub_ring_housing_fraction", "parameter", unit="1", start=-1.0,
                 description="share of the ring's part of the rub power entering the housing node (rest stays in "
                             "the ring and casing, not modelled); < 0: the data-file value (0)"),
        Variable("bearing_oil_flow", "parameter", unit="m3/s", start=-1.0,
                 description="oil-jet flow through the bearing (renewal of the lubricant nodes); < 0: data/thermal.toml"
                             " [defaults] jet_L_per_min, 0 (none, as Table 1's network; the jet option's 2 L/min at"
                             f" #0 and 3 L/min at #5: {_DOC})"),
        Variable("sfd_oil_flow", "parameter", unit="m3/s", start=THERMAL_DATA["oil_flow"]["sfd_L_per_min"] * _LMIN,
                 description="squeeze-film damper oil flow (renewal of the SFD oil node)"),
        # the geometry of Table 1's network: by default the record of ``bearing`` (data/thermal.toml, the paper's
        # Table 3); each one set replaces that record's value (SI here; the record is in mm and degrees)
        Variable("bore", "parameter", unit="m", start=_REC0["bore_diameter_mm"] * 1e-3,
                 description=_table3("bearing bore, shaft radius r_s = bore/2")),
        Variable("outside_diameter", "parameter", unit="m", start=_REC0["outside_diameter_mm"] * 1e-3,
                 description=_table3("bearing outside diameter, r_o = OD/2")),
        Variable("width", "parameter", unit="m", start=_REC0["width_mm"] * 1e-3,
                 description=_table3("bearing width W_i = W_e")),
        Variable("balls", "parameter", unit="1", start=_REC0["n_balls"], type="Integer",
                 description=_table3("number of balls n")),
        Variable("ball_diameter", "parameter", unit="m", start=_REC0["ball_diameter_mm"] * 1e-3,
                 description=_table3("ball diameter 2 r_b")),
        Variable("contact_angle", "parameter", unit="rad", start=math.radians(_REC0["contact_angle_deg"]),
                 description=_table3("initial contact angle, gamma = D cos(alpha)/d_m of the oil convection")),
        Variable("damper_radius", "parameter", unit="m", start=_REC0["damper_radius_mm"] * 1e-3,
                 description=_table3("squeeze film damper journal radius r_j")),
        Variable("damper_length", "parameter", unit="m", start=_REC0["damper_length_mm"] * 1e-3,
                 description=_table3("squeeze film damper length L_j")),
        Variable("damper_clearance", "parameter", unit="m", start=_REC0["damper_clearance_mm"] * 1e-3,
                 description=_table3("squeeze film damper radial clearance c_sf")),
        Variable("shaft_length", "parameter", unit="m", start=_REC0["shaft_length_mm"] * 1e-3,
                 description=f"shaft conduction length L_s of R_sa (default {_DFLT['shaft_length_mm']:g} mm, "
                             f"data/thermal.toml [defaults]: an assumption, {_DOC})",
                 plausible=(0.005, 2.0)),
        Variable("housing_wall", "parameter", unit="m", start=_REC0["housing_wall_mm"] * 1e-3,
                 description=f"housing wall outside the damper film, r_h = r_j + c_sf + wall (default "
                             f"{_DFLT['housing_wall_mm']:g} mm, data/thermal.toml [defaults]: an assumption, {_DOC})",
                 plausible=(0.001, 0.2)),
        Variable("housing_length", "parameter", unit="m", start=_REC0["housing_length_mm"] * 1e-3,
                 description=f"housing length L_h (default {_DFLT['housing_length_per_damper_length']:g} x "
                             f"damper_length, data/thermal.toml [defaults]: an assumption, {_DOC})",
                 plausible=(0.002, 1.0)),
        Variable("rub_radius", "parameter", unit="m", start=_REC0["rub_ring_radius_mm"] * 1e-3,
                 description="rotor radius at the rub ring, R_r of eq. (11), the rub's sliding speed for the Blok "
                             "partition (default bore/2, as components/rubring/data/rubrings.toml; set it to the "
                             "rub ring's radius)",
                 plausible=(0.002, 1.0)),
        Variable("method", "parameter", unit="1", start="exact", type="String",
                 description="integration: 'exact' (held-input exact solution) or 'backward-euler'"),
        Variable("P_drag", "input", 1, "W", "bearing drag-torque power (mean over the step)"),
        Variable("P_sfd", "input", 1, "W", "squeeze film viscous power (mean over the step)"),
        Variable("P_rub", "input", 1, "W", "rub friction power, eq. (11) (mean over the step)"),
        Variable("eps", "output", 3, "m",
                 "thermal growths [eps_i, eps_e, eps_b]: inner raceway, outer raceway, ball radius; + = expansion",
                 labels=("inner_race", "outer_race", "ball")),
        Variable("T_oil", "output", 1, "K", "bearing oil temperature (mean of the lubricant nodes)", start=303.15),
        Variable("T_sfd_oil", "output", 1, "K", "squeeze-film oil temperature", start=303.15),
        Variable("T_inner_race", "output", 1, "K", "inner race temperature", start=303.15),
        Variable("T_ball", "output", 1, "K", "ball temperature", start=303.15),
        Variable("T_outer_race", "output", 1, "K", "outer race temperature", start=303.15),
        Variable("T_nodes", "output", 9, "K", "all nodes: " + ", ".join(NODES), start=303.15, labels=tuple(NODES)),
    )
    preferred_step = 1e-3
    phases = frozenset({"TM", "TO"})
    #: the parameter that is the shaft speed at the bearing, and the input whose producer (the bearing, P_drag = M
    #: omega) turns at it: the two must agree (master/scenario/build.check_speeds)
    fixed_speed, speed_follows = "omega", "P_drag"
    step_cost_s, kernel_step_cost_s = 45e-6, 5e-6  # bench/bench_estimate.py

    def setup(self, t0=0.0):
        super().setup(t0)
        p = self.p
        check_selection(self, "bearing", BEARINGS, [name for name, key, _ in GEOMETRY if key in REQUIRED],
                        what="Table 3 record", tables="[bearing.ID], [damper.ID]")
        if p["method"] not in METHODS:
            raise ContractError(f"{self.name}.method must be one of {METHODS}, got {p['method']!r}")
        for key in ("T_ambient", "T_initial", "T_supply"):
            if not p[key] > 0.0:
                raise ContractError(f"{self.name}.{key} must be > 0 K, got {p[key]}")
        for key in ("T_initial", "T_supply"):
            # the oil starts at T_initial and is supplied at T_supply: oil temperatures of the viscosity fit (a
            # value in degrees C, 30 for 303.15 K, ran until the bearing refused its oil as "diverged", or silently)
            try:
                check_oil_temperature(p[key])
            except ValueError as exc:
                raise ContractError(f"{self.name}.{key}: {exc}; temperatures are in kelvin") from None
        for name, key, scale in GEOMETRY:
            if name in self.explicit:
                v = p[name]
                ok = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                if name == "contact_angle":
                    if not (ok and 0.0 <= v < math.pi / 2):
                        raise ContractError(f"{self.name}.contact_angle must be in [0, pi/2) rad, got {v!r}")
                elif not (ok and v > 0 and (name != "balls" or float(v).is_integer())):
                    what = "a whole number > 0" if name == "balls" else "a finite number > 0"
                    raise ContractError(f"{self.name}.{name} must be {what}, got {v!r}")
        # the record the network is built from: the data file's number (unchanged) or the record with the set
        # values (the defaults that follow the geometry, housing_length and rub_radius, follow the set values)
        over = {key: (p[name] / scale if name != "balls" else int(p[name]))
                for name, key, scale in GEOMETRY if name in self.explicit}
        if p["bearing"] == NO_RECORD:
            bearing = over
        else:
            bearing = {**BEARINGS[p["bearing"]], **over} if over else p["bearing"]
        try:
            full = bearing_data(bearing)
            self.network = build_network(
                bearing, p["omega"], p["T_ambient"], p["T_supply"], p["drag_inner_fraction"],
                p["contact_race_fraction"], p["rub_shaft_fraction"], p["bearing_oil_flow"], p["sfd_oil_flow"],
                p["rub_ring_housing_fraction"])
        except ValueError as exc:
            raise ContractError(f"{self.name}: {exc}") from None
        for name, key, scale in GEOMETRY:
            if name not in self.explicit:
                p[name] = full[key] * scale if name != "balls" else int(full[key])
        self._bearing = bearing
        g = radii(bearing)
        st = THERMAL_DATA["steel"]
        self._growth_args = (p["T_initial"], st["expansion"], st["poisson"], g["r_i"], g["r_e"], g["r_j"], g["r_b"])
        self._method = p["method"]
        self.state = {"T": np.full(self.network.n, p["T_initial"])}
        self._kernel_h = None
        self._publish(self.state["T"])

    def _publish(self, T):
        Tl = T[:9].tolist()      # the nine named nodes (the journal's inner shells follow, geometry.py)
        eps = growths(Tl[SHAFT], Tl[LI], Tl[BALL], Tl[LE], Tl[JOURNAL], *self._growth_args)
        # one fresh buffer per step; the outputs are views of it
        buf = np.array((*Tl, *eps, 0.5 * (Tl[LI] + Tl[LE]), Tl[SFD], Tl[IR], Tl[BALL], Tl[OR]))
        y = self.y
        y["T_nodes"] = buf[0:9]
        y["eps"] = buf[9:12]
        y["T_oil"] = buf[12:13]
        y["T_sfd_oil"] = buf[13:14]
        y["T_inner_race"] = buf[14:15]
        y["T_ball"] = buf[15:16]
        y["T_outer_race"] = buf[16:17]

    def validity(self):
        return CHECKS

    def powers(self) -> np.ndarray:
        u = self.u
        q = (u["P_drag"][0].item(), u["P_sfd"][0].item(), u["P_rub"][0].item())
        if not math.isfinite(q[0] + q[1] + q[2]):
            raise ContractError(f"{self.name}: non-finite power input P_drag, P_sfd, P_rub = {list(q)} W")
        if min(q) < -1e-6:
            bad = [n for n, v in zip(("P_drag", "P_sfd", "P_rub"), q) if v < -1e-6]
            raise ContractError(f"{self.name}: negative heat source {', '.join(bad)} = {min(q)} W (must be >= 0)")
        return np.array(q)

    # -- the compiled kernel (components/kernels.py) ---------------------------------------------------------
    STEP = staticmethod(tm_step)

    def kernel_state(self):
        return ThermalState(self.state["T"])

    def kernel_prepare(self, h):
        if h != getattr(self, "_kernel_h", None):
            if not h > 0.0:
                raise ContractError(f"{self.name}: step size must be > 0, got {h}")
            Phi, gb, GS = self.network.step_matrices(h, self._method)
            self._kernel_p = ThermalParams(Phi, gb, GS, np.empty(self.network.n),
                                           *(float(a) for a in self._growth_args))
            self._kernel_h = h

    def kernel_params(self):
        return self._kernel_p

    def kernel_status(self, status, t, h):
        self.powers()          # names the non-finite or negative power
        raise RuntimeError(f"{self.name}: kernel status {status} at t = {t + h:.9g} s")

    def steady_state(self, P_drag: float, P_sfd: float, P_rub: float) -> np.ndarray:
        """Node temperatures (K) of the steady state under constant powers (the linear solve K T = b + S u): the
        nine named nodes, then the journal's inner shells."""
        self.set_inputs({"P_drag": [P_drag], "P_sfd": [P_sfd], "P_rub": [P_rub]})
        return self.network.steady(self.powers())

    def growths_at(self, T) -> np.ndarray:
        """eps = [eps_i, eps_e, eps_b] (m) of node temperatures T (K)."""
        return np.array(growths(T[SHAFT], T[LI], T[BALL], T[LE], T[JOURNAL], *self._growth_args))
