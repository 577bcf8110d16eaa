"""The co-simulated parts of an engine file, and the quantities a scenario's components take from it.

An engine file describes, for each bearing location of its ``[attach]`` (``bearing<ID>``, ``rubring<ID>``), what
sits there (docs/reference/engine-format.md)::

    [bearing.0]            # the ball bearing at [attach] bearing0
    balls = 21
    ball_diameter_mm = 8.73
    ...
    [damper.0]             # its squeeze film damper
    [rubring.0]            # the rub ring at [attach] rubring0
    [thermal.0]            # its thermal network (optional keys)
    [unbalance]            # the residual unbalance at [attach] unbalance (optional)

:class:`EngineView` turns a file into named SI quantities, the one value each component built from it takes:
``"damper.0.clearance"`` [m] is the clearance of damper ``0`` and of the film in thermal network ``0``;
``"spool.pt.omega"`` [rad/s] (from the spool's ``speed_rpm``) the speed of the rotor's first spool, of the
bearings and rub rings on it and of their thermal networks (``"bearing.0.omega"``, ``"rubring.0.omega"`` name
it through the spool of the part's node); ``"spool.pt.inertia"`` [kg m^2] its polar inertia computed from the
rotor (spool_inertia.py); ``"spool#1"``, ``"spool#2"`` the first and second spool of the file; ``"file"`` the
engine file itself. A value the file does not give is a physical consequence of what it gives (the rub ring's
radius: its bearing's bore / 2), a generic default with its source (:data:`KEYS`), or refused with the missing
key named. ``overrides`` (name -> SI value) replace a quantity, and everything derived from it follows.

Example::

    >>> from rotorcosim.components.rotor import engine_parts, model
    >>> v = engine_parts.EngineView(model.DEFAULT_FILE)
    >>> v.value("damper.0.clearance")[0], v.value("bearing.5.omega")[0] == v.value("spool.pt.omega")[0]
    (0.000635, True)
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from . import model as fem
from .engine_shape import refuse, shape_problems
from .spool_inertia import spool_polar_inertia

#: rev/min -> rad/s (components/speeds.py's factor, which the paper engine's default speeds use)
RPM = math.pi / 30.0
DOC = "docs/reference/engine-format.md"


def _mm(v):
    return v * 1e-3


def _deg(v):
    return math.radians(v)


def _mpa(v):
    return v * 1e6


def _l_per_min(v):
    return v * (1e-3 / 60.0)


def _same(v):
    return v


@dataclass(frozen=True)
class Key:
    """One key of a part's table: its quantity (``name``, SI), the file's unit, the conversion to SI, whether it
    must be a whole number, and what applies when the file does not give it: ``default`` (a value in the file's
    unit), ``rule`` (a physical consequence of other quantities), neither (``required``), or ``None`` with
    ``component_default`` (the component's own documented default applies)."""

    key: str
    name: str
    unit: str
    to_si: Callable[[float], float]
    meaning: str
    default: float | None = None
    rule: str | None = None
    source: str = ""
    whole: bool = False
    positive: bool = True
    component_default: bool = False

    @property
    def required(self) -> bool:
        return self.default is None and self.rule is None and not self.component_default


_THERMAL_DATA = "components/thermal/data/thermal.toml [defaults] and [oil_flow] (docs/explanation/paper-components.md)"

#: the keys of each part's table, in the order the reference lists them
KEYS: dict[str, tuple[Key, ...]] = {
    "bearing": (
        Key("balls", "balls", "1", int, "number of balls", whole=True),
        Key("ball_diameter_mm", "ball_diameter", "mm", _mm, "ball diameter"),
        Key("bore_mm", "bore", "mm", _mm, "inner race bore"),
        Key("outside_diameter_mm", "outside_diameter", "mm", _mm, "outer race outside diameter"),
        Key("width_mm", "width", "mm", _mm, "bearing width"),
        Key("contact_angle_deg", "contact_angle", "deg", _deg, "initial (unloaded) contact angle",
            positive=False),
        Key("preload_N", "preload", "N", _same, "axial preload", positive=False),
    ),
    "damper": (
        Key("radius_mm", "radius", "mm", _mm, "journal radius (also the journal's mass and the thermal network's r_j)"),
        Key("length_mm", "length", "mm", _mm, "film land length (also the journal's mass and L_j)"),
        Key("clearance_mm", "clearance", "mm", _mm, "radial clearance (also the thermal network's c_sf)"),
        Key("supply_pressure_MPa", "supply_pressure", "MPa", _mpa, "oil supply pressure at the land ends (gauge)",
            positive=False),
        Key("k_spring", "k_spring", "N/m", _same, "centering spring (O-ring, squirrel cage) stiffness",
            positive=False),
    ),
    "rubring": (
        Key("clearance_mm", "clearance", "mm", _mm, "radial clearance between the rotor and the ring"),
        Key("radius_mm", "radius", "mm", _mm, "rotor radius at the ring (the rub's sliding speed)",
            rule="bore", source="the ring on the shaft next to its bearing: [bearing.ID] bore_mm / 2"),
    ),
    "thermal": (
        Key("shaft_length_mm", "shaft_length", "mm", _mm, "shaft conduction length L_s to the shaft's sink",
            component_default=True, source=_THERMAL_DATA + ": 100 mm, an assumption"),
        Key("housing_wall_mm", "housing_wall", "mm", _mm, "housing wall outside the damper film",
            component_default=True, source=_THERMAL_DATA + ": 15 mm, an assumption"),
        Key("housing_length_mm", "housing_length", "mm", _mm, "housing length L_h",
            component_default=True, source=_THERMAL_DATA + ": 2 x the damper length, an assumption"),
        Key("sfd_oil_flow_L_per_min", "sfd_oil_flow", "L/min", _l_per_min, "damper oil feed",
            component_default=True, source=_THERMAL_DATA + ": 1 L/min, an engineering estimate", positive=False),
        Key("bearing_oil_flow_L_per_min", "bearing_oil_flow", "L/min", _l_per_min, "oil jet through the bearing",
            component_default=True, source=_THERMAL_DATA + ": none (0), as the paper's network", positive=False),
    ),
    "fuse": (
        Key("housing_mass_kg", "housing_mass", "kg", _same, "mass of the bearing's housing the fuse carries (it moves "
            "with the damper's housing side; the hub keeps its own mass)"),
        Key("k_intact", "k_intact", "N/m", _same, "intact radial stiffness (x and y; also the housing's axial hold)"),
        Key("damping", "damping", "N s/m", _same, "damping, intact and after the break", default=0.0,
            positive=False, source="none"),
        Key("break_load_N", "break_load", "N", _same, "radial elastic force k_intact |x| at which the fuse breaks"),
        Key("k_broken", "k_broken", "N/m", _same, "stiffness of the soft path after the break (0: none)",
            default=0.0, positive=False, source="none: nothing holds the housing radially but the bumper"),
        Key("stages", "stages", "1", int, "break stages, 1 or 2", default=1, whole=True, source="one stage"),
        Key("break_load_2_N", "break_load_2", "N", _same, "with stages = 2: the soft path's force k_broken |x| "
            "at which it breaks", default=0.0, positive=False, source="none (one stage)"),
        Key("k_broken_2", "k_broken_2", "N/m", _same, "with stages = 2: stiffness after the second break",
            default=0.0, positive=False, source="none (one stage)"),
        Key("bumper_clearance_mm", "bumper_clearance", "mm", _mm, "radial clearance of the bumper", default=0.0,
            positive=False, source="no bumper unless bumper_stiffness is given"),
        Key("bumper_stiffness", "bumper_stiffness", "N/m", _same, "contact stiffness of the bumper (0: none)",
            default=0.0, positive=False, source="no bumper"),
        Key("bumper_friction", "bumper_friction", "1", _same, "friction coefficient of the bumper contact",
            default=0.0, positive=False, source="frictionless"),
    ),
    "unbalance": (
        Key("residual_N", "residual", "N", _same, "residual unbalance force before the blade loss, at the "
            "unbalance node, turning with the first spool", default=0.0, positive=False,
            source="none: an engine has no residual unbalance unless its file gives one"),
        Key("phase_deg", "phase", "deg", _deg, "angle of the lost blade relative to the residual unbalance",
            default=90.0, positive=False,
            source="quadrature (components/rotor/component.py: the residual changes the amplitude least)"),
    ),
}
#: the SI unit of a quantity given in a file unit
SI_UNIT = {"mm": "m", "deg": "rad", "MPa": "Pa", "L/min": "m3/s"}
#: the part tables keyed by id (``[unbalance]`` is one table)
PER_ID = ("bearing", "damper", "rubring", "thermal", "fuse")
#: part tables a bearing has only where the file gives one (a support fuse)
OPTIONAL = ("fuse",)
#: which [attach] entry each part table belongs to
ATTACH_OF = {"bearing": "bearing", "damper": "bearing", "thermal": "bearing", "rubring": "rubring",
             "fuse": "bearing"}


def _key(table: str, key: str) -> Key | None:
    return next((k for k in KEYS[table] if k.key == key), None)


def _by_name(table: str, name: str) -> Key | None:
    return next((k for k in KEYS[table] if k.name == name), None)


def _is_speed(v: Any) -> bool:
    """A spool's operating speed: a finite, non-zero number (its sign the direction of rotation)."""
    return not isinstance(v, bool) and isinstance(v, (int, float)) and math.isfinite(v) and v != 0


def _check_value(k: Key, v: Any) -> str | None:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        return f"must be a finite number ({k.unit}), got {v!r}"
    if k.whole and (not isinstance(v, int) or v < 1):
        return f"must be a whole number >= 1, got {v!r}"
    if k.positive and not v > 0:
        return f"must be > 0 ({k.unit}), got {v!r}"
    if not k.positive and v < 0:
        return f"must be >= 0 ({k.unit}), got {v!r}"
    if k.key == "contact_angle_deg" and not v < 90.0:
        return f"must be below 90 deg, got {v!r}"
    return None


def problems(data: dict) -> list[str]:
    """One line per problem of the part tables of an engine file's ``data`` (an unknown key or id, a bad value)."""
    out = []
    attach = data.get("attach", {}) if isinstance(data.get("attach"), dict) else {}
    for table in PER_ID:
        parts = data.get(table)
        if parts is None:
            continue
        if not isinstance(parts, dict):
            out.append(f"[{table}]: must hold one table per id ([{table}.ID]), got {parts!r}")
            continue
        for pid, spec in parts.items():
            where = f"[{table}.{pid}]"
            if not isinstance(spec, dict):
                out.append(f"{where}: must be a table of keys, got {spec!r}")
                continue
            if f"{ATTACH_OF[table]}{pid}" not in attach:
                out.append(f"{where}: [attach] has no {ATTACH_OF[table]}{pid} (the part sits at that attachment)")
            for key, v in spec.items():
                k = _key(table, key)
                if k is None:
                    out.append(f"{where} {key}: unknown key (known: {', '.join(x.key for x in KEYS[table])})")
                    continue
                err = _check_value(k, v)
                if err:
                    out.append(f"{where} {key}: {err}")
            if table == "fuse":
                out += _fuse_problems(where, spec)
    unb = data.get("unbalance")
    if unb is not None:
        if not isinstance(unb, dict):
            out.append(f"[unbalance]: must be a table, got {unb!r}")
        else:
            for key, v in unb.items():
                k = _key("unbalance", key)
                if k is None:
                    out.append(f"[unbalance] {key}: unknown key (known: "
                               f"{', '.join(x.key for x in KEYS['unbalance'])})")
                    continue
                err = _check_value(k, v)
                if err:
                    out.append(f"[unbalance] {key}: {err}")
    return out


def absent(data: dict) -> list[str]:
    """One line per required key that a part table the engine file gives, for a part its [attach] names, leaves
    out (``"[fuse.0] k_intact: missing (...)"``): check-engine lists them with the file's other problems, rather
    than a run or the linearised engine stopping at the first value it asks for."""
    attach = data.get("attach", {}) if isinstance(data.get("attach"), dict) else {}
    out = []
    for table in PER_ID:
        parts = data.get(table)
        for pid, spec in (parts.items() if isinstance(parts, dict) else ()):
            if isinstance(spec, dict) and f"{ATTACH_OF[table]}{pid}" in attach:
                out += [f"[{table}.{pid}] {k.key}: missing ({k.meaning}, {k.unit}; required: {DOC})"
                        for k in KEYS[table] if k.required and k.key not in spec]
    return out


def _fuse_problems(where: str, spec: dict) -> list[str]:
    """What a fuse's keys say that the value checks do not: a number of stages other than 1 or 2, a soft path
    stiffer than the intact one. (The component refuses the same, and inconsistent stages, by its parameter's name
    when a run sets it up.)"""
    out = []
    stages = spec.get("stages", 1)
    if isinstance(stages, int) and not isinstance(stages, bool) and stages > 2:   # < 1: the value check
        out.append(f"{where} stages: must be 1 or 2, got {stages!r}")
    k, kb = spec.get("k_intact"), spec.get("k_broken", 0.0)
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in (k, kb)) and kb > k:
        out.append(f"{where} k_broken: must be at most k_intact = {k:g} N/m (the post-fuse path is the softer one), "
                   f"got {kb!r}")
    return out


