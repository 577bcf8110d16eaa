"""The full (unreduced) finite-element model of the engine: two spinning rotors, supports, casing.

Paper section 2.1 (Fig. 2, Table 2) and eq. (16): M q'' + (C + Omega_pt G_pt + Omega_gg G_gg) q + K q = F.
Built from a TOML data file (data/engine.toml by default). Timoshenko shaft elements and disks (beam), 8-node
solids for the casing shell (hexa), spring elements for the struts, mounts and bearings.

Bearings #0 and #5 are not in K: their forces, and the damper and rub-ring reactions on the housings, enter as
external forces at the port DOFs (:attr:`FullModel.ports`). The engine with them linearised (ball contacts, the
outer race + journal body of eq. 5, O-ring and film) is :meth:`FullModel.coupled`, given the supports' values,
which the system's linearisation (rotorcosim.cases.blade_loss.linear_engine) takes from the bearing and damper components.
"""
from __future__ import annotations

import hashlib
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import toml_text
from .beam import disk, shaft_element
from .hexa import hex8

DEFAULT_FILE = Path(__file__).with_name("data") / "engine.toml"
RPM = 2.0 * math.pi / 60.0


def _read(path: str | Path | None) -> tuple[Path, bytes]:
    p = Path(path) if path else DEFAULT_FILE
    if p.is_dir():
        raise IsADirectoryError(f"rotor model file {p} is a folder, not a TOML file")
    if not p.is_file():
        raise FileNotFoundError(f"rotor model file not found: {p}")
    return p, p.read_bytes()


def file_digest(path: str | Path | None = None) -> str:
    """The SHA-256 of the model file's bytes, without parsing it (the per-process caches' key)."""
    return hashlib.sha256(_read(path)[1]).hexdigest()


