"""The polar moment of inertia J of a spool (a rotor of the model file) about its spin axis.

J = r^T M r, with M the spool's assembled mass matrix and r the rigid rotation of every node about z: the kinetic
energy J Omega^2 / 2 of the spool turning rigidly, the inertia of its torque balance ``J dOmega/dt = T``
(components/spool). For the Timoshenko elements' consistent torsional mass (rho I_p L / 3 [[1, 1/2], [1/2, 1]],
beam.py) this sum is the hollow cylinder's exact rho pi (d_o^4 - d_i^4) L / 32 per element; each disk adds its
polar inertia I_p.

Example::

    >>> from rotorcosim.components.rotor.spool_inertia import polar_inertia
    >>> round(polar_inertia("", "pt"), 4) > 0      # the shipped engine's power turbine, kg m^2
    True
"""
from __future__ import annotations

import math

import numpy as np

from . import model as fem


def spool_polar_inertia(data: dict, spool: str) -> float:
    """J [kg m^2] of ``[spool.<spool>]`` of an engine file's data (model.py's format): its shaft elements and
    disks."""
    r = data["spool"][spool]
    z = np.asarray(r["z_mm"], float) * 1e-3
    d_out, d_in = (np.asarray(d) for d in fem.rotor_diameters(data, spool))
    rho = float(data["material"][r.get("material", "rotor")]["rho"])
    shaft = float(np.sum(rho * math.pi / 32 * (d_out ** 4 - d_in ** 4) * np.diff(z)))
    return shaft + sum(fem.disk_inertia(data, dk)[1] for dk in r.get("disks", []))


def polar_inertia(model_file: str = "", spool: str = "pt") -> float:
    """J [kg m^2] of spool ``spool`` (a ``[spool.NAME]`` of the model file, '' = the shipped engine); the shaft
    of a single-shaft file (shaft_model.py) whatever ``spool`` says."""
    data, _ = fem.load_data(model_file or None)
    if "shaft" in data:                       # a single-shaft model file (shaft_model.py): its one spool
        s = data["shaft"]
        z = np.asarray(s["z_mm"], float) * 1e-3
        d_out, d_in = (np.asarray(s[k], float) * 1e-3 for k in ("d_out_mm", "d_in_mm"))
        rho = float(s["material"]["rho"])
        return float(np.sum(rho * math.pi / 32 * (d_out ** 4 - d_in ** 4) * np.diff(z))) + sum(
            float(dk["Ip"]) for dk in s.get("disks", []))
    spools = data.get("spool", {})
    if spool not in spools:
        raise ValueError(f"rotor model file {model_file or fem.DEFAULT_FILE}: no spool {spool!r} "
                         f"(its spools: {', '.join(spools) or 'none'})")
    return spool_polar_inertia(data, spool)
