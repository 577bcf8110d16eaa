"""Every problem of an engine file, by name, before anything is assembled; and the engine's figures of merit.

:func:`problems` walks the whole file (docs/reference/engine-format.md) and returns one line per problem found
(a node out of range, stations that overlap, a support or attachment on a node or hub that does not exist, a
negative, zero or NaN dimension, a missing key...), so a user fixes them all in one pass instead of one per
run. :func:`report` gives what ``rotorcosim check-engine`` prints of a valid file: nodes per spool, masses,
spool polar inertias.

Example::

    from rotorcosim.components.rotor import engine_check, model
    data, _ = model.load_data("engine.toml")
    for line in engine_check.problems(data):
        print(line)
"""
from __future__ import annotations

import math

import numpy as np

from . import attach as attach_layout
from . import engine_parts
from . import model as fem
from .engine_shape import shape_problems
from .spool_inertia import spool_polar_inertia

RESERVED = ("hub", "ground")


def _num(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


class _Problems:
    def __init__(self, data: dict):
        self.data = data
        self.out: list[str] = []

    def add(self, where: str, what: str) -> None:
        line = f"{where}: {what}"
        if line not in self.out:   # kxx and kyy given by one k: its problem once
            self.out.append(line)

    def value(self, where: str, value, *, positive=True, allow_knob=False):
        """A finite number > 0 (>= 0 with positive=False), or a [calibration] knob's name; None if not."""
        if allow_knob and isinstance(value, str):
            cal = self.data.get("calibration", {})
            if value not in cal:
                self.add(where, f"names {value!r}, which [calibration] does not define")
                return None
            value = cal[value]
        if not _num(value) or not math.isfinite(value) or (value <= 0 if positive else value < 0):
            self.add(where, f"must be a finite number {'> 0' if positive else '>= 0'}, got {value!r}")
            return None
        return float(value)


def problems(data: dict) -> list[str]:
    """One line per problem of the engine description ``data`` (empty: none found). A value of the wrong TOML
    shape (:func:`.engine_shape.shape_problems`) is reported alone: the values are judged once the shape holds."""
    shape = shape_problems(data)
    if shape:
        return shape
    p = _Problems(data)
    fmt = data.get("engine", {}).get("format")
    if fmt is None:
        p.add("[engine]", f"format missing (this version reads format = {fem.FORMAT})")
    elif fmt != fem.FORMAT:
        p.add("[engine] format", f"{fmt!r}: this version reads format {fem.FORMAT}")
    mats = data.get("material", {})
    for name, m in mats.items():
        if not isinstance(m, dict):
            p.add(f"material.{name}", "must be a table (E, rho, nu or G)")
            continue
        for k in ("E", "rho"):
            if k not in m:
                p.add(f"material.{name}", f"{k} missing")
            else:
                p.value(f"material.{name}.{k}", m[k])
        if "G" in m:
            p.value(f"material.{name}.G", m["G"])
        elif "nu" not in m:
            p.add(f"material.{name}", "nu (or G) missing")
        elif not (_num(m["nu"]) and -1.0 < m["nu"] < 0.5):
            p.add(f"material.{name}.nu", f"must be a Poisson's ratio within (-1, 0.5), got {m['nu']!r}")
    dmp = data.get("damping")
    if not isinstance(dmp, dict):
        p.add("[damping]", "missing (zeta, f1_Hz, f2_Hz; zeta = 0 for none)")
    else:
        for k, pos in (("zeta", False), ("f1_Hz", True), ("f2_Hz", True)):
            p.value(f"damping.{k}", dmp.get(k), positive=pos)

    spools = data.get("spool")
    nodes: dict[str, int] = {}
    if not isinstance(spools, dict) or not spools:
        p.add("[spool.NAME]", "no spool (one table per shaft)")
        spools = {}
    elif len(spools) > fem.MAX_SPOOLS:
        p.add("[spool]", f"{len(spools)} spools; the engine format carries at most {fem.MAX_SPOOLS}")
    for s, r in spools.items():
        w = f"spool.{s}"
        if s in RESERVED:
            p.add(w, f"{s!r} is a reserved word of node references; name the spool otherwise")
        if not isinstance(r, dict):
            p.add(w, "must be a table")
            continue
        if r.get("material", "rotor") not in mats:
            p.add(f"{w}.material", f"{r.get('material', 'rotor')!r} is not a [material] table")
        p.value(f"{w}.speed_rpm", r.get("speed_rpm"))
        z = r.get("z_mm")
        if not isinstance(z, list) or len(z) < 2:
            p.add(f"{w}.z_mm", "needs a list of at least 2 stations (mm)")
            continue
        bad = [i for i, v in enumerate(z) if not (_num(v) and math.isfinite(v))]
        if bad:
            p.add(f"{w}.z_mm[{bad[0]}]", f"must be a finite number, got {z[bad[0]]!r}")
            continue
        nodes[s] = len(z)
        for i in range(len(z) - 1):
            if not z[i + 1] > z[i]:
                p.add(f"{w}.z_mm", f"stations overlap: node {i + 1} at {z[i + 1]} mm is not after node {i} at "
                                   f"{z[i]} mm")
        ne = len(z) - 1
        d_out, d_in = r.get("d_out_mm"), r.get("d_in_mm")
        for key, d, pos in (("d_out_mm", d_out, True), ("d_in_mm", d_in, False)):
            if not isinstance(d, list) or len(d) != ne:
                p.add(f"{w}.{key}", f"needs {ne} values (one per element between the {len(z)} stations), got "
                                    f"{len(d) if isinstance(d, list) else d!r}")
                continue
            for e, v in enumerate(d):
                p.value(f"{w}.{key}[{e}]", v, positive=pos, allow_knob=True)
        if isinstance(d_out, list) and isinstance(d_in, list) and len(d_out) == len(d_in) == ne:
            for e, (a, b) in enumerate(zip(d_out, d_in)):
                if _num(a) and _num(b) and math.isfinite(a) and math.isfinite(b) and a > 0 and not b < a:
                    p.add(f"{w} element {e}", f"inner diameter {b} mm is not smaller than the outer {a} mm")
        for key in ("drive_node", "axial_node"):
            if key in r and not _node_ok(r[key], len(z)):
                p.add(f"{w}.{key}", f"node {r[key]!r} out of range 0-{len(z) - 1}")
        if "drive_node" not in r:
            p.add(w, "drive_node missing (the node whose torsion is held: the spool turns at constant speed)")
        _layers(p, w, r, len(z), mats)
        for key, v in r.get("rayleigh", {}).items():
            vals = v if isinstance(v, list) else [v]
            if isinstance(v, list) and len(v) != ne:
                p.add(f"{w}.rayleigh.{key}", f"needs {ne} values (one per element) or one number, got {len(v)}")
                continue
            for e, x in enumerate(vals):
                p.value(f"{w}.rayleigh.{key}" + (f"[{e}]" if isinstance(v, list) else ""), x, positive=False)
        for i, dk in enumerate(r.get("disks", [])):
            dw = f"{w}.disks[{i}] ({dk.get('name', '')!r})" if isinstance(dk, dict) else f"{w}.disks[{i}]"
            if not isinstance(dk, dict):
                p.add(dw, "must be a table {node, mass, Ip, Id}")
                continue
            if not _node_ok(dk.get("node"), len(z)):
                p.add(dw, f"node {dk.get('node')!r} out of range 0-{len(z) - 1}")
            p.value(f"{dw}.mass", dk.get("mass"), positive=False, allow_knob=True)
            _disk_inertia(p, dw, dk)

    cas = data.get("casing")
    hubs: list[str] = []
    if cas is not None:
        if not isinstance(cas, dict):
            p.add("[casing]", "must be a table")
        else:
            rings = cas.get("ring_z_mm", [])
            for k in ("radius_mm", "thickness_mm"):
                p.value(f"casing.{k}", cas.get(k))
            if cas.get("material", "casing") not in mats:
                p.add("casing.material", f"{cas.get('material', 'casing')!r} is not a [material] table")
            if not (isinstance(rings, list) and len(rings) >= 2 and all(_num(v) for v in rings)
                    and all(b > a for a, b in zip(rings, rings[1:]))):
                p.add("casing.ring_z_mm", "needs >= 2 strictly increasing positions (mm)")
                rings = []
            nc = cas.get("n_circ")
            if not (isinstance(nc, int) and nc >= 4):
                p.add("casing.n_circ", f"must be an integer >= 4, got {nc!r}")
                nc = 0
            for h, hv in cas.get("hubs", {}).items():
                hubs.append(h)
                if rings and not any(abs(float(hv.get("z_mm", math.nan)) - r) < 1e-9 for r in rings):
                    p.add(f"casing.hubs.{h}", f"z = {hv.get('z_mm')!r} mm is not on a casing ring")
                p.value(f"casing.hubs.{h}.mass", hv.get("mass"))
            for i, mt in enumerate(cas.get("mounts", [])):
                ok = (isinstance(mt.get("ring"), int) and 0 <= mt["ring"] < len(rings)
                      and isinstance(mt.get("node"), int) and 0 <= mt["node"] < (nc or 1)
                      and mt.get("dir") in (0, 1, 2))
                if not ok:
                    p.add(f"casing.mounts[{i}]", f"ring/node/dir out of range: {mt}")
                p.value(f"casing.mounts[{i}].k", mt.get("k"), allow_knob=True)
    for h, pv in data.get("pedestal", {}).items():
        if h in hubs:
            p.add(f"pedestal.{h}", "is also a casing hub")
        hubs.append(h)
        # a housing without mass leaves the mass matrix singular: no modes, no reduced rotor, no run
        p.value(f"pedestal.{h}.mass", pv.get("mass"))
        # named, not read as k = None ("pedestal.h0.k: ... got None" for a pedestal with kxx only)
        _stiffness_missing(p, f"pedestal.{h}", pv)
        for k in ("kxx", "kyy"):
            if k in pv or "k" in pv:
                p.value(f"pedestal.{h}.{k if k in pv else 'k'}", pv.get(k, pv.get("k")), allow_knob=True)

    def ref(where, r, *, hub_ok=True, ground_ok=False):
        if ground_ok and r == "ground":
            return
        if not (isinstance(r, list) and len(r) == 2):
            forms = "[spool, node]" + (', ["hub", name]' if hub_ok else "") + (' or "ground"' if ground_ok else "")
            p.add(where, f"must be {forms}, got {r!r}")
            return
        body, n = r
        if body == "hub" and hub_ok:
            if n not in hubs:
                p.add(where, f"hub {n!r} does not exist (hubs: {', '.join(hubs) or 'none'})")
        elif body not in nodes:
            p.add(where, f"spool {body!r} does not exist (spools: {', '.join(spools) or 'none'})")
        elif not _node_ok(n, nodes[body]):
            p.add(where, f"node {n!r} does not exist on spool {body!r} (nodes 0-{nodes[body] - 1})")

    for i, s in enumerate(data.get("support", [])):
        w = f"support[{i}] ({s.get('name', '')!r})"
        ref(f"{w}.a", s.get("a"), hub_ok=False)
        ref(f"{w}.b", s.get("b"), ground_ok=True)
        if fem.is_speed_dependent(s):
            _speed_table(p, w, s)
            continue
        _stiffness_missing(p, w, s)
        for k in ("kxx", "kyy"):
            if k in s or "k" in s:
                p.value(f"{w}.{k if k in s else 'k'}", s.get(k, s.get("k")))
        for k in ("cxx", "cyy"):
            p.value(f"{w}.{k if k in s else 'c'}", s.get(k, s.get("c", 0.0)), positive=False)
    attach = data.get("attach", {})
    if not isinstance(attach, dict):
        attach = {}
    for key, a in attach.items():
        try:
            attach_layout.layout({key: a})
        except ValueError as exc:
            if "has no bearing" not in str(exc):   # a rub ring's bearing is checked below, with all of them
                p.add(f"attach.{key}", str(exc).removeprefix("rotor model: ").removeprefix(f"[attach] {key!r} is "))
                continue
        if key == "oil_temperature_C":
            continue
        ref(f"attach.{key}.node", a.get("node") if isinstance(a, dict) else a, hub_ok=False)
        if key.startswith("bearing"):
            h = a.get("housing") if isinstance(a, dict) else None
            if h not in hubs:
                p.add(f"attach.{key}.housing", f"hub {h!r} does not exist (hubs: {', '.join(hubs) or 'none'})")
        if key.startswith("rubring") and f"bearing{key[len('rubring'):]}" not in attach:
            p.add(f"attach.{key}", f"no bearing{key[len('rubring'):]} in [attach] (a rub ring's ring is on the "
                                   "housing of the bearing of the same id)")
    return p.out + engine_parts.problems(data) + engine_parts.absent(data)


def _disk_inertia(p: _Problems, dw: str, dk: dict) -> None:
    """A disk's inertias: Ip and Id with a mass in kg, r_gyration_mm with a mass named by [calibration] (Ip = m r_g^2,
    Id = Ip / 2). A key of the other form is not read (model.disk_inertia): it is refused, not ignored."""
    if isinstance(dk.get("mass"), str):
        unread, how = [k for k in ("Ip", "Id") if k in dk], "a mass named by [calibration] takes them from r_gyration_mm"
        if "r_gyration_mm" not in dk:
            p.add(f"{dw}.r_gyration_mm", "missing (a mass named by [calibration] takes Ip = m r_g^2, Id = Ip / 2)")
        else:
            p.value(f"{dw}.r_gyration_mm", dk.get("r_gyration_mm"))
    else:
        unread, how = [k for k in ("r_gyration_mm",) if k in dk], "it goes with a mass named by [calibration]"
        for k in ("Ip", "Id"):
            p.value(f"{dw}.{k}", dk.get(k), positive=False)
    for k in unread:
        p.add(f"{dw}.{k}", f"not read ({how})")


def _layers(p: _Problems, w: str, r: dict, nodes: int, mats: dict) -> None:
    """The problems of a spool's ``layers`` (a second element between the nodes of an element)."""
    for i, layer in enumerate(r.get("layers", [])):
        lw = f"{w}.layers[{i}]"
        if not _node_ok(layer.get("element"), nodes - 1):
            p.add(f"{lw}.element", f"{layer.get('element')!r} out of range 0-{nodes - 2} (the element between nodes "
                                   "element and element + 1)")
        m = layer.get("material", r.get("material", "rotor"))
        if m not in mats:
            p.add(f"{lw}.material", f"{m!r} is not a [material] table")
        a = p.value(f"{lw}.d_out_mm", layer.get("d_out_mm"))
        b = p.value(f"{lw}.d_in_mm", layer.get("d_in_mm"), positive=False)
        if a is not None and b is not None and not b < a:
            p.add(lw, f"inner diameter {b:g} mm is not smaller than the outer {a:g} mm")


def _speed_table(p: _Problems, w: str, s: dict) -> None:
    """The problems of a support with coefficient tables over ``speed_rpm`` or cross-coupled coefficients."""
    speeds = s.get("speed_rpm")
    n = None
    if speeds is not None:
        if not (isinstance(speeds, list) and speeds):
            p.add(f"{w}.speed_rpm", "must be a list of speeds (rev/min) at which the coefficients are given")
            return
        for k, v in enumerate(speeds):
            p.value(f"{w}.speed_rpm[{k}]", v, positive=False)
        if all(_num(v) for v in speeds) and not all(b > a for a, b in zip(speeds, speeds[1:])):
            p.add(f"{w}.speed_rpm", "must increase strictly")
        n = len(speeds)
    for k in fem.COEFFICIENTS:
        base = "k" if k in ("kxx", "kyy") else "c" if k in ("cxx", "cyy") else None
        key = k if k in s or base is None or base not in s else base
        if key not in s:
            if k in ("kxx", "kyy"):
                p.add(w, f"{k} (or k) missing")
            continue
        v = s[key]
        vals = v if isinstance(v, list) else [v]
        if isinstance(v, list) and len(v) != (n or 0):
            p.add(f"{w}.{key}", f"has {len(v)} values; give one per speed_rpm ({n or 0})")
            continue
        for j, x in enumerate(vals):
            where = f"{w}.{key}[{j}]" if isinstance(v, list) else f"{w}.{key}"
            if k in ("kxx", "kyy"):
                p.value(where, x)
            elif k in ("cxx", "cyy"):
                p.value(where, x, positive=False)
            elif not (_num(x) and math.isfinite(x)):
                p.add(where, f"must be a finite number, got {x!r}")


def _stiffness_missing(p, where: str, table: dict) -> None:
    """Name the direct stiffnesses a support or pedestal table leaves out (neither kxx/kyy nor k for both)."""
    missing = [k for k in ("kxx", "kyy") if k not in table and "k" not in table]
    if missing:
        p.add(where, f"{' and '.join(missing)} missing: give kxx and kyy, or k for both")


def _node_ok(n, count: int) -> bool:
    return isinstance(n, int) and not isinstance(n, bool) and 0 <= n < count


def report(full: fem.FullModel) -> dict:
    """Nodes, masses [kg] and polar inertias [kg m^2] of an assembled engine (``check-engine``)."""
    data = full.data
    out = {"spools": {}, "hubs": list(full.info.get("hubs", []))}
    total = 0.0
    for s, r in data["spool"].items():
        z = np.asarray(r["z_mm"], float) * 1e-3
        d_out, d_in = fem.rotor_diameters(data, s)
        rho = float(data["material"][r.get("material", "rotor")]["rho"])
        L = np.diff(z)
        do, di = np.asarray(d_out), np.asarray(d_in)
        shaft_m = float(np.sum(rho * math.pi / 4 * (do ** 2 - di ** 2) * L))
        disks = [fem.disk_inertia(data, dk) for dk in r.get("disks", [])]
        m = shaft_m + sum(d[0] for d in disks)
        total += m
        out["spools"][s] = {
            "name": r.get("name", s), "nodes": len(z), "length_mm": float((z[-1] - z[0]) * 1e3),
            "speed_rpm": float(r["speed_rpm"]), "mass_kg": m, "shaft_mass_kg": shaft_m,
            "disk_mass_kg": sum(d[0] for d in disks), "polar_inertia_kgm2": spool_polar_inertia(data, s)}
    hub_m = 0.0
    for hv in data.get("casing", {}).get("hubs", {}).values() if data.get("casing") else ():
        hub_m += float(hv["mass"])
    for pv in data.get("pedestal", {}).values():
        hub_m += float(pv["mass"])
    out["hub_mass_kg"] = hub_m
    out["casing_mass_kg"] = float(full.info.get("casing_mass_kg", 0.0))
    out["rotor_mass_kg"] = total
    out["dof"] = full.n
    out["attach"] = {k: v for k, v in data.get("attach", {}).items()}
    return out


#: dimensions an engine written in mm does not have: a shaft section thinner than this [mm] (a 50 mm shaft written
#: in metres reads 0.05 mm) or a spool longer than this [mm] (1.2 m written in um, or a length in m x 1000 twice)
MIN_SHAFT_DIAMETER_MM = 5.0
MAX_SPOOL_LENGTH_MM = 20000.0
#: the separation margin asked between a synchronous critical speed and an operating speed when the mode's
#: amplification factor is not known (an undamped engine: no damping, so no finite factor): the order of API 684's
#: margins (:func:`required_margin`), which grow with the amplification factor to 16 % below and 26 % above
SEPARATION_MARGIN = 0.15
#: API 684's amplification factor below which a mode needs no separation margin (critically damped)
AF_NO_MARGIN = 2.5


def amplification_factor(zeta: float | None) -> float | None:
    """The amplification factor AF = 1 / (2 zeta) of a mode of damping ratio ``zeta`` (the peak's sharpness,
    N_c / (N_2 - N_1) between its half-power points, for light damping); None for an undamped mode (zeta <= 0
    or unknown)."""
    return 1.0 / (2.0 * zeta) if zeta is not None and zeta > 0.0 else None


def required_margin(af: float | None, above: bool) -> float:
    """The separation margin [fraction of the operating speed] API 684 asks of a critical speed of amplification
    factor ``af`` below (``above`` False) or above an operating speed: none for AF < 2.5; below,
    min(16, 17 (1 - 1 / (AF - 1.5))) %; above, min(26, 10 + 17 (1 - 1 / (AF - 1.5))) % (API 684 SP6.8.2.10, as
    ROSS's ross/report.py implements it; the standard's own text not consulted); :data:`SEPARATION_MARGIN` for
    an undamped mode (``af`` None)."""
    if af is None:
        return SEPARATION_MARGIN
    if af < AF_NO_MARGIN:
        return 0.0
    base = 17.0 * (1.0 - 1.0 / (af - 1.5))
    return (min(26.0, 10.0 + base) if above else min(16.0, base)) / 100.0


#: a bearing's bore fits its station when it is within this fraction of the outer diameter of a shaft section
#: (or layer) that meets at the node: an engine file's diameters are rounded, a press fit is microns
BORE_FIT = 0.02


def implausible(data: dict) -> list[str]:
    """One warning line per spool whose dimensions are implausible for lengths in mm (a valid file's; see
    :data:`MIN_SHAFT_DIAMETER_MM`, :data:`MAX_SPOOL_LENGTH_MM`)."""
    out = []
    for s, r in data.get("spool", {}).items():
        z = np.asarray(r["z_mm"], float)
        d_out = [float(fem.knob_value(data, v)) for v in r["d_out_mm"]]
        thin = [e for e, d in enumerate(d_out) if d < MIN_SHAFT_DIAMETER_MM]
        if thin:
            out.append(f"spool.{s}.d_out_mm[{thin[0]}] = {d_out[thin[0]]:g} mm: a shaft thinner than "
                       f"{MIN_SHAFT_DIAMETER_MM:g} mm ({len(thin)} section(s)); lengths are in mm (an engine written "
                       "in metres?)")
        length = float(z[-1] - z[0])
        if length > MAX_SPOOL_LENGTH_MM:
            out.append(f"spool.{s}.z_mm: a spool {length / 1e3:g} m long (above {MAX_SPOOL_LENGTH_MM / 1e3:g} m); "
                       "lengths are in mm")
    return out


def seat_diameters_mm(data: dict, spool: str, node: int) -> list[float]:
    """Outer diameters [mm] of the shaft sections (and layers) of ``spool`` that meet at ``node``: where a
    bearing attached there sits."""
    r = data["spool"][spool]
    ne = len(r["d_out_mm"])
    elems = [e for e in (node - 1, node) if 0 <= e < ne]
    out = [float(fem.knob_value(data, r["d_out_mm"][e])) for e in elems]
    out += [float(layer["d_out_mm"]) for layer in r.get("layers", []) if layer.get("element") in elems]
    return out


def bore_fit(data: dict, key: str, bore_mm: float) -> str | None:
    """A warning when the bore [mm] of the bearing ``key`` of [attach] fits no section at its node, else None."""
    spool, node = data["attach"][key]["node"]
    seats = seat_diameters_mm(data, spool, node)
    if any(abs(bore_mm - d) <= BORE_FIT * d for d in seats):
        return None
    return (f"attach.{key}: its bore {bore_mm:g} mm does not fit the shaft at node [{spool!r}, {node}] (outer "
            f"diameter {' / '.join(f'{d:g}' for d in seats)} mm; within {BORE_FIT:.0%} expected)")


def operating_speeds(data: dict) -> dict[str, list[float]]:
    """The operating speeds [rev/min] of each spool (its ``speed_rpm``, unsigned)."""
    return {s: [abs(float(r["speed_rpm"]))] for s, r in data["spool"].items()}


def destabilising(data: dict) -> list[str]:
    """The names of the supports that can destabilise the engine: cross-coupled coefficients (a skew-symmetric
    stiffness feeds energy into a forward whirl; a cross damping can make the damping indefinite). Without any,
    the linear engine cannot grow: its stiffness and damping are symmetric and not negative, its gyroscopic terms
    skew (they exchange energy between the planes, they add none)."""
    return [s.get("name", f"support[{i}]") for i, s in enumerate(data.get("support", []))
            if any(np.any(np.asarray(s.get(k, 0.0), float) != 0.0) for k in ("kxy", "kyx", "cxy", "cyx"))]


def stability(modes: list[dict], rpm: float) -> list[str]:
    """One warning line per whirl mode of ``modes`` (critical.whirl_modes at ``rpm``, the first spool's
    operating speed) whose damping ratio is negative: the mode grows, whatever the unbalance."""
    return [f"unstable {m['whirl']} whirl mode at {m['frequency_Hz']:.4g} Hz at {rpm:.0f} rev/min (damping ratio "
            f"{m['damping_ratio']:.3g}, log dec {m['log_dec']:.3g}): the linearised engine is unstable there, its "
            "response grows whatever the unbalance (the cross-coupled supports feed it)"
            for m in modes if m["damping_ratio"] < 0.0]


def separation(criticals: list[dict], spool: str, name: str, speeds: list[float]) -> tuple[list[dict], list[str]]:
    """The separation margin of each synchronous critical speed excited by ``spool`` from each of its operating
    ``speeds`` [rev/min], (critical - operating) / operating, against the margin API 684 asks of its mode
    (:func:`required_margin` of its amplification factor, from the row's ``damping_ratio``; the flat
    :data:`SEPARATION_MARGIN` for an undamped mode), and a warning line for each nearer than that: (rows
    ``{"rpm", "whirl", "spool", "damping_ratio", "amplification_factor", "margins": [{"operating_rpm",
    "margin_percent", "required_percent"}]}``, warnings)."""
    rows, warn = [], []
    for c in criticals:
        af = amplification_factor(c.get("damping_ratio"))
        margins = []
        for op in speeds:
            m = (c["rpm"] - op) / op
            need = required_margin(af, above=m > 0.0)
            margins.append({"operating_rpm": op, "margin_percent": 100.0 * m, "required_percent": 100.0 * need})
            if abs(m) < need:
                rule = (f"API 684 asks a separation margin of {need:.1%} of a mode of amplification factor "
                        f"{af:.2f}" if af is not None else
                        f"API 684 asks a separation margin of the order of {need:.0%} (an undamped mode: no "
                        "amplification factor)")
                warn.append(f"spool {spool} ({name}): {c['whirl']} critical speed {c['rpm']:.0f} rev/min is "
                            f"{100 * abs(m):.1f} % {'below' if m < 0 else 'above'} the operating speed {op:.0f} "
                            f"rev/min; {rule}")
        rows.append({**c, "damping_ratio": c.get("damping_ratio"), "amplification_factor": af, "spool": spool,
                     "margins": margins})
    return rows, warn