def load_data(path: str | Path | None = None) -> tuple[dict, str]:
    """The model data and the SHA-256 of the file's bytes (the cache key)."""
    p, raw = _read(path)
    try:
        data = toml_text.loads(raw.decode("utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"rotor model file {p}: {exc}") from None
    except UnicodeDecodeError as exc:
        raise ValueError(f"rotor model file {p}: not a text file ({exc})") from None
    return data, hashlib.sha256(raw).hexdigest()


@dataclass
class FullModel:
    """Assembled matrices (dense, SI) and the DOF maps.

    ``G_pt`` / ``G_gg`` are per rad/s of the power-turbine / gas-generator spin; ``ports`` maps a port name
    (brg0, brg5: x y z of the PT node at the bearing; housing0/5: x y of the hub; rub0/5: x y of the PT node at
    the rub ring; unbalance: x y of the blade-loss node) to free-DOF indices.
    """

    M: np.ndarray
    K: np.ndarray
    C: np.ndarray
    G_pt: np.ndarray
    G_gg: np.ndarray
    ports: dict[str, np.ndarray]
    rotor_lateral: np.ndarray          # free-DOF indices of ux, uy of all rotor nodes (whirl classification)
    omega_pt: float
    omega_gg: float
    data: dict
    digest: str
    info: dict = field(default_factory=dict)

    @property
    def n(self) -> int:
        return self.M.shape[0]

    def coupled(self, supports: dict) -> dict:
        """The engine with bearings #0/#5 as the co-simulated system linearised (the one engine model of the
        critical speeds and the calibration): per support ``{pt_node, hub, k_contact, m_journal, k_spring,
        c_film}``, the ball contacts (radial stiffness at the preloaded rest) join the power-turbine node to a
        journal body of its own (outer race + SFD journal, eq. 5: 2 DOF, x and y) which the O-ring centering
        spring and the linearised film join to the casing hub. Returns the augmented matrices ``M, K, C, G_pt,
        G_gg`` (the model's DOFs first, then x, y of each journal in the order of ``supports``), ``journal``
        (support key -> its two DOF indices) and ``rotor_lateral``."""
        n0 = self.n
        nj = 2 * len(supports)
        n = n0 + nj

        def grow(A):
            B = np.zeros((n, n))
            B[:n0, :n0] = A
            return B

        M, K, C, Gp, Gg = (grow(A) for A in (self.M, self.K, self.C, self.G_pt, self.G_gg))
        journal = {}
        for s_i, (key, s) in enumerate(supports.items()):
            jx = n0 + 2 * s_i
            journal[key] = np.array([jx, jx + 1])
            for d in range(2):
                i = self.info["dof"]("pt", s["pt_node"], d)
                h = self.info["dof"]("hub", s["hub"], d)
                j = jx + d
                M[j, j] += _positive(f"support {key} m_journal", s["m_journal"])
                _couple(K, i, j, _positive(f"support {key} k_contact", s["k_contact"]))
                _couple(K, j, h, _nonneg(f"support {key} k_spring", s["k_spring"]))
                _couple(C, j, h, _nonneg(f"support {key} c_film", s["c_film"]))
        return {"M": M, "K": K, "C": C, "G_pt": Gp, "G_gg": Gg, "journal": journal,
                "rotor_lateral": self.rotor_lateral}

    def linear_support(self, supports: dict) -> tuple[np.ndarray, np.ndarray]:
        """Bearings #0/#5 as massless springs (contact in series with the centering spring, film damping in
        parallel) between the PT node and its hub, x and y: the same-size matrices of the MTA verification
        (verification.py), which needs the model's own DOFs. The engine's critical speeds and calibration use
        :meth:`coupled` (with the journal mass), not this."""
        K = np.zeros_like(self.K)
        C = np.zeros_like(self.K)
        for key, s in supports.items():
            k = 1.0 / (1.0 / s["k_contact"] + 1.0 / s["k_spring"])
            for d in range(2):
                i = self.info["dof"]("pt", s["pt_node"], d)
                j = self.info["dof"]("hub", s["hub"], d)
                _couple(K, i, j, k)
                _couple(C, i, j, s["c_film"])
        return K, C


def _couple(A, i, j, k):
    """Add a spring k between DOFs i and j (j = None: to ground)."""
    A[i, i] += k
    if j is not None:
        A[j, j] += k
        A[i, j] -= k
        A[j, i] -= k


def _positive(name, value):
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise ValueError(f"rotor model: {name} must be a finite number > 0, got {value!r}")
    return float(value)


def _poisson(name, value):
    """Poisson's ratio of an isotropic solid: -1 < nu < 1/2, where its strain energy is positive definite
    (Timoshenko & Goodier, Theory of Elasticity; 1e300 overflowed the element matrices)."""
    if not (isinstance(value, (int, float)) and -1.0 < value < 0.5):
        raise ValueError(f"rotor model: {name} must be a Poisson's ratio within (-1, 0.5), got {value!r}")
    return float(value)


def _nonneg(name, value):
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
        raise ValueError(f"rotor model: {name} must be a finite number >= 0, got {value!r}")
    return float(value)


def rotor_diameters(data: dict, rotor: str) -> tuple[list[float], list[float]]:
    """Element outer/inner diameters (m)."""
    r = data[rotor]
    d_out = [_positive(f"{rotor}.d_out_mm[{k}]", _knob(data, v)) * 1e-3 for k, v in enumerate(r["d_out_mm"])]
    d_in = [_nonneg(f"{rotor}.d_in_mm[{k}]", _knob(data, v)) * 1e-3 for k, v in enumerate(r["d_in_mm"])]
    return d_out, d_in


def _knob(data: dict, value):
    """A number, or the name of a [calibration] knob whose value is used."""
    if isinstance(value, str):
        cal = data.get("calibration", {})
        if value not in cal:
            raise ValueError(f"rotor model: unknown calibration knob {value!r}")
        return cal[value]
    return value


def disk_inertia(data: dict, dk: dict) -> tuple[float, float, float]:
    """(mass, Ip, Id) of a disk entry; mass may name a calibration knob, then Ip = m r_g^2 and Id = Ip / 2."""
    mass = dk["mass"]
    if isinstance(mass, str):
        cal = data.get("calibration", {})
        if mass not in cal:
            raise ValueError(f"rotor model: disk {dk.get('name', '')!r} names unknown calibration knob {mass!r}")
        mass = _positive(mass, cal[mass])
        Ip = mass * (_positive("r_gyration_mm", dk["r_gyration_mm"]) * 1e-3) ** 2
        return mass, Ip, Ip / 2.0
    return float(mass), float(dk["Ip"]), float(dk["Id"])


def build(data: dict, digest: str = "", omega_pt: float | None = None, omega_gg: float | None = None,
          source: str | Path | None = None) -> FullModel:
    """Assemble the full model from the data (see data/engine.toml for the meaning of each entry); a missing
    table or key, or a value of the wrong kind, is a ValueError naming the file (``source``) and the key."""
    where = f"rotor model file {source or DEFAULT_FILE}"
    try:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # non-finite matrices refused below
            return _assemble(data, digest, omega_pt, omega_gg)
    except KeyError as exc:
        raise ValueError(f"{where}: missing table or key {exc.args[0]!r} (see data/engine.toml)") from None
    except (TypeError, IndexError, AttributeError) as exc:
        raise ValueError(f"{where}: a value of the wrong kind or size ({type(exc).__name__}: {exc}; see "
                         "data/engine.toml)") from None
    except ValueError as exc:
        msg = str(exc)
        if msg.startswith("rotor model file"):
            raise ValueError(msg) from None
        raise ValueError(f"{where}: {msg.removeprefix('rotor model: ')}") from None


def _assemble(data: dict, digest: str, omega_pt: float | None, omega_gg: float | None) -> FullModel:
    pt, gg, cas = data["power_turbine"], data["gas_generator"], data["casing"]
    zpt = np.asarray(pt["z_mm"], float) * 1e-3
    zgg = np.asarray(gg["z_mm"], float) * 1e-3
    if len(zpt) != 22 or len(zgg) != 16:
        raise ValueError(f"rotor model: the power turbine has 22 nodes and the gas generator 16 (paper), got "
                         f"{len(zpt)} and {len(zgg)}")
    for name, z in (("power_turbine", zpt), ("gas_generator", zgg)):
        if not np.all(np.diff(z) > 0):
            raise ValueError(f"rotor model: {name}.z_mm must increase strictly")
    mat_r, mat_c = data["material"]["rotor"], data["material"]["casing"]
    E, rho = (_positive(f"material.rotor.{k}", mat_r[k]) for k in ("E", "rho"))
    nu = _poisson("material.rotor.nu", mat_r["nu"])
    Gmod = E / (2 * (1 + nu))
    Ec, rhoc = (_positive(f"material.casing.{k}", mat_c[k]) for k in ("E", "rho"))
    nuc = _poisson("material.casing.nu", mat_c["nu"])

    # global numbering before constraints: PT nodes, GG nodes (6 DOF), shell nodes, hubs (3 DOF)
    nc = int(cas["n_circ"])
    rings = np.asarray(cas["ring_z_mm"], float) * 1e-3
    if nc < 4 or len(rings) < 2 or not np.all(np.diff(rings) > 0):
        raise ValueError("rotor model: casing needs n_circ >= 4 and >= 2 strictly increasing ring_z_mm")
    hubs = list(cas["hubs"].keys())
    base_pt, base_gg = 0, 6 * 22
    base_sh = base_gg + 6 * 16
    n_shell_nodes = 2 * nc * len(rings)
    base_hub = base_sh + 3 * n_shell_nodes
    ntot = base_hub + 3 * len(hubs)

    def shell_node(ring, circ, layer):  # layer 0 inner, 1 outer
        return (ring * nc + circ % nc) * 2 + layer

    def gdof(body, node, d):
        if body == "pt":
            if not 0 <= int(node) < 22:
                raise ValueError(f"rotor model: power-turbine node {node} out of range 0-21")
            return base_pt + 6 * int(node) + d
        if body == "gg":
            if not 0 <= int(node) < 16:
                raise ValueError(f"rotor model: gas-generator node {node} out of range 0-15")
            return base_gg + 6 * int(node) + d
        if body == "hub":
            if node not in cas["hubs"]:
                raise ValueError(f"rotor model: unknown casing hub {node!r} (known: {', '.join(hubs)})")
            if d > 2:
                raise ValueError("rotor model: hubs have 3 DOF")
            return base_hub + 3 * hubs.index(node) + d
        raise ValueError(f"rotor model: unknown body {body!r}")

    M = np.zeros((ntot, ntot))
    K = np.zeros((ntot, ntot))
    Gp = np.zeros((ntot, ntot))
    Gg = np.zeros((ntot, ntot))

    # rotors
    for key, z, base, Gm in (("power_turbine", zpt, base_pt, Gp), ("gas_generator", zgg, base_gg, Gg)):
        d_out, d_in = rotor_diameters(data, key)
        if len(d_out) != len(z) - 1 or len(d_in) != len(z) - 1:
            raise ValueError(f"rotor model: {key} needs {len(z) - 1} element diameters")
        for e in range(len(z) - 1):
            ke, me, ge = shaft_element(z[e + 1] - z[e], E, Gmod, rho, d_out[e], d_in[e])
            idx = np.arange(base + 6 * e, base + 6 * e + 12)
            K[np.ix_(idx, idx)] += ke
            M[np.ix_(idx, idx)] += me
            Gm[np.ix_(idx, idx)] += ge
        for dk in data[key].get("disks", []):
            md, gd = disk(*disk_inertia(data, dk))
            n = int(dk["node"])
            if not 0 <= n < len(z):
                raise ValueError(f"rotor model: {key} disk node {n} out of range")
            idx = np.arange(base + 6 * n, base + 6 * n + 6)
            M[np.ix_(idx, idx)] += md
            Gm[np.ix_(idx, idx)] += gd

    # casing shell: 8-node solids, one through the thickness
    R = _positive("casing.radius_mm", cas["radius_mm"]) * 1e-3
    t = _positive("casing.thickness_mm", cas["thickness_mm"]) * 1e-3
    ang = 2 * math.pi * np.arange(nc) / nc
    xyz_shell = np.zeros((n_shell_nodes, 3))
    for r_i, zr in enumerate(rings):
        for c in range(nc):
            for layer, rad in ((0, R - t / 2), (1, R + t / 2)):
                xyz_shell[shell_node(r_i, c, layer)] = (rad * math.cos(ang[c]), rad * math.sin(ang[c]), zr)
    for r_i in range(len(rings) - 1):
        for c in range(nc):
            nodes = [shell_node(r_i, c, 0), shell_node(r_i, c + 1, 0), shell_node(r_i, c + 1, 1),
                     shell_node(r_i, c, 1)]
            nodes += [shell_node(r_i + 1, c, 0), shell_node(r_i + 1, c + 1, 0), shell_node(r_i + 1, c + 1, 1),
                      shell_node(r_i + 1, c, 1)]
            ke, me = hex8(xyz_shell[nodes], Ec, nuc, rhoc)
            idx = (base_sh + 3 * np.asarray(nodes)[:, None] + np.arange(3)).reshape(-1)
            K[np.ix_(idx, idx)] += ke
            M[np.ix_(idx, idx)] += me

    K_struct = K.copy()   # Rayleigh damping acts on the elastic elements only (the supports have their own)
    C = np.zeros((ntot, ntot))

    # hubs and struts (spring elements in the local radial / tangential / axial frame)
    st = cas["struts"]
    for h, hv in cas["hubs"].items():
        # a hub may have its own bearing frame (``struts = {k_r, k_t, k_a}``), else the casing's common one
        sth = hv.get("struts", st)
        kr, kt, ka = (_positive(f"casing.hubs.{h}.struts.{k}" if "struts" in hv else f"casing.struts.{k}", sth[k])
                      for k in ("k_r", "k_t", "k_a"))
        zh = float(hv["z_mm"]) * 1e-3
        hit = np.nonzero(np.abs(rings - zh) < 1e-9)[0]
        if hit.size != 1:
            raise ValueError(f"rotor model: hub {h!r} at z = {hv['z_mm']} mm is not on a casing ring")
        mh = _positive(f"casing.hubs.{h}.mass", hv["mass"])
        hd = [gdof("hub", h, d) for d in range(3)]
        for d in hd:
            M[d, d] += mh
        for c in range(nc):
            er = np.array([math.cos(ang[c]), math.sin(ang[c]), 0.0])
            et = np.array([-math.sin(ang[c]), math.cos(ang[c]), 0.0])
            ez = np.array([0.0, 0.0, 1.0])
            k3 = kr * np.outer(er, er) + kt * np.outer(et, et) + ka * np.outer(ez, ez)
            sd = [base_sh + 3 * shell_node(int(hit[0]), c, 0) + d for d in range(3)]
            idx = np.array(hd + sd)
            K[np.ix_(idx, idx)] += np.block([[k3, -k3], [-k3, k3]])

    # mounts to ground
    for m_i, mt in enumerate(cas["mounts"]):
        ring, node, d = int(mt["ring"]), int(mt["node"]), int(mt["dir"])
        if not (0 <= ring < len(rings) and 0 <= node < nc and 0 <= d < 3):
            raise ValueError(f"rotor model: casing mount {m_i} ({mt}) out of range")
        i = base_sh + 3 * shell_node(ring, node, 1) + d
        _couple(K, i, None, _positive(f"casing.mounts[{m_i}].k", _knob(data, mt["k"])))
        _couple(C, i, None, _nonneg(f"casing.mounts[{m_i}].c", mt["c"]))

    # linear supports of Table 2
    for s in data["support"]:
        a, b = s["a"], s["b"]
        k = _positive(f"support {s['name']!r} k", s["k"])
        c = _nonneg(f"support {s['name']!r} c", s["c"])
        for d in range(2):
            i, j = gdof(a[0], a[1], d), gdof(b[0], b[1], d)
            _couple(K, i, j, k)
            _couple(C, i, j, c)
        if "k_axial" in s:
            _couple(K, gdof(a[0], a[1], 2), gdof(b[0], b[1], 2), _positive("k_axial", s["k_axial"]))

    # Rayleigh damping of the structure: zeta at f1 and f2
    dmp = data["damping"]
    zeta = _nonneg("damping.zeta", dmp["zeta"])
    w1, w2 = 2 * math.pi * _positive("f1_Hz", dmp["f1_Hz"]), 2 * math.pi * _positive("f2_Hz", dmp["f2_Hz"])
    alpha = 2 * zeta * w1 * w2 / (w1 + w2)
    beta = 2 * zeta / (w1 + w2)
    C += alpha * M + beta * K_struct

    # constant speed: the spin angle of each rotor is prescribed at its drive node
    fixed = [gdof("pt", pt["drive_node"], 5), gdof("gg", gg["drive_node"], 5)]
    free = np.setdiff1d(np.arange(ntot), fixed)
    newidx = -np.ones(ntot, dtype=int)
    newidx[free] = np.arange(free.size)

    def dof(body, node, d):
        i = newidx[gdof(body, node, d)]
        if i < 0:
            raise ValueError(f"rotor model: DOF {body}:{node}:{d} is constrained")
        return int(i)

    sub = np.ix_(free, free)
    ports = {
        "brg0": [dof("pt", pt["bearing0_node"], d) for d in range(3)],
        "brg5": [dof("pt", pt["bearing5_node"], d) for d in range(3)],
        "housing0": [dof("hub", "h0", d) for d in range(2)],
        "housing5": [dof("hub", "h5", d) for d in range(2)],
        "rub0": [dof("pt", pt["rub0_node"], d) for d in range(2)],
        "rub5": [dof("pt", pt["rub5_node"], d) for d in range(2)],
        "unbalance": [dof("pt", pt["unbalance_node"], d) for d in range(2)],
    }
    lateral = [dof(b, n, d) for b, nn in (("pt", 22), ("gg", 16)) for n in range(nn) for d in range(2)]
    for name, r in (("power_turbine", pt), ("gas_generator", gg)):
        # the speed ratio gas generator / power turbine divides by the first (0 was a ZeroDivisionError); a
        # negative speed is a spool turning the other way, kept
        v = r["spin_rpm"]
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v != 0):
            raise ValueError(f"rotor model: {name}.spin_rpm must be a finite, non-zero speed in rev/min, got {v!r}")
    w_pt = pt["spin_rpm"] * RPM if omega_pt is None else float(omega_pt)
    w_gg = gg["spin_rpm"] * RPM if omega_gg is None else float(omega_gg)
    for name, A in (("mass", M), ("stiffness", K), ("damping", C)):
        if not np.all(np.isfinite(A)):
            # a value so large that the element matrices overflow (casing.radius_mm = 1e300)
            raise ValueError(f"rotor model: the assembled {name} matrix is not finite: a length, modulus or mass "
                             "of the file is too large (lengths are in mm)")
    info = {"dof": dof, "rayleigh": (alpha, beta), "n_shell_dof": 3 * n_shell_nodes, "n_hub_dof": 3 * len(hubs),
            "pt_lateral": np.array([dof("pt", n, d) for n in range(22) for d in range(2)])}
    return FullModel(M=M[sub], K=K[sub], C=C[sub], G_pt=Gp[sub], G_gg=Gg[sub],
                     ports={k: np.asarray(v) for k, v in ports.items()}, rotor_lateral=np.asarray(lateral),
                     omega_pt=w_pt, omega_gg=w_gg, data=data, digest=digest, info=info)


def load(path: str | Path | None = None, **kw) -> FullModel:
    data, digest = load_data(path)
    return build(data, digest, source=path, **kw)
