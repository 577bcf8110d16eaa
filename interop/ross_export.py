"""An engine of rotorcosim's format as a ``ross.Rotor`` (needs ROSS: ``pip install "rotorcosim[ross]"``).

What goes over: each shaft section as a uniform ``ShaftElement`` (the material's E, G, rho; the [damping]
table's Rayleigh coefficients plus the spool's own ``rayleigh`` on every element when ``damped``; the spool's
``shear_effects`` and ``rotary_inertia``), disks as ``DiskElement``, linear supports as
``BearingElement`` (to ground, or through ``n_link`` to a pedestal's node, which carries the pedestal's mass as a
``PointMass`` and its springs to ground). The co-simulated bearings the file attaches are linearised as
``rotorcosim critical-speeds`` does (the scenario's ball contacts at the preloaded rest -> outer race + journal
body -> O-ring + film at the stated oil temperature -> housing, :mod:`rotorcosim.cases.blade_loss.linear_engine`):
contact bearing from the shaft node to a journal node (``PointMass``), O-ring + film from it to the housing's node.
A fused bearing's (``[fuse.ID]``) O-ring + film end at its own housing's node (``PointMass`` of ``housing_mass_kg``),
which the fuse at the stage asked for (``fuse_stage``: 0 intact, 1 broken, 2 broken in its second stage) links to
the hub.

Two spools become a ``ross.CoAxialRotor`` (nodes numbered shaft after shaft; ROSS turns both at one speed, so an
engine whose spools turn at different speeds gets ROSS's gyroscopic terms at the first spool's). Not carried (an
error naming it): a casing shell (ROSS has no solid elements). The Rayleigh damping of
disks and hub masses (rotorcosim damps M as a whole) is left out: ROSS's coefficients act per shaft element.

Example::

    rotor = to_ross("my_engine/engine.toml", scenario="my_engine/blade_loss.toml")
    rotor.run_campbell(np.linspace(0, 2000, 41)).plot()
"""
from __future__ import annotations

import math
from pathlib import Path

from rotorcosim.components.rotor import attach as attach_layout
from rotorcosim.components.rotor import engine_check
from rotorcosim.components.rotor import model as fem


def _load(engine) -> tuple[dict, str]:
    if isinstance(engine, (str, Path)):
        data, _ = fem.load_data(engine)
        return data, str(engine)
    return engine, "engine description"


def linear_supports(data: dict, scenario=None, fuse_stage: int = 0) -> dict | None:
    """The attached co-simulated bearings linearised (None: the engine attaches none), fuses at ``fuse_stage``."""
    attach = data.get("attach", {})
    if not attach_layout.layout(attach).bearings:
        return None
    from rotorcosim.cases.blade_loss import linear_engine
    from rotorcosim.master.scenario.build import load_scenario

    sc = load_scenario(scenario) if isinstance(scenario, (str, Path)) else scenario
    return linear_engine.supports(sc, data=data, fuse_stage=fuse_stage)


