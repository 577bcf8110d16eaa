"""The example airframe (data/pylon_wing.toml): how it is derived, so that the shipped numbers can be remade.

A regional twin turboprop of about 20 t (the class of the ATR 72; the values are round engineering estimates of
that class, not any aircraft's data) as a free-free finite-element frame of 3-D Euler-Bernoulli beams
(Przemieniecki, *Theory of Matrix Structural Analysis*, 1968, ch. 5 and 11: the 12-DOF space-frame element with
its consistent mass), in the engine's axes (x outboard along the right wing, y up, z forward along the engine's
axis), origin on the fuselage axis at the wing's elastic axis:

* the fuselage, z from -15 m to +12 m in 1.5 m elements: EI 1.5e9 N m^2 (both planes), GJ 1.0e9 N m^2, EA 5e10 N,
  450 kg/m with its payload, polar inertia 650 kg m^2/m;
* two wings, x from 0 to +-13.5 m (a node at the engine's station, 4.1 m): flap EI 1.5e8 N m^2, chord EI
  1.5e9 N m^2, GJ 5e7 N m^2, EA 1e10 N, 180 kg/m with fuel, 45 kg m^2/m;
* the pylon on the right wing, a triangulated frame of three tubes (EA 1e9 N, EI 5e6 N m^2, GJ 4e6 N m^2,
  25 kg/m) from the wing node at (4.1, 0, 0) m to the two interface points ``pylon_aft`` (4.1, -0.6, 0.4) m and
  ``pylon_fwd`` (4.1, -0.6, 1.6) m and between them: where the engine's aft (casing ring 0) and forward (ring 6)
  mounts end, on top of its casing (radius 0.3 m, axis at y = -0.9 m).

The engine is not in this model: its mass and stiffness come in through the mounts (components/rotor/mounts.py).
The eigenproblem K phi = w^2 M phi (scipy.linalg.eigh) gives six rigid-body modes (below 0.5 Hz, left out: the
engine's forces at 50-270 Hz would move the aircraft as a whole by microns) and the elastic modes, kept up to
:data:`F_MAX_HZ`, mass-normalised, with a modal damping ratio of 2 % (a built-up airframe's order). The response
points read the fuselage's node through a rigid offset (u + theta x r): ``flight_deck`` at (0, 0.5, 10.5) m,
``seat_track`` on the cabin floor at (0.5, -0.8, 3.0) m. Element size 1.5 m: halving it (fuselage and wings)
moves the modes below 80 Hz by less than 1 %, those up to 150 Hz by up to 4.7 %: above ~80 Hz the model is the
frame's, a stand-in for a real FE model's export.

``python -m rotorcosim.components.airframe.example FILE`` writes the file (tests/components/test_airframe.py
holds the shipped one equal to it).
"""
from __future__ import annotations

import sys

import numpy as np
import scipy.linalg as sla

from .modal import to_toml

#: the elastic modes kept [Hz]
F_MAX_HZ = 150.0
#: modal damping ratio of every mode
ZETA = 0.02
#: rigid-body modes are below this [Hz]
RIGID_HZ = 0.5
FUSELAGE = dict(EA=5e10, EIa=1.5e9, EIb=1.5e9, GJ=1.0e9, m=450.0, jp=650.0)
WING = dict(EA=1e10, EIa=1.5e8, EIb=1.5e9, GJ=5e7, m=180.0, jp=45.0)
PYLON = dict(EA=1e9, EIa=5e6, EIb=5e6, GJ=4e6, m=25.0, jp=0.5)
WING_X = [0.0, 1.5, 3.0, 4.1, 5.5, 7.0, 8.5, 10.0, 11.75, 13.5]
ENGINE_X = 4.1
INTERFACE = {"pylon_aft": (ENGINE_X, -0.6, 0.4), "pylon_fwd": (ENGINE_X, -0.6, 1.6)}
RESPONSE = {"flight_deck": ((0.0, 0.5, 10.5), 10.5), "seat_track": ((0.5, -0.8, 3.0), 3.0)}


def frame_element(L: float, EA, EIa, EIb, GJ, m, jp) -> tuple[np.ndarray, np.ndarray]:
    """Local stiffness and consistent mass of a 3-D beam (DOFs u v w tx ty tz at each end; x along the element;
    ``EIa`` bends in the x-y plane (v, tz), ``EIb`` in the x-z plane (w, ty); ``m`` kg/m, ``jp`` kg m^2/m)."""
    K = np.zeros((12, 12))
    M = np.zeros((12, 12))
    bar = np.array([[1.0, -1.0], [-1.0, 1.0]])
    cm = np.array([[2.0, 1.0], [1.0, 2.0]]) / 6.0
    for idx, kv, mv in (([0, 6], EA / L, m * L), ([3, 9], GJ / L, jp * L)):
        K[np.ix_(idx, idx)] += kv * bar
        M[np.ix_(idx, idx)] += mv * cm
    kb = np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                   [-12, -6 * L, 12, -6 * L], [6 * L, 2 * L * L, -6 * L, 4 * L * L]]) / L ** 3
    mb = np.array([[156, 22 * L, 54, -13 * L], [22 * L, 4 * L * L, 13 * L, -3 * L * L],
                   [54, 13 * L, 156, -22 * L], [-13 * L, -3 * L * L, -22 * L, 4 * L * L]]) * (m * L / 420.0)
    flip = np.diag([1.0, -1.0, 1.0, -1.0])       # x-z plane: w' = -ty
    for idx, EI, S in (([1, 5, 7, 11], EIa, np.eye(4)), ([2, 4, 8, 10], EIb, flip)):
        K[np.ix_(idx, idx)] += EI * (S @ kb @ S)
        M[np.ix_(idx, idx)] += S @ mb @ S
    return K, M