def missing(data: dict) -> list[str]:
    """The required keys (no default, no rule, no component default) that the part tables of an engine file's
    ``data`` lack for the parts its [attach] names, one entry per table: ``"[bearing.0] balls, bore_mm"``; a table
    absent altogether lacks every required key."""
    attach = data.get("attach", {}) if isinstance(data.get("attach"), dict) else {}
    out = []
    for entry in attach:
        for table in PER_ID:
            pid = entry[len(ATTACH_OF[table]):]
            if not entry.startswith(ATTACH_OF[table]) or entry in ("unbalance", "oil_temperature_C"):
                continue
            tables = data.get(table) if isinstance(data.get(table), dict) else {}
            if table in OPTIONAL and pid not in tables:
                continue
            spec = tables.get(pid) if isinstance(tables.get(pid), dict) else {}
            lack = [k.key for k in KEYS[table] if k.required and k.key not in spec]
            if lack:
                out.append(f"[{table}.{pid}] {', '.join(lack)}")
    return out


class EngineView:
    """The named SI quantities of the engine file ``path`` (module docstring), with ``overrides``."""

    def __init__(self, path: str | Path | None = None, overrides: dict[str, Any] | None = None,
                 data: dict | None = None):
        self.path = str(Path(path) if path else fem.DEFAULT_FILE)
        self.data, self.digest = (data, "") if data is not None else fem.load_data(self.path)
        if data is None:
            # a run reads the file through this view: what check-engine lists of its shape and its parts refuses
            # it here, a typo'd key included, rather than being read as absent
            refuse(shape_problems(self.data) or problems(self.data), f"engine file {self.path}")
        self.overrides = dict(overrides or {})
        self._spools = list(self.data.get("spool", {})) if isinstance(self.data.get("spool"), dict) else []
        self._inertia: dict[str, float] = {}

    # -- names ------------------------------------------------------------------------------------------
    def _spool_of(self, entry: str) -> str:
        at = self.data.get("attach", {}).get(entry)
        node = at.get("node") if isinstance(at, dict) else None
        if not (isinstance(node, list) and node and isinstance(node[0], str)):
            raise ValueError(f"engine file {self.path}: [attach] has no {entry} = {{ node = [spool, node] }}")
        return node[0]

    def canonical(self, name: str) -> str:
        """The quantity ``name`` stands for: ``"spool#1.omega"`` -> ``"spool.pt.omega"``, ``"bearing.0.omega"``
        -> the speed of the spool bearing 0's node is on."""
        parts = name.split(".")
        if parts[0].startswith("spool#") and len(parts) == 2:
            try:
                n = int(parts[0][6:])
            except ValueError:
                raise ValueError(f"engine quantity {name!r}: spool#N with N = 1, 2, ...") from None
            if not self._spools:
                raise ValueError(f"engine file {self.path}: no [spool.NAME]")
            # a second spool an engine does not have: the first (its terms vanish in the rotor model)
            return f"spool.{self._spools[min(n, len(self._spools)) - 1]}.{parts[1]}"
        if len(parts) == 3 and parts[0] in ("bearing", "rubring") and parts[2] == "omega":
            return f"spool.{self._spool_of(parts[0] + parts[1])}.omega"
        return name

    def set(self, name: str, value: Any, label: str | None = None) -> str:
        """Override quantity ``name`` (SI); returns the canonical name stored (a speed in rad/s is stored as the
        spool's rev/min, the file's quantity, so that everything derived from it follows). ``label``: how an error
        names the value (the parameter it was given as)."""
        c = self.canonical(name)
        what = f"{label} must be" if label else f"{c} must be"
        tail = f" (the engine's {c})" if label else ""
        if c == "file":
            self.__init__(value, self.overrides)
            return c
        parts = c.split(".")
        table = parts[0] if parts[0] in KEYS else None
        k = _by_name(table, parts[-1]) if table else None
        if k is not None:
            si = SI_UNIT.get(k.unit, k.unit)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                raise ValueError(f"{what} a finite number ({si}), got {value!r}{tail}")
            if k.whole and (not float(value).is_integer() or value < 1):
                raise ValueError(f"{what} a whole number >= 1, got {value!r}{tail}")
            if k.positive and not value > 0:
                raise ValueError(f"{what} a finite number > 0 ({si}), got {value!r}{tail}")
            if not k.positive and value < 0:
                raise ValueError(f"{what} >= 0 ({si}), got {value!r}{tail}")
        if parts[0] == "spool" and len(parts) == 3 and parts[2] in ("omega", "speed_rpm"):
            # the spool's operating speed: every speed of that spool follows it, the schedule's cycle included
            if not _is_speed(value):
                raise ValueError(f"{what} a finite non-zero number (the spool's operating speed, "
                                 f"{'rad/s' if parts[2] == 'omega' else 'rev/min'}), got {value!r}{tail}")
            if parts[2] == "omega":
                c, value = f"spool.{parts[1]}.speed_rpm", float(value) / RPM
        self.overrides[c] = value
        return c

    # -- values -----------------------------------------------------------------------------------------
    def value(self, name: str) -> tuple[Any, str]:
        """(SI value, where it comes from) of quantity ``name``; ``(None, source)`` for a key whose component
        default applies. A key the file must give and does not is a ValueError naming it."""
        c = self.canonical(name)
        if c in self.overrides:
            return self.overrides[c], "override"
        parts = c.split(".")
        if c == "file":
            return self.path, "the engine"
        if parts[0] == "spool" and len(parts) == 3:
            return self._spool(parts[1], parts[2])
        if parts[0] == "unbalance" and len(parts) == 2:
            return self._part("unbalance", None, parts[1])
        if parts[0] in PER_ID and len(parts) == 3:
            return self._part(parts[0], parts[1], parts[2])
        raise ValueError(f"engine quantity {name!r} is not one of the engine format's ({DOC})")

    def _spool(self, spool: str, what: str) -> tuple[Any, str]:
        spools = self.data.get("spool", {})
        if spool not in spools:
            raise ValueError(f"engine file {self.path}: no [spool.{spool}] (its spools: "
                             f"{', '.join(self._spools) or 'none'})")
        where = f"{self.path} [spool.{spool}]"
        if what in ("speed_rpm", "omega"):
            key = f"spool.{spool}.speed_rpm"
            if key in self.overrides:
                rpm, src = float(self.overrides[key]), "override"
            else:
                rpm = spools[spool].get("speed_rpm")
                if not _is_speed(rpm):
                    raise ValueError(f"{where} speed_rpm: the spool's operating speed (rev/min) missing or not a "
                                     f"non-zero number, got {rpm!r}")
                rpm, src = float(rpm), f"{where} speed_rpm"
            return (rpm if what == "speed_rpm" else rpm * RPM), src
        if what == "inertia":
            if spool not in self._inertia:
                self._inertia[spool] = spool_polar_inertia(self.data, spool)
            return self._inertia[spool], f"computed from {where} (shaft sections and disks)"
        if what == "name":
            return str(spools[spool].get("name", spool)), where
        raise ValueError(f"engine quantity 'spool.{spool}.{what}': a spool has speed_rpm, omega, inertia, name")

    def _table(self, table: str, pid: str | None) -> tuple[dict, str]:
        raw = self.data.get(table, {})
        spec = raw if pid is None else (raw.get(pid) if isinstance(raw, dict) else None)
        where = f"[{table}]" if pid is None else f"[{table}.{pid}]"
        return (spec if isinstance(spec, dict) else {}), where

    def _part(self, table: str, pid: str | None, name: str) -> tuple[Any, str]:
        k = _by_name(table, name)
        if k is None:
            raise ValueError(f"engine quantity '{table}.{pid + '.' if pid else ''}{name}': {table} has "
                             f"{', '.join(x.name for x in KEYS[table])}")
        spec, where = self._table(table, pid)
        if k.key in spec:
            v = spec[k.key]
            err = _check_value(k, v)
            if err:
                raise ValueError(f"engine file {self.path}: {where} {k.key}: {err}")
            return k.to_si(v), f"{self.path} {where} {k.key}"
        if k.default is not None:
            return k.to_si(k.default), f"default {k.default:g} {k.unit}: {k.source}"
        if k.rule == "bore":
            bore, _ = self.value(f"bearing.{pid}.bore")
            return bore / 2, f"default: {k.source}"
        if k.component_default:
            return None, f"default: {k.source}"
        raw = self.data.get(table, {})
        if pid is not None and isinstance(raw, dict) and pid not in raw:
            # a scenario's template id the engine does not describe at all: no key of it is "missing"
            ids = ", ".join(sorted(map(str, raw))) or "none"
            raise ValueError(f"engine file {self.path}: no {where} (the {table} ids it has: {ids}); a scenario's "
                             f"[templates] {table} lists ids the engine file describes")
        what = f"the {table} at {ATTACH_OF.get(table, table)}{pid}" if pid is not None else f"the {table}"
        raise ValueError(f"engine file {self.path}: {where} {k.key} missing ({k.meaning}, {k.unit}; {what} needs "
                         f"it: {DOC})")
