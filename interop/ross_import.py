"""ROSS rotors to rotorcosim's engine format.

:func:`from_ross` takes a ``ross.Rotor`` / ``ross.CoAxialRotor``, or the path of a file written by its
``Rotor.save`` (read without ROSS, :mod:`.ross_toml`), and returns an engine description (a dict; write it with
:func:`rotorcosim.interop.write_engine`):

* shaft elements -> spools: a chain of elements whose nodes follow each other is one spool (a coaxial rotor
  gives two); each element one section (uniform only: a tapered element is an error naming it); a further
  element between the same two nodes (ROSS's layered sections) a layer of that element (``layers``); their
  materials keep ROSS's E, G_s, rho;
* disks -> disks (m, Ip, Id);
* bearings and seals -> linear supports (kxx, kyy, cxx, cyy, the cross-coupled kxy, kyx, cxy, cyx, kzz as
  k_axial) to ground, to another spool's node (``n_link``) or to a pedestal (a ROSS node on no shaft, whose
  point mass and ground bearing make it one); speed-dependent coefficients become coefficient tables over
  ``speed_rpm`` (ROSS's ``frequency``), or, when ``speed_rpm_coefficients`` names a speed, their values there
  (linear interpolation); mass coefficients are errors;
* each spool turns at ``speed_rpm`` (ROSS's files carry no operating speed); its torsion and axial motion are
  held at its first node (ROSS leaves them free: rigid modes that no lateral result depends on);
* the shaft elements' options: ROSS's ``alpha``, ``beta`` (Rayleigh damping of each element, C_e = alpha M_e +
  beta K_e) as the spool's ``rayleigh``, ``shear_effects = false`` (Euler-Bernoulli) and ``rotary_inertia =
  false`` as the spool's keys of those names; no structural damping besides ([damping] zeta = 0).

``attach`` makes ROSS bearings the co-simulated ball bearings ("bearing<ID>": any number, any ids): a bearing to
ground has its linear coefficients become a pedestal (the housing, ``hub_mass_kg``) on which the ball bearing and
its squeeze film damper sit; a bearing linked to a pedestal (a ROSS point mass on its own bearing to ground, as
in ROSS's coaxial rotor) is replaced by the ball bearing and its damper, the pedestal being their housing; an
intershaft bearing (linked to another shaft's node) is refused, the ball bearing's outer race sitting still in a
damper on a housing. The rub rings go to the same nodes and the unbalance to ``unbalance_node``.

Example::

    engine = from_ross("rotor_example.toml", attach={"bearing0": 0, "bearing5": 6}, unbalance_node=2)
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorcosim.components.rotor.attach import ID
from rotorcosim.components.rotor.model import MAX_SPOOLS
from rotorcosim.scenarios import natural_key

from . import ross_toml

#: the speed given to the spools when the caller gives none [rev/min]
DEFAULT_SPEED_RPM = 10000.0
#: the housing mass of a co-simulated bearing's pedestal when the caller gives none [kg]
DEFAULT_HUB_MASS_KG = 3.0
RPM = np.pi / 30.0


class RossImportError(ValueError):
    """A ROSS rotor that the engine format cannot express; the message names the element."""


def _live(rotor) -> dict:
    """The elements of a live ross.Rotor as :func:`ross_toml.read` gives them."""
    def arr(b, k):
        v = getattr(b, k, 0)
        return [float(x) for x in np.atleast_1d(v)] if v is not None else [0.0]

    out = {"version": "live", "shafts": [], "disks": [], "bearings": [], "point_masses": [],
           "nodes_pos": [float(x) for x in rotor.nodes_pos]}
    for e in rotor.shaft_elements:
        out["shafts"].append({"kind": "ShaftElement", "tag": e.tag, "n": int(e.n), "L": float(e.L),
                              "idl": float(e.idl), "odl": float(e.odl), "idr": float(e.idr), "odr": float(e.odr),
                              "alpha": float(getattr(e, "alpha", 0.0)), "beta": float(getattr(e, "beta", 0.0)),
                              "shear_effects": bool(e.shear_effects), "rotary_inertia": bool(e.rotary_inertia),
                              "gyroscopic": bool(e.gyroscopic),
                              "material": {"name": e.material.name, "rho": float(e.material.rho),
                                           "E": float(e.material.E), "G_s": float(e.material.G_s)}})
    for d in rotor.disk_elements:
        out["disks"].append({"kind": "DiskElement", "tag": d.tag, "n": int(d.n), "m": float(d.m),
                             "Id": float(d.Id), "Ip": float(d.Ip)})
    for b in rotor.bearing_elements:
        freq = getattr(b, "frequency", None)
        row = {"kind": type(b).__name__, "tag": b.tag, "n": int(b.n),
               "n_link": None if b.n_link is None else int(b.n_link),
               "frequency": None if freq is None else [float(x) for x in np.atleast_1d(freq)]}
        for k in ("kxx", "kyy", "kxy", "kyx", "cxx", "cyy", "cxy", "cyx", "kzz", "mxx", "myy", "mxy", "myx"):
            row[k] = arr(b, k)
        out["bearings"].append(row)
    for pm in getattr(rotor, "point_mass_elements", []) or []:
        out["point_masses"].append({"kind": "PointMass", "tag": pm.tag, "n": int(pm.n), "mx": float(pm.mx),
                                    "my": float(pm.my)})
    return out


def _values(b: dict, key: str) -> list[float]:
    v = b.get(key, [0.0])
    return [float(x) for x in np.atleast_1d(v)] if v is not None else [0.0]


def _table(b: dict, what: str) -> dict | None:
    """The support entry's coefficients of a ROSS bearing or seal whose coefficients depend on speed: speed_rpm
    (ROSS's ``frequency``) and per coefficient its values there (one value when it is constant; cross-coupled
    ones only when not zero); None for a bearing of constant coefficients."""
    keys = ("kxx", "kyy", "kxy", "kyx", "cxx", "cyy", "cxy", "cyx")
    vals = {k: _values(b, k) for k in keys + ("kzz",)}
    if all(len(v) == 1 for v in vals.values()):
        return None
    freq = b.get("frequency")
    n = max(len(v) for v in vals.values())
    if freq is None or len(freq) != n:
        raise RossImportError(f"ROSS {what}: coefficients of {n} values but no matching frequency")
    if len(set(vals["kzz"])) > 1:
        raise RossImportError(f"ROSS {what}: a speed-dependent kzz is not carried")
    out = {"speed_rpm": [float(f) / RPM for f in freq]}
    for k in keys:
        v = vals[k]
        if k in ("kxy", "kyx", "cxy", "cyx") and not any(v):
            continue
        out[k] = v if len(v) > 1 else v[0]
    if vals["kzz"][0] > 0:
        out["k_axial"] = vals["kzz"][0]
    return out


def _coefficient(b: dict, key: str, speed_rpm: float | None) -> float:
    v = b.get(key, [0.0])
    v = [float(x) for x in np.atleast_1d(v)] if v is not None else [0.0]
    if len(v) == 1:
        return v[0]
    freq = b.get("frequency")
    if speed_rpm is None:
        raise RossImportError(f"ROSS {b['kind']} {b['tag']!r}: {key} depends on speed ({len(v)} values); give the "
                              "speed to take the coefficients at (--coefficients-at RPM)")
    if freq is None or len(freq) != len(v):
        raise RossImportError(f"ROSS {b['kind']} {b['tag']!r}: {key} has {len(v)} values but no matching frequency")
    f = np.asarray(freq, float)
    lo, hi = float(f.min()) / RPM, float(f.max()) / RPM
    # beyond its speeds the interpolation would hold the end value, where ROSS extrapolates: not ROSS's rotor
    if not lo * (1 - 1e-9) <= speed_rpm <= hi * (1 + 1e-9):
        raise RossImportError(f"ROSS {b['kind']} {b['tag']!r}: --coefficients-at {speed_rpm:g} rev/min is outside the "
                              f"speeds its {key} is given at ({lo:.6g} to {hi:.6g} rev/min)")
    return float(np.interp(speed_rpm * RPM, f, np.asarray(v, float)))


def from_ross(rotor, *, speed_rpm: float | None = None, speed_rpm_coefficients: float | None = None,
              attach: dict | None = None, unbalance_node: int | None = None,
              hub_mass_kg: float = DEFAULT_HUB_MASS_KG, name: str | None = None) -> dict:
    """The engine description of ``rotor`` (a ``ross.Rotor``, or the path of a ROSS TOML file).

    ``speed_rpm``: the spools' speed (default: the rotor's ``rated_w``, else :data:`DEFAULT_SPEED_RPM`);
    ``speed_rpm_coefficients``: the speed at which speed-dependent bearing coefficients are taken (None: such a
    bearing is an error); ``attach``: {"bearing<ID>": ROSS node, ...} of the ROSS bearings to become the
    co-simulated ball bearings (ids of letters, digits or _); ``unbalance_node``: the ROSS node of the blade loss (default: the
    first disk's); ``hub_mass_kg``: the housing mass of each attached bearing's pedestal."""
    if isinstance(rotor, (str, Path)):
        el = ross_toml.read(rotor)
        source = f"ROSS file {Path(rotor).name} (ROSS {el['version']})"
    else:
        el = _live(rotor)
        source = f"ross.{type(rotor).__name__}"
        if speed_rpm is None and getattr(rotor, "rated_w", None):
            speed_rpm = float(rotor.rated_w) / RPM
    speed = float(speed_rpm) if speed_rpm is not None else DEFAULT_SPEED_RPM
    if not (np.isfinite(speed) and speed > 0):
        raise RossImportError(f"speed must be a finite number > 0 rev/min, got {speed_rpm!r}")
    if unbalance_node is not None and not attach:
        raise RossImportError("--unbalance-node places the blade loss of the co-simulated bearings: it applies with "
                              "--attach only (without it the engine has no [attach] table)")
    if speed_rpm_coefficients is not None and not (np.isfinite(speed_rpm_coefficients) and speed_rpm_coefficients >= 0):
        raise RossImportError(f"--coefficients-at must be a finite speed >= 0 rev/min, got {speed_rpm_coefficients!r}")
    if not (isinstance(hub_mass_kg, (int, float)) and np.isfinite(hub_mass_kg) and hub_mass_kg > 0):
        raise RossImportError(f"hub mass (--hub-mass) must be a finite mass > 0 kg, got {hub_mass_kg!r}")
    _check_elements(el)

    # spools: chains of shaft elements
    shafts = sorted(el["shafts"], key=lambda e: int(e["n"]))
    for e in shafts:
        if e.get("idr", e["idl"]) != e["idl"] or e.get("odr", e["odl"]) != e["odl"]:
            raise RossImportError(f"ROSS shaft element {e['tag']!r} is tapered (odl {e['odl']}, odr {e['odr']}, idl "
                                  f"{e['idl']}, idr {e['idr']} m); the engine format has uniform sections: split it "
                                  "into uniform elements in ROSS")
        if e.get("gyroscopic", True) is False:
            raise RossImportError(f"ROSS shaft element {e['tag']!r}: gyroscopic = false is not carried (rotorcosim's "
                                  "elements always have their gyroscopic terms)")
    # layered sections: a second (third...) element between the same two nodes becomes a layer of the first
    layered: dict[int, list[dict]] = {}
    main = []
    for e in shafts:
        if main and int(main[-1]["n"]) == int(e["n"]):
            layered.setdefault(int(e["n"]), []).append(e)
        else:
            main.append(e)
    shafts = main
    chains: list[list[dict]] = []
    for e in shafts:
        if chains and int(chains[-1][-1]["n"]) + 1 == int(e["n"]):
            chains[-1].append(e)
        else:
            chains.append([e])
    if len(chains) > MAX_SPOOLS:
        raise RossImportError(f"ROSS rotor with {len(chains)} shafts; the engine format carries at most "
                              f"{MAX_SPOOLS} spools")
    names = ["shaft"] if len(chains) == 1 else ["inner", "outer"] if len(chains) == 2 else \
        [f"shaft{i}" for i in range(len(chains))]
    where: dict[int, tuple[str, int]] = {}       # ROSS node -> (spool, local node)
    materials: dict[tuple, str] = {}
    engine: dict = {"engine": {"format": 1, "name": name or f"imported from {source}",
                               "source": source},
                    "material": {}, "damping": {"zeta": 0.0, "f1_Hz": 1.0, "f2_Hz": 2.0}, "spool": {}}
    pos = el.get("nodes_pos")
    for s, chain in zip(names, chains):
        first = int(chain[0]["n"])
        z0 = float(pos[first]) if pos else 0.0
        z = [z0]
        for e in chain:
            z.append(z[-1] + float(e["L"]))
        for k in range(len(chain) + 1):
            where[first + k] = (s, k)
        def material(m):
            key = (float(m["E"]), float(m["G_s"]), float(m["rho"]))
            if key not in materials:
                label = "".join(c if c.isalnum() else "_" for c in str(m.get("name", "material"))) or "material"
                if label in engine["material"]:
                    label = f"{label}_{len(materials)}"
                materials[key] = label
                engine["material"][label] = {"E": key[0], "G": key[1], "rho": key[2]}
            return materials[key]

        mats = [material(e["material"]) for e in chain]
        layers = [{"element": k, "d_out_mm": float(x["odl"]) * 1e3, "d_in_mm": float(x["idl"]) * 1e3,
                   "material": material(x["material"])}
                  for k, e in enumerate(chain) for x in layered.get(int(e["n"]), [])]
        if len(set(mats)) > 1:
            raise RossImportError(f"ROSS shaft {s}: elements of {len(set(mats))} materials; the engine format has "
                                  "one material per spool")
        engine["spool"][s] = {"name": s, "speed_rpm": speed, "material": mats[0],
                              "z_mm": [v * 1e3 for v in z],
                              "d_out_mm": [float(e["odl"]) * 1e3 for e in chain],
                              "d_in_mm": [float(e["idl"]) * 1e3 for e in chain],
                              "drive_node": 0, "axial_node": 0, "disks": [],
                              **_beam_options(s, chain, layered)}
        if layers:
            engine["spool"][s]["layers"] = layers

    def node(n, what):
        if n not in where:
            raise RossImportError(f"ROSS {what}: node {n} is on no shaft")
        return list(where[n])

    for d in el["disks"]:
        s, k = node(int(d["n"]), f"disk {d['tag']!r}")
        engine["spool"][s]["disks"].append({"node": k, "name": str(d["tag"]), "mass": float(d["m"]),
                                            "Ip": float(d["Ip"]), "Id": float(d["Id"])})

    # extra nodes (on no shaft): pedestals, from their point masses and their bearings to ground
    pedestals: dict[int, dict] = {}
    for pm in el["point_masses"]:
        n = int(pm["n"])
        if n in where:
            raise RossImportError(f"ROSS point mass {pm['tag']!r} on shaft node {n}: not carried (a disk with Ip = "
                                  "Id = 0 is)")
        mx = float(pm.get("mx", pm.get("m", 0.0)) or 0.0)
        my = float(pm.get("my", pm.get("m", 0.0)) or 0.0)
        if mx != my:
            raise RossImportError(f"ROSS point mass {pm['tag']!r}: mx != my is not carried")
        pedestals.setdefault(n, {"mass": 0.0})["mass"] += mx
    supports = []
    pedestal_nodes = {int(pm["n"]) for pm in el["point_masses"]}
    attach = dict(attach or {})
    for key in attach:
        if not (key.startswith("bearing") and ID.match(key[len("bearing"):])):
            raise RossImportError(f"attach: {key!r} is not bearing<ID> (an id of letters, digits or _)")
    attached: dict[str, dict] = {}
    for b in el["bearings"]:
        what = f"{b['kind']} {b['tag']!r}"
        for k in ("mxx", "myy", "mxy", "myx"):
            if k in b and any(v != 0.0 for v in _values(b, k)):
                raise RossImportError(f"ROSS {what}: added mass {k} is not carried")
        table = _table(b, what) if speed_rpm_coefficients is None else None
        if table is None:
            co = {k: _coefficient(b, k, speed_rpm_coefficients) for k in ("kxx", "kyy", "cxx", "cyy", "kzz", "kxy",
                                                                          "kyx", "cxy", "cyx")}
        n, link = int(b["n"]), b.get("n_link")
        link = None if link is None or link == "None" else int(link)
        cross = table is not None or any(co[k] != 0.0 for k in ("kxy", "kyx", "cxy", "cyx"))
        if cross and (n not in where or n in attach.values()):
            kind = "speed-dependent" if table is not None else "cross-coupled"
            raise RossImportError(f"ROSS {what}: {kind} coefficients at node {n}, "
                                  + ("a pedestal's bearing to ground: not carried (give --coefficients-at RPM)"
                                     if n not in where else "which a co-simulated bearing's pedestal cannot carry "
                                     "(leave it a linear support, or give --coefficients-at RPM)"))
        if n not in where:                     # a pedestal's own bearing to ground
            if link is not None:
                raise RossImportError(f"ROSS {what}: links node {n} (on no shaft) to node {link}: not carried")
            p = pedestals.setdefault(n, {"mass": 0.0})
            if "kxx" in p:
                raise RossImportError(f"ROSS {what}: a second bearing to ground at node {n}")
            p.update(kxx=co["kxx"], kyy=co["kyy"], cxx=co["cxx"], cyy=co["cyy"], kzz=co["kzz"], tag=b["tag"])
            continue
        key = next((a for a, v in attach.items() if int(v) == n), None)
        if key is not None:
            if link is not None and link in where:
                grounded = sorted(int(x["n"]) for x in el["bearings"] if int(x["n"]) in where
                                  and x.get("n_link") in (None, "None", *pedestal_nodes))
                raise RossImportError(
                    f"ROSS {what} links node {n} to node {link} of a shaft (an intershaft bearing), which the "
                    f"co-simulated ball bearing {key} cannot be (its outer race sits still in a damper on a housing): "
                    f"attach a bearing to ground or to a pedestal instead (ROSS nodes {', '.join(map(str, grounded))}"
                    ") or leave it a linear support")
            # to ground: its coefficients become the housing's pedestal; to a pedestal node (a ROSS point mass on
            # its own bearing to ground): that pedestal is the housing, and the ball bearing and its damper take
            # the place of the ROSS bearing between shaft and housing
            attached[key] = {"node": node(n, what), "co": co, "tag": b["tag"], "housing": link}
            continue
        sup = {"name": str(b["tag"]), "a": node(n, what)}
        if link is None:
            sup["b"] = "ground"
        elif link in where:
            sup["b"] = node(link, what)
        else:
            sup["b"] = ["hub", f"n{link}"]
            pedestals.setdefault(link, {"mass": 0.0})
        if table is not None:
            sup.update(table)
        else:
            sup.update({"kxx": co["kxx"], "kyy": co["kyy"], "cxx": co["cxx"], "cyy": co["cyy"]})
            sup.update({k: co[k] for k in ("kxy", "kyx", "cxy", "cyx") if co[k] != 0.0})
            if co["kzz"] > 0:
                sup["k_axial"] = co["kzz"]
        supports.append(sup)
    missing = sorted(set(attach) - set(attached))
    if attached:
        # the spin and axial DOF are held at a node of no co-simulated bearing (whose axial motion is a port)
        taken = {tuple(a["node"]) for a in attached.values()}
        for sname, sp in engine["spool"].items():
            free = [k for k in range(len(sp["z_mm"])) if (sname, k) not in taken]
            sp["drive_node"] = sp["axial_node"] = free[-1]
    if missing:
        raise RossImportError(f"attach: no ROSS bearing (to ground) at node(s) "
                              f"{', '.join(str(attach[k]) for k in missing)} for {', '.join(missing)}")
    peds = {}
    for n, p in sorted(pedestals.items()):
        if "kxx" not in p:
            raise RossImportError(f"ROSS node {n} (on no shaft) has no bearing to ground: not carried")
        peds[f"n{n}"] = _pedestal(p, f"ROSS node {n}")
    for key, a in sorted(attached.items(), key=lambda kv: natural_key(kv[0])):
        if a["housing"] is not None:
            hub = f"n{a['housing']}"
            if peds[hub]["mass"] == 0.0:
                peds[hub]["mass"] = float(hub_mass_kg)       # a massless ROSS pedestal: the housing's mass
            a["hub"] = hub
            continue
        hub = a["hub"] = f"h{key[len('bearing'):]}"
        peds[hub] = _pedestal({**a["co"], "mass": hub_mass_kg}, f"ROSS bearing {a['tag']!r}")
    if supports:
        engine["support"] = supports
    if peds:
        engine["pedestal"] = peds
    if attached:
        if unbalance_node is None:
            if not el["disks"]:
                raise RossImportError("attach: the rotor has no disk; give the unbalance node")
            unbalance_node = int(el["disks"][0]["n"])
        ids = sorted((k[len("bearing"):] for k in attached), key=natural_key)
        engine["attach"] = {
            **{f"bearing{i}": {"node": attached[f"bearing{i}"]["node"], "housing": attached[f"bearing{i}"]["hub"]}
               for i in ids},
            **{f"rubring{i}": {"node": attached[f"bearing{i}"]["node"]} for i in ids},
            "unbalance": {"node": node(int(unbalance_node), "unbalance")},
            "oil_temperature_C": 30.0}
    return engine


def _beam_options(s: str, chain: list[dict], layered: dict[int, list[dict]]) -> dict:
    """The spool keys of ROSS's element options along ``chain`` (its elements, ``layered``: their layers by
    ROSS element number): ``shear_effects`` and ``rotary_inertia`` where false (one value per spool: mixed values
    are an error naming the shaft), and ``rayleigh`` (alpha, beta: one number where every element has the same,
    else one per element; a layer must have its element's) where any is not 0."""
    out: dict = {}
    for flag in ("shear_effects", "rotary_inertia"):
        values = {bool(x.get(flag, True)) for e in chain for x in [e, *layered.get(int(e["n"]), [])]}
        if len(values) > 1:
            raise RossImportError(f"ROSS shaft {s}: elements with {flag} true and false; the engine format has one "
                                  f"{flag} per spool")
        if values == {False}:
            out[flag] = False
    ray = {}
    for key in ("alpha", "beta"):
        vals = [float(e.get(key, 0.0)) for e in chain]
        for e, v in zip(chain, vals):
            for x in layered.get(int(e["n"]), []):
                if float(x.get(key, 0.0)) != v:
                    raise RossImportError(f"ROSS shaft element {x['tag']!r}: a layer of Rayleigh {key} "
                                          f"{x.get(key, 0.0)!r} on an element of {v!r}; the engine format gives a "
                                          "layer its element's")
        if any(v != 0.0 for v in vals):
            ray[key] = vals[0] if len(set(vals)) == 1 else vals
    if ray:
        out["rayleigh"] = ray
    return out


def _number(e: dict, key: str, what: str, *, positive: bool = False, inner_of: str | None = None) -> float:
    """The element's ``key`` as a finite number (> 0 with ``positive``, else >= 0); RossImportError naming the
    element and the key otherwise."""
    if key not in e:
        raise RossImportError(f"ROSS {what}: {key} missing")
    v = e[key]
    ok = isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v) and (v > 0 if positive else v >= 0)
    if not ok:
        raise RossImportError(f"ROSS {what}: {key} must be a finite number {'> 0' if positive else '>= 0'}, got {v!r}")
    if inner_of is not None and not v < e[inner_of]:
        raise RossImportError(f"ROSS {what}: inner diameter {key} = {v!r} m is not smaller than the outer "
                              f"{inner_of} = {e[inner_of]!r} m")
    return float(v)


