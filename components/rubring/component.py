"""The rub-ring component: rotor/ring contact with Coulomb friction and the friction power of eq. (11).

Paper section 2.3 (eq. 11) and Table 3 (clearance 0.508 mm); the contact law and its sign conventions are in
contact.py. The ring is carried by the housing (casing node): forces act on the rotor (``F_rotor``) and, equal and
opposite, on the housing (``F_housing``).

Inputs are the rotor's and the housing's displacement and velocity at the ring (absolute, m and m/s); the force is
evaluated at the inputs given for the step (the rotor's state at the end of the step, Gauss-Seidel order) and held
over it. The component is memoryless, so ``P_rub`` evaluated at those held inputs is also the mean friction power
over the step that those forces deliver (the held force times the held sliding speed).

Parameters default to ring #0 (``bearing = 0``); ``bearing = 5`` picks ring #5's clearance and radius. Values in
data/rubrings.toml, their reasons in docs/explanation/paper-components.md: stiffness 3e8 N/m (conformal line contact, Johnson), damping 4900 N s/m, friction 0.2, clearance 0.508 mm, radius
25.4 mm (41.9 mm at #5), omega = 16 000 rev/min (power-turbine speed).
"""
from __future__ import annotations

import tomllib
from pathlib import Path

from ..contract import ContractError, Memoryless, Variable
from ..kernels import KernelComponent
# ``bearing`` = NO_RECORD: no ring of the paper's; clearance and radius are given
from ..records import NO_RECORD, check_selection
from ..speeds import PT_OMEGA
from ..validity import Check
from .contact import RubParams, tm_step

DATA = Path(__file__).with_name("data") / "rubrings.toml"
with open(DATA, "rb") as _f:
    _DATA = tomllib.load(_f)
RINGS = {int(k): v for k, v in _DATA["ring"].items()}
CONTACT = _DATA["contact"]
#: parameters that follow the ``bearing`` selection unless set explicitly
GEOMETRY = {"clearance": "clearance_mm", "radius": "radius_mm"}
#: the largest normal force the shipped contact stiffness describes: data/rubrings.toml [contact] estimates it from
#: Johnson's conformal line contact (Contact Mechanics, sec. 5.6) as 2.7-3.3e8 N/m over 5-50 kN, so a constant
#: 3e8 N/m is within 10 % of that law up to 50 kN; beyond it the law (stiffening with load) is not the one used
LINEAR_CONTACT_N = 50e3


def _normal(y):
    return y["F_normal"][:, 0]