def _rotation(p1, p2, up) -> np.ndarray:
    e1 = (p2 - p1) / np.linalg.norm(p2 - p1)
    e2 = up - (up @ e1) * e1
    e2 /= np.linalg.norm(e2)
    return np.vstack([e1, e2, np.cross(e1, e2)])


def model() -> dict:
    """Nodes, elements, the assembled K and M (free-free) of the frame (module docstring)."""
    nodes: list[tuple] = []

    def node(p) -> int:
        p = tuple(round(float(v), 9) for v in p)
        if p not in nodes:
            nodes.append(p)
        return nodes.index(p)

    elems = []
    fz = np.arange(-15.0, 12.0 + 1e-9, 1.5)
    for a, b in zip(fz, fz[1:]):
        elems.append((node((0, 0, a)), node((0, 0, b)), FUSELAGE, (0.0, 1.0, 0.0)))
    for side in (1.0, -1.0):
        for a, b in zip(WING_X, WING_X[1:]):
            elems.append((node((side * a, 0, 0)), node((side * b, 0, 0)), WING, (0.0, 1.0, 0.0)))
    w = node((ENGINE_X, 0, 0))
    aft, fwd = node(INTERFACE["pylon_aft"]), node(INTERFACE["pylon_fwd"])
    for a, b in ((w, aft), (w, fwd), (aft, fwd)):
        elems.append((a, b, PYLON, (1.0, 0.0, 0.0)))
    xyz = np.asarray(nodes)
    n = 6 * len(nodes)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    for a, b, props, up in elems:
        R = _rotation(xyz[a], xyz[b], np.asarray(up))
        T = np.kron(np.eye(4), R)
        ke, me = frame_element(float(np.linalg.norm(xyz[b] - xyz[a])), **props)
        idx = np.r_[6 * a:6 * a + 6, 6 * b:6 * b + 6]
        K[np.ix_(idx, idx)] += T.T @ ke @ T
        M[np.ix_(idx, idx)] += T.T @ me @ T
    return {"xyz": xyz, "K": K, "M": M, "node": node}


def _offset(r) -> np.ndarray:
    """The rigid offset of a point r from its node: u_point = A u_node (u + theta x r), 3 x 6."""
    rx, ry, rz = r
    return np.hstack([np.eye(3), -np.array([[0.0, -rz, ry], [rz, 0.0, -rx], [-ry, rx, 0.0]])])


def derive() -> dict:
    """The modal data of the file: frequencies [Hz], shapes per point (mass-normalised; modes x 6 or 3)."""
    fe = model()
    w2, phi = sla.eigh(fe["K"], fe["M"])
    f = np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * np.pi)
    rigid = int(np.sum(f < RIGID_HZ))
    if rigid != 6:
        raise RuntimeError(f"the free-free frame has {rigid} modes below {RIGID_HZ} Hz, not 6")
    keep = np.flatnonzero((f >= RIGID_HZ) & (f <= F_MAX_HZ))
    f, phi = f[keep], phi[:, keep]
    # a deterministic sign: each mode's largest entry positive
    phi = phi * np.sign(phi[np.argmax(np.abs(phi), axis=0), np.arange(phi.shape[1])])
    node = fe["node"]
    interface = {k: phi[6 * node(p):6 * node(p) + 6].T for k, p in INTERFACE.items()}
    response = {}
    for k, (p, z) in RESPONSE.items():
        i = node((0.0, 0.0, z))
        response[k] = (_offset(np.asarray(p) - fe["xyz"][i]) @ phi[6 * i:6 * i + 6]).T
    positions = {k: np.asarray(p) * 1e3 for k, p in INTERFACE.items()}
    positions |= {k: np.asarray(p) * 1e3 for k, (p, _) in RESPONSE.items()}
    return {"frequency_Hz": f, "interface": interface, "response": response, "positions_mm": positions}


def text() -> str:
    """The file's text (data/pylon_wing.toml)."""
    d = derive()
    header = __doc__.split("\n\n``python -m")[0].replace("data/pylon_wing.toml", "this file")
    header += ("\n\nWritten by rotorcosim.components.airframe.example (python -m "
               "rotorcosim.components.airframe.example FILE).\nUnits: Hz, kg; shapes mass-normalised "
               "(modal_mass_kg 1), m/sqrt(kg) and rad/sqrt(kg), in the engine's axes.")
    n = len(d["frequency_Hz"])
    return to_toml("example pylon, wing and fuselage of a regional turboprop", "rotorcosim.components.airframe."
                   "example: a free-free beam frame", d["frequency_Hz"], np.ones(n), ZETA, d["interface"],
                   d["response"], d["positions_mm"], header)


if __name__ == "__main__":      # pragma: no cover
    out = sys.argv[1] if len(sys.argv) > 1 else None
    if out is None:
        sys.stdout.write(text())
    else:
        with open(out, "w", encoding="utf-8") as fh:
            fh.write(text())