def to_ross(engine, *, scenario=None, damped: bool = True, fuse_stage: int = 0):
    """A ``ross.Rotor`` of the engine (a file path or an engine description); ``scenario``: the scenario (path
    or Scenario) whose components linearise the attached bearings (None: the shipped blade-loss scenario);
    ``damped``: False leaves every damping out (undamped critical speeds, as rotorcosim reports them);
    ``fuse_stage``: the fused bearings' fuses intact (0) or broken (1, 2)."""
    try:
        import ross as rs
    except ImportError:
        raise ImportError("to_ross needs ROSS: pip install \"rotorcosim[ross]\"") from None
    data, where = _load(engine)
    found = engine_check.problems(data)
    if found:
        raise ValueError(f"{where}: {found[0]}" + (f" (and {len(found) - 1} more: rotorcosim check-engine)"
                                                   if len(found) > 1 else ""))
    if data.get("casing"):
        raise ValueError(f"{where}: a casing shell (8-node solids) has no ROSS element; to_ross carries rotors, "
                         "supports and pedestals")
    spools = data["spool"]
    alpha = beta = 0.0
    if damped:
        d = data["damping"]
        w1, w2 = 2 * math.pi * d["f1_Hz"], 2 * math.pi * d["f2_Hz"]
        alpha, beta = 2 * d["zeta"] * w1 * w2 / (w1 + w2), 2 * d["zeta"] / (w1 + w2)
    first: dict[str, int] = {}             # spool -> its first node's number in ROSS (spools numbered on)
    shafts = []
    n_next = 0
    for sname, sp in spools.items():
        mat = data["material"][sp.get("material", "rotor")]
        G = mat["G"] if "G" in mat else mat["E"] / (2.0 * (1.0 + mat["nu"]))
        material = rs.Material(name=sp.get("material", "rotor"), rho=mat["rho"], E=mat["E"], G_s=G)
        d_out, d_in = fem.rotor_diameters(data, sname)
        z = [v * 1e-3 for v in sp["z_mm"]]
        first[sname] = n_next
        layers = sp.get("layers", [])
        if layers and len(spools) > 1:
            raise ValueError(f"{where}: spool.{sname}.layers: to_ross carries layered sections on a single spool "
                             "only (ROSS's CoAxialRotor numbers its elements itself)")
        elems = []
        beam = fem.element_options(sp, sname, len(z) - 1)
        for e in range(len(z) - 1):
            # the element's own Rayleigh damping on top of the structure's (both C = alpha M + beta K of it)
            opts = {"alpha": alpha + (beam.alpha[e] if damped else 0.0),
                    "beta": beta + (beam.beta[e] if damped else 0.0),
                    "shear_effects": beam.shear, "rotary_inertia": beam.rotary}
            # a layered section: ROSS's further ShaftElement between the same two nodes (n given)
            elems.append(rs.ShaftElement(L=z[e + 1] - z[e], idl=d_in[e], odl=d_out[e], material=material,
                                         tag=f"{sname} section {e}", **opts, **({"n": e} if layers else {})))
            for i, layer in enumerate(x for x in layers if x["element"] == e):
                lm = data["material"][layer.get("material", sp.get("material", "rotor"))]
                lmat = rs.Material(name=layer.get("material", "layer"), rho=lm["rho"], E=lm["E"],
                                   G_s=lm["G"] if "G" in lm else lm["E"] / (2.0 * (1.0 + lm["nu"])))
                elems.append(rs.ShaftElement(L=z[e + 1] - z[e], idl=layer["d_in_mm"] * 1e-3,
                                             odl=layer["d_out_mm"] * 1e-3, material=lmat, n=e,
                                             tag=f"{sname} section {e} layer {i}", **opts))
        shafts.append(elems)
        n_next += len(z)

    def gnode(ref) -> int:
        return first[ref[0]] + int(ref[1])

    disks = []
    for sname, sp in spools.items():
        for dk in sp.get("disks", []):
            m, Ip, Id = fem.disk_inertia(data, dk)
            disks.append(rs.DiskElement(n=gnode([sname, dk["node"]]), m=m, Id=Id, Ip=Ip,
                                        tag=str(dk.get("name", "disk"))))
    bearings, masses = [], []
    hub_node: dict[str, int] = {}

    def c(v):
        return float(v) if damped else 0.0

    def hub(h):
        nonlocal n_next
        if h not in hub_node:
            pv = data["pedestal"][h]
            hub_node[h] = n = n_next
            n_next += 1
            if pv["mass"] > 0:
                masses.append(rs.PointMass(n=n, m=float(pv["mass"]), tag=f"hub {h}"))
            kx, ky = (fem.knob_value(data, pv.get(k, pv.get("k"))) for k in ("kxx", "kyy"))
            cx, cy = (pv.get(k, pv.get("c", 0.0)) for k in ("cxx", "cyy"))
            bearings.append(rs.BearingElement(n=n, kxx=kx, kyy=ky, cxx=c(cx), cyy=c(cy), tag=f"pedestal {h}"))
        return hub_node[h]

    for s in data.get("support", []):
        a, b = s["a"], s["b"]
        kx, ky = (s.get(k, s.get("k")) for k in ("kxx", "kyy"))
        cx, cy = (s.get(k, s.get("c", 0.0)) for k in ("cxx", "cyy"))
        if b == "ground":
            link = None
        elif b[0] == "hub":
            link = hub(b[1])
        else:
            link = gnode(b)
        # cross-coupled coefficients, and coefficient tables over speed (ROSS's frequency, rad/s)
        extra = {k: s[k] if k.startswith("k") else (s[k] if damped else 0.0)
                 for k in ("kxy", "kyx", "cxy", "cyx") if k in s}
        if "speed_rpm" in s:
            extra["frequency"] = [v * math.pi / 30.0 for v in s["speed_rpm"]]
            cx, cy = (v if damped else 0.0 for v in (cx, cy))
        else:
            cx, cy = c(cx), c(cy)
        bearings.append(rs.BearingElement(n=gnode(a), n_link=link, kxx=kx, kyy=ky, cxx=cx, cyy=cy,
                                          kzz=s.get("k_axial", 0.0), tag=str(s.get("name", "support")), **extra))
    sup = linear_supports(data, scenario, fuse_stage)
    for key, v in (sup or {}).items():
        node = v["node"]
        j = n_next
        n_next += 1
        h = hub(v["hub"])
        fuse = v.get("fuse")
        if fuse is not None:
            # the bearing's own housing on the fuse to the hub
            hf = n_next
            n_next += 1
            masses.append(rs.PointMass(n=hf, m=float(data["fuse"][key[1:]]["housing_mass_kg"]),
                                       tag=f"housing {key} on its fuse"))
            bearings.append(rs.BearingElement(n=hf, n_link=h, kxx=fuse["k"], cxx=c(fuse["c"]),
                                              tag=f"fuse {key}"))
            h = hf
        masses.append(rs.PointMass(n=j, m=v["m_journal"], tag=f"journal {key}"))
        bearings.append(rs.BearingElement(n=gnode(node), n_link=j, kxx=v["k_contact"], cxx=0.0,
                                          tag=f"ball contacts {key}"))
        bearings.append(rs.BearingElement(n=j, n_link=h, kxx=v["k_spring"], cxx=c(v["c_film"]),
                                          tag=f"O-ring + film {key}"))
    tag = data.get("engine", {}).get("name", "rotorcosim engine")
    if len(shafts) == 2:
        # ROSS numbers a coaxial rotor's nodes shaft after shaft, as above; both shafts turn at one speed there
        return rs.CoAxialRotor(shafts, disk_elements=disks, bearing_elements=bearings,
                               point_mass_elements=masses or None, tag=tag)
    return rs.Rotor(shafts[0], disk_elements=disks, bearing_elements=bearings, point_mass_elements=masses or None,
                    tag=tag)