class RubRing(Memoryless, KernelComponent):
    """Rotor / rub-ring contact at bearing #0 or #5."""

    description = "Rub ring: penalty contact with damping, Coulomb friction (spin + whirl), friction power eq. (11)"
    variables = (
        Variable("bearing", "parameter", unit="1", start=NO_RECORD, type="Integer",
                 description="which ring of the paper's (at bearing 0 or 5) gives the clearance and radius not set "
                             "explicitly; -1 (default): none, both are given (a scenario takes them from its engine "
                             "file's [rubring.ID])"),
        Variable("clearance", "parameter", unit="m", start=RINGS[0]["clearance_mm"] * 1e-3,
                 description="radial clearance between the rotor and the ring",
                 plausible=(1e-5, 5e-3)),  # seal and rub-ring clearances: tens of um to a few mm
        Variable("stiffness", "parameter", unit="N/m", start=CONTACT["stiffness"], description="contact stiffness"),
        Variable("damping", "parameter", unit="N.s/m", start=CONTACT["damping"],
                 description="contact damping on the penetration rate"),
        # at most 2: the largest dry coefficients of metal pairs in the handbooks are ~1.0-1.4 (clean aluminium on
        # aluminium 1.05-1.35, silver on silver 1.4: CRC Handbook of Chemistry and Physics, "Coefficient of
        # friction"); 50 was accepted. The shipped 0.2: docs/explanation/paper-components.md
        Variable("friction", "parameter", unit="1", start=CONTACT["friction"], description="Coulomb coefficient",
                 min=0.0, max=2.0),
        Variable("radius", "parameter", unit="m", start=RINGS[0]["radius_mm"] * 1e-3,
                 description="rotor surface radius at the ring (spin surface speed omega * radius)",
                 plausible=(0.002, 1.0)),   # a shaft of a few mm to a fan's hub, in m
        Variable("omega", "parameter", unit="rad/s", start=PT_OMEGA, description="rotor spin speed (counter-clockwise +)"),
        Variable("slip_regularisation", "parameter", unit="m/s", start=CONTACT["slip_regularisation"],
                 description="sliding speed below which the friction force is proportional to the slip"),
        Variable("X_rotor", "input", 2, "m", "rotor displacement at the ring (absolute)"),
        Variable("V_rotor", "input", 2, "m/s", "rotor velocity at the ring (absolute)"),
        Variable("X_housing", "input", 2, "m", "housing (ring) displacement (absolute)"),
        Variable("V_housing", "input", 2, "m/s", "housing (ring) velocity (absolute)"),
        Variable("F_rotor", "output", 2, "N", "contact + friction force on the rotor"),
        Variable("F_housing", "output", 2, "N", "reaction on the housing, -F_rotor"),
        Variable("P_rub", "output", 1, "W", "friction power, eq. (11) (mean over the step)"),
        Variable("F_normal", "output", 1, "N", "normal contact force magnitude"),
    )
    preferred_step = 1e-5
    phases = frozenset({"TM"})
    #: the parameter that is the speed of the rotor node the ring is linked to (master/scenario/build.check_speeds)
    fixed_speed = "omega"
    step_cost_s, kernel_step_cost_s = 6.5e-6, 0.5e-6  # bench/bench_estimate.py

    def setup(self, t0=0.0):
        super().setup(t0)
        p = self.p
        explicit = self.explicit
        check_selection(self, "bearing", RINGS, GEOMETRY, what="ring record", tables="[rubring.ID]")
        for key, data_key in GEOMETRY.items():
            if key not in explicit:
                p[key] = RINGS[p["bearing"]][data_key] * 1e-3
        for key in ("clearance", "stiffness", "radius", "slip_regularisation"):
            if not p[key] > 0.0:
                raise ContractError(f"{self.name}.{key} must be > 0, got {p[key]}")
        if p["damping"] < 0.0:   # friction: its declared range (min, max)
            raise ContractError(f"{self.name}.damping must be >= 0, got {p['damping']}")
        if p["clearance"] >= p["radius"]:
            # a radial gap as wide as the shaft is no rub ring: in practice mm given where metres are meant
            hint = (f"; lengths are in metres: {p['clearance']:g} mm = {p['clearance'] * 1e-3:g} m"
                    if p["clearance"] * 1e-3 < p["radius"] else "")
            raise ContractError(f"{self.name}.clearance = {p['clearance']:g} m is not smaller than the rotor's radius "
                                f"at the ring ({p['radius']:g} m){hint}")
        self._args = (p["clearance"], p["stiffness"], p["damping"], p["friction"], p["radius"], p["omega"],
                      p["slip_regularisation"])
        self.state = {}
        self._evaluate(t0)

    def validity(self):
        """The normal force within the range of the shipped stiffness's contact law (LINEAR_CONTACT_N); a
        stiffness set by the scenario is its own law, with no range known here: nothing declared then."""
        if self.p["stiffness"] != CONTACT["stiffness"]:
            return ()
        return (Check("rub contact force", ("F_normal",), _normal, LINEAR_CONTACT_N, "N",
                      "contact stiffness 3e8 N/m: Johnson's steel line contact, within 10 % for 5-50 kN "
                      "(data/rubrings.toml)"),)

    # -- the compiled kernel (components/kernels.py): set-up and every step evaluate through it -------------
    STEP = staticmethod(tm_step)

    def kernel_state(self):
        return ()

    def kernel_params(self):
        return self._kernel_p

    def kernel_status(self, status, t, h):
        raise ContractError(f"{self.name}: non-finite rotor/housing motion at t = {t + h:.9g} s")

    def _evaluate(self, t):
        self._kernel_p = RubParams(*(float(a) for a in self._args))
        self.kernel_step(t, 0.0)