def _check_elements(el: dict) -> None:
    """Every value the engine file takes from the ROSS elements, checked and named by element and key before
    anything is written (the engine file's own checks would name only the engine key it became)."""
    for e in el["shafts"]:
        what = f"ShaftElement {e.get('tag')!r}"
        _number(e, "L", what, positive=True)
        for side in ("l", "r"):
            if f"od{side}" in e or side == "l":
                _number(e, f"od{side}", what, positive=True)
                _number(e, f"id{side}", what, inner_of=f"od{side}")
        m = e.get("material")
        if not isinstance(m, dict):
            raise RossImportError(f"ROSS {what}: material missing")
        for k in ("E", "G_s", "rho"):
            _number(m, k, f"{what} material {m.get('name', '')!r}", positive=True)
    for d in el["disks"]:
        for k in ("m", "Ip", "Id"):
            _number(d, k, f"DiskElement {d.get('tag')!r}")
    for b in el["bearings"]:
        for k in ("kxx", "kyy", "kxy", "kyx", "cxx", "cyy", "cxy", "cyx", "kzz"):
            v = b.get(k, [0.0])
            vals = [v] if not isinstance(v, (list, tuple, np.ndarray)) else list(v)
            if not all(isinstance(x, (int, float, np.floating, np.integer)) and not isinstance(x, bool)
                       and np.isfinite(x) for x in vals):
                raise RossImportError(f"ROSS {b.get('kind', 'BearingElement')} {b.get('tag')!r}: {k} must be finite "
                                      f"numbers, got {v!r}")


def _pedestal(p: dict, what: str) -> dict:
    out = {"mass": float(p["mass"])}
    if p["kxx"] == p["kyy"]:
        out["k"] = p["kxx"]
    else:
        out["kxx"], out["kyy"] = p["kxx"], p["kyy"]
    if p["cxx"] == p["cyy"]:
        out["c"] = p["cxx"]
    else:
        out["cxx"], out["cyy"] = p["cxx"], p["cyy"]
    if p.get("kzz", 0.0) > 0:
        out["k_axial"] = p["kzz"]
    return out
