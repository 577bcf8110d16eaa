"""The polar moment of inertia J of a spool (a rotor of the model file) about its spin axis.

J = r^T M r, with M the spool's assembled mass matrix (its Timoshenko shaft elements' consistent mass and its
disks, beam.py, as model.py assembles them) and r the rigid rotation of every node about z (1 at each node's rz
DOF): the kinetic energy J Omega^2 / 2 of the spool turning rigidly, the inertia of its torque balance
``J dOmega/dt = T`` (components/spool). The model's drive node is constrained in rz (the constant-speed model),
so J is summed over the element matrices before that constraint.

Example::

    >>> from rotorcosim.components.rotor.spool_inertia import polar_inertia
    >>> round(polar_inertia("", "power_turbine"), 4) > 0      # the shipped engine's power turbine, kg m^2
    True
"""
from __future__ import annotations

import numpy as np

from . import model as fem
from .beam import disk, shaft_element


def polar_inertia(model_file: str = "", spool: str = "power_turbine") -> float:
    """J [kg m^2] of rotor ``spool`` ("power_turbine" or "gas_generator") of the model file ('' = shipped); the
    shaft of a single-shaft file (shaft_model.py) whatever ``spool`` says."""
    data, _ = fem.load_data(model_file or None)
    if "shaft" in data:                       # a single-shaft model file (shaft_model.py): its one spool
        data = {"shaft": data["shaft"], "material": {"rotor": data["shaft"]["material"]}}
        spool = "shaft"
    if spool not in data or "z_mm" not in data.get(spool, {}):
        raise ValueError(f"rotor model file {model_file or fem.DEFAULT_FILE}: no rotor {spool!r}")
    r = data[spool]
    z = np.asarray(r["z_mm"], float) * 1e-3
    mat = data["material"]["rotor"]
    E, rho, nu = float(mat["E"]), float(mat["rho"]), float(mat["nu"])
    if spool == "shaft":
        d_out, d_in = [float(v) * 1e-3 for v in r["d_out_mm"]], [float(v) * 1e-3 for v in r["d_in_mm"]]
    else:
        d_out, d_in = fem.rotor_diameters(data, spool)
    rz = np.zeros(12)
    rz[[5, 11]] = 1.0
    J = 0.0
    for e in range(len(z) - 1):
        _, me, _ = shaft_element(z[e + 1] - z[e], E, E / (2 * (1 + nu)), rho, d_out[e], d_in[e])
        J += float(rz @ me @ rz)
    for dk in r.get("disks", []):
        md, _ = disk(*fem.disk_inertia(data, dk)) if spool != "shaft" else disk(dk["mass"], dk["Ip"], dk["Id"])
        J += float(md[5, 5])
    return J
