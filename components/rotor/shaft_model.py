"""A single shaft on linear supports to ground, as a rotor model file (``[shaft]``): the rotor component's model
for test rotors such as the Jeffcott rotor of the ``jeffcott_rundown`` check case.

The same Timoshenko elements and disks as the engine (beam.py), assembled into the FullModel the rotor component
reduces by MTA (model.FullModel): M q'' + (C + Omega G) q + K q = F, 6 DOF per node. The file::

    [shaft]
    z_mm = [0.0, 250.0, 500.0]             # stations (nodes), strictly increasing
    d_out_mm = [20.0, 20.0]                # per element
    d_in_mm = [0.0, 0.0]
    material = { E = 2.1e11, rho = 7850.0, nu = 0.3 }
    spin_rpm = 9000.0                      # the reference speed of the gyroscopic matrix (G is per rad/s)
    disks = [{ node = 1, mass = 10.0, Ip = 0.0, Id = 0.01 }]
    # linear supports to ground, x and y (k N/m, c N s/m); k_axial and k_torsion hold the axial and spin DOFs
    supports = [{ node = 0, k = 1e12, c = 0.0, k_axial = 1e12, k_torsion = 1e6 }, { node = 2, k = 1e12, c = 0.0 }]
    dampers = [{ node = 1, c = 253.0 }]    # viscous dampers to ground, x and y
    [shaft.ports]                          # the rotor component's ports (component.LOAD_GROUPS) by node
    unbalance = 1
    default = 1                            # every port not named

The shaft is the power-turbine spool of the rotor component (``G_pt``); it has no gas generator (``G_gg = 0``).

Example::

    >>> from rotorcosim.components.rotor.shaft_model import is_shaft_model
    >>> is_shaft_model({"shaft": {}})
    True
"""
from __future__ import annotations

import math

import numpy as np

from .beam import disk, shaft_element
from .model import RPM, FullModel

#: the port groups and their DOFs per node (x y z for the bearing ports, x y otherwise)
_PORT_DOFS = {"brg0": 3, "brg5": 3, "housing0": 2, "housing5": 2, "rub0": 2, "rub5": 2, "unbalance": 2}


def is_shaft_model(data: dict) -> bool:
    """True for a model file of this format (a ``[shaft]`` table)."""
    return "shaft" in data


def _num(where, v, lo=0.0, strict=False):
    if not (isinstance(v, (int, float)) and math.isfinite(v) and (v > lo if strict else v >= lo)):
        raise ValueError(f"rotor model: {where} must be a finite number {'>' if strict else '>='} {lo:g}, got {v!r}")
    return float(v)


def build(data: dict, digest: str = "", omega_pt=None, omega_gg=None, source=None) -> FullModel:
    """The FullModel of a ``[shaft]`` model file (module docstring); ValueError naming the key otherwise."""
    where = f"rotor model file {source}"
    try:
        return _assemble(data["shaft"], data, digest, omega_pt)
    except KeyError as exc:
        raise ValueError(f"{where}: missing key {exc.args[0]!r} in [shaft] (components/rotor/shaft_model.py)") from None
    except (TypeError, IndexError) as exc:
        raise ValueError(f"{where}: a value of the wrong kind or size in [shaft] ({exc})") from None
    except ValueError as exc:
        raise ValueError(f"{where}: {str(exc).removeprefix('rotor model: ')}") from None


def _assemble(s: dict, data: dict, digest: str, omega_pt) -> FullModel:
    z = np.asarray(s["z_mm"], float) * 1e-3
    if z.size < 2 or not np.all(np.diff(z) > 0):
        raise ValueError("shaft.z_mm needs >= 2 strictly increasing stations")
    ne, nn = z.size - 1, z.size
    d_out, d_in = s["d_out_mm"], s["d_in_mm"]
    if len(d_out) != ne or len(d_in) != ne:
        raise ValueError(f"shaft: d_out_mm and d_in_mm need {ne} values (one per element)")
    mat = s["material"]
    E = _num("shaft.material.E", mat["E"], strict=True)
    rho = _num("shaft.material.rho", mat["rho"], strict=True)
    nu = _num("shaft.material.nu", mat["nu"], -1.0, strict=True)
    n = 6 * nn
    M, K, C, G = (np.zeros((n, n)) for _ in range(4))
    for e in range(ne):
        ke, me, ge = shaft_element(z[e + 1] - z[e], E, E / (2 * (1 + nu)), rho,
                                   _num(f"shaft.d_out_mm[{e}]", d_out[e], strict=True) * 1e-3,
                                   _num(f"shaft.d_in_mm[{e}]", d_in[e]) * 1e-3)
        idx = np.arange(6 * e, 6 * e + 12)
        K[np.ix_(idx, idx)] += ke
        M[np.ix_(idx, idx)] += me
        G[np.ix_(idx, idx)] += ge

    def node(where, v):
        if not (isinstance(v, int) and 0 <= v < nn):
            raise ValueError(f"{where}: node {v!r} out of range 0-{nn - 1}")
        return v

    for i, dk in enumerate(s.get("disks", [])):
        k = node(f"shaft.disks[{i}]", dk["node"])
        md, gd = disk(_num("disk mass", dk["mass"]), _num("disk Ip", dk["Ip"]), _num("disk Id", dk["Id"]))
        idx = np.arange(6 * k, 6 * k + 6)
        M[np.ix_(idx, idx)] += md
        G[np.ix_(idx, idx)] += gd
    for i, sp in enumerate(s.get("supports", [])):
        k = node(f"shaft.supports[{i}]", sp["node"])
        for d in range(2):
            K[6 * k + d, 6 * k + d] += _num(f"shaft.supports[{i}].k", sp["k"])
            C[6 * k + d, 6 * k + d] += _num(f"shaft.supports[{i}].c", sp.get("c", 0.0))
        K[6 * k + 2, 6 * k + 2] += _num(f"shaft.supports[{i}].k_axial", sp.get("k_axial", 0.0))
        K[6 * k + 5, 6 * k + 5] += _num(f"shaft.supports[{i}].k_torsion", sp.get("k_torsion", 0.0))
    for i, dp in enumerate(s.get("dampers", [])):
        k = node(f"shaft.dampers[{i}]", dp["node"])
        for d in range(2):
            C[6 * k + d, 6 * k + d] += _num(f"shaft.dampers[{i}].c", dp["c"])
    ports_in = s.get("ports", {})
    unknown = set(ports_in) - set(_PORT_DOFS) - {"default"}
    if unknown:
        raise ValueError(f"shaft.ports: unknown port {sorted(unknown)[0]!r} (known: {', '.join(_PORT_DOFS)}, default)")
    ports = {}
    for g, nd in _PORT_DOFS.items():
        if g not in ports_in and "default" not in ports_in:
            raise ValueError(f"shaft.ports: no node for port {g!r} (or give a default)")
        k = node(f"shaft.ports.{g}", ports_in.get(g, ports_in.get("default")))
        ports[g] = np.arange(6 * k, 6 * k + nd)
    if not np.all(np.isfinite(M)) or not np.all(np.isfinite(K)):
        raise ValueError("the assembled matrices are not finite")
    try:
        np.linalg.cholesky(K)
    except np.linalg.LinAlgError:
        raise ValueError("the stiffness matrix is singular: support the shaft laterally, axially (k_axial) and "
                         "in torsion (k_torsion)") from None
    spin = _num("shaft.spin_rpm", s["spin_rpm"], strict=True)
    w = spin * RPM if omega_pt is None else float(omega_pt)
    lateral = np.array([6 * k + d for k in range(nn) for d in range(2)])
    return FullModel(M=M, K=K, C=C, G_pt=G, G_gg=np.zeros_like(G), ports=ports, rotor_lateral=lateral,
                     omega_pt=w, omega_gg=0.0, data=data, digest=digest, info={"nodes": nn})
