"""The full (unreduced) finite-element model of the engine: two spinning rotors, supports, casing.

Paper section 2.1 (Fig. 2, Table 2) and eq. (16): M q'' + (C + Omega_pt G_pt + Omega_gg G_gg) q + K q = F.
Built from an engine file of the engine format (docs/reference/engine-format.md; data/engine.toml, the paper's
engine, by default): one or more spools (up to MAX_SPOOLS), supports, pedestals, an optional casing, and where the co-simulated parts
attach ([attach] -> :attr:`FullModel.ports`). Timoshenko shaft elements and disks (beam), 8-node
solids for the casing shell (hexa), spring elements for the struts, mounts and bearings.

The co-simulated bearings ([attach] bearing<ID>; #0 and #5 of the paper's engine) are not in K: their forces, and the damper and rub-ring reactions on the housings, enter as
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
from ..bounded_read import read_bytes
from . import attach as attach_layout
from . import mounts as mount_tables
from .engine_shape import refuse, shape_problems
from .beam import disk, shaft_element
from .hexa import hex8

DEFAULT_FILE = Path(__file__).with_name("data") / "engine.toml"
#: the engine format this module reads ([engine] format)
FORMAT = 1
RPM = 2.0 * math.pi / 60.0
#: spools an engine file may have. The first turns at the rotor component's omega_pt; the second at omega_gg; a
#: third and later at their files' speeds in a constant ratio to the second (G_gg carries them: _assemble)
MAX_SPOOLS = 8


def _read(path: str | Path | None) -> tuple[Path, bytes]:
    p = Path(path) if path else DEFAULT_FILE
    if p.is_dir():
        raise IsADirectoryError(f"rotor model file {p} is a folder, not a TOML file")
    if not p.is_file():
        raise FileNotFoundError(f"rotor model file not found: {p}")
    return p, read_bytes(p, "rotor model file")


#: how many engine files an ``[engine] extends`` chain may hold
MAX_EXTENDS = 8


def file_digest(path: str | Path | None = None) -> str:
    """The SHA-256 of the model file's bytes (and of the files it extends), without parsing a file that extends
    none (the per-process caches' key)."""
    raw = _read(path)[1]
    if b"extends" in raw:
        return load_data(path)[1]
    return hashlib.sha256(raw).hexdigest()


def _merged(base: dict, over: dict) -> dict:
    """``over`` laid on ``base``: tables merged key by key, any other value (a list, a number) replaced."""
    out = dict(base)
    for k, v in over.items():
        out[k] = _merged(base[k], v) if isinstance(v, dict) and isinstance(base.get(k), dict) else v
    return out


def load_data(path: str | Path | None = None, _chain: tuple = ()) -> tuple[dict, str]:
    """The model data and the SHA-256 of the file's bytes (the cache key). A file whose ``[engine] extends``
    names another engine file (relative to it) is that file's data with its own tables laid over it (tables
    merged key by key, other values replaced): an engine that differs from another by a part (a fuse at a
    bearing) without a copy of its geometry; the digest then covers both."""
    p, raw = _read(path)
    try:
        data = toml_text.loads(raw.decode("utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"rotor model file {p}: {exc}") from None
    except UnicodeDecodeError as exc:
        raise ValueError(f"rotor model file {p}: not a text file ({exc})") from None
    digest = hashlib.sha256(raw).hexdigest()
    head = data.get("engine")
    base = head.get("extends") if isinstance(head, dict) else None
    if base is not None:
        if not isinstance(base, str) or not base:
            raise ValueError(f"rotor model file {p}: [engine] extends must name an engine file, got {base!r}")
        chain = (*_chain, p.resolve())
        if (p.parent / base).resolve() in chain:   # not "a chain longer than 8 files"
            raise ValueError(f"rotor model file {p}: [engine] extends loops back on itself "
                             f"({' -> '.join(map(str, (*chain, (p.parent / base).resolve())))})")
        if len(_chain) >= MAX_EXTENDS:
            raise ValueError(f"rotor model file {p}: [engine] extends chain longer than {MAX_EXTENDS} files")
        bdata, bdigest = load_data(p.parent / base, chain)
        own = dict(data, engine={k: v for k, v in head.items() if k != "extends"})
        data = _merged(bdata, own)
        digest = hashlib.sha256((digest + bdigest).encode()).hexdigest()
    return data, digest


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
        spring and the linearised film join to the casing hub (a fused bearing's, ``fuse = {housing, k, c}``: to
        its own housing, which the fuse's stiffness ``k`` and damping ``c`` of the stage considered join to the
        hub). Returns the augmented matrices ``M, K, C, G_pt,
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
            fuse = s.get("fuse")
            for d in range(2):
                i = self.info["dof"](*_node(s), d)
                h = self.info["dof"]("hub", s["hub"], d)
                if fuse is not None:
                    f = self.info["dof"]("hub", fuse["housing"], d)
                    _couple(K, f, h, _nonneg(f"support {key} fuse k", fuse["k"]))
                    _couple(C, f, h, _nonneg(f"support {key} fuse c", fuse["c"]))
                    h = f
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
                i = self.info["dof"](*_node(s), d)
                j = self.info["dof"]("hub", s["hub"], d)
                _couple(K, i, j, k)
                _couple(C, i, j, s["c_film"])
        return K, C


def _node(support: dict) -> tuple:
    """(spool, node) of a linearised support: ``node`` = [spool, node], or ``pt_node`` on spool "pt"."""
    if "node" in support:
        return tuple(support["node"])
    return ("pt", support["pt_node"])


def _couple(A, i, j, k):
    """Add a spring k between DOFs i and j (j = None: to ground)."""
    A[i, i] += k
    if j is not None:
        A[j, j] += k
        A[i, j] -= k
        A[j, i] -= k


def _positive(name, value):
    if value is None:   # a key the file leaves out (check-engine lists it: engine_parts.absent)
        raise ValueError(f"rotor model: {name} missing (a finite number > 0; docs/reference/engine-format.md)")
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
    r = data["spool"][rotor]
    d_out = [_positive(f"spool.{rotor}.d_out_mm[{k}]", knob_value(data, v)) * 1e-3 for k, v in enumerate(r["d_out_mm"])]
    d_in = [_nonneg(f"spool.{rotor}.d_in_mm[{k}]", knob_value(data, v)) * 1e-3 for k, v in enumerate(r["d_in_mm"])]
    return d_out, d_in


def knob_value(data: dict, value):
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
    """Assemble the full model from the data (docs/reference/engine-format.md for the meaning of each entry); a missing
    table or key, or a value of the wrong kind, is a ValueError naming the file (``source``) and the key."""
    where = f"rotor model file {source or DEFAULT_FILE}"
    refuse(shape_problems(data), where)
    try:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # non-finite matrices refused below
            return _assemble(data, digest, omega_pt, omega_gg)
    except KeyError as exc:
        raise ValueError(f"{where}: missing table or key {exc.args[0]!r} (see docs/reference/engine-format.md)") from None
    except (TypeError, IndexError, AttributeError) as exc:
        raise ValueError(f"{where}: a value of the wrong kind or size ({type(exc).__name__}: {exc}; see "
                         "docs/reference/engine-format.md)") from None
    except ValueError as exc:
        msg = str(exc)
        if msg.startswith("rotor model file"):
            raise ValueError(msg) from None
        raise ValueError(f"{where}: {msg.removeprefix('rotor model: ')}") from None


def _material(data: dict, name: str, where: str) -> tuple[float, float, float, float]:
    """(E, G, rho, nu) of ``[material.NAME]``: E, rho and either nu (G = E / 2(1 + nu)) or G (ROSS's G_s; nu =
    E / 2G - 1)."""
    mats = data.get("material", {})
    if name not in mats:
        raise ValueError(f"rotor model: {where} names material {name!r}, which [material] does not define "
                         f"(defined: {', '.join(mats) or 'none'})")
    m = mats[name]
    E, rho = (_positive(f"material.{name}.{k}", m[k]) for k in ("E", "rho"))
    if "G" in m:
        G = _positive(f"material.{name}.G", m["G"])
        return E, G, rho, _poisson(f"material.{name} (nu = E / 2G - 1)", E / (2.0 * G) - 1.0)
    nu = _poisson(f"material.{name}.nu", m["nu"])
    return E, E / (2 * (1 + nu)), rho, nu


def _spools(data: dict) -> dict:
    sp = data["spool"]
    if not isinstance(sp, dict) or not sp:
        raise ValueError("rotor model: [spool.NAME] tables needed (one per shaft), none found")
    if len(sp) > MAX_SPOOLS:
        raise ValueError(f"rotor model: {len(sp)} spools; the engine format carries at most {MAX_SPOOLS} "
                         f"({', '.join(sp)})")
    for reserved in ("hub", "ground"):
        if reserved in sp:
            raise ValueError(f"rotor model: a spool may not be named {reserved!r} (a reserved word of node references)")
    return sp


def _assemble(data: dict, digest: str, omega_pt: float | None, omega_gg: float | None) -> FullModel:
    fmt = data.get("engine", {}).get("format", FORMAT)
    if fmt != FORMAT:
        raise ValueError(f"rotor model: [engine] format = {fmt!r}; this version reads format {FORMAT}")
    spools = _spools(data)
    names = list(spools)
    z = {}
    for s in names:
        z[s] = np.asarray(spools[s]["z_mm"], float) * 1e-3
        if len(z[s]) < 2:
            raise ValueError(f"rotor model: spool.{s}.z_mm needs at least 2 stations, got {len(z[s])}")
        if not np.all(np.isfinite(z[s])):
            raise ValueError(f"rotor model: spool.{s}.z_mm has a value that is not a finite number")
        if not np.all(np.diff(z[s]) > 0):
            k = int(np.nonzero(np.diff(z[s]) <= 0)[0][0])
            raise ValueError(f"rotor model: spool.{s}.z_mm must increase strictly (stations overlap: node {k + 1} "
                             f"at {spools[s]['z_mm'][k + 1]} mm is not after node {k} at {spools[s]['z_mm'][k]} mm)")
    cas = data.get("casing")
    peds = data.get("pedestal", {})

    # global numbering before constraints: spool nodes (6 DOF), shell nodes, hubs (3 DOF: casing hubs, pedestals)
    base = {}
    nxt = 0
    for s in names:
        base[s] = nxt
        nxt += 6 * len(z[s])
    base_sh = nxt
    if cas is not None:
        nc = int(cas["n_circ"])
        rings = np.asarray(cas["ring_z_mm"], float) * 1e-3
        if nc < 4 or len(rings) < 2 or not np.all(np.diff(rings) > 0):
            raise ValueError("rotor model: casing needs n_circ >= 4 and >= 2 strictly increasing ring_z_mm")
        n_shell_nodes = 2 * nc * len(rings)
        hubs = list(cas["hubs"].keys())
    else:
        nc, rings, n_shell_nodes, hubs = 0, np.zeros(0), 0, []
    for p in peds:
        if p in hubs:
            raise ValueError(f"rotor model: hub {p!r} is both a casing hub and a pedestal")
    hubs = hubs + list(peds)
    # a fused bearing's own housing: a body of its own after the hubs (its name no TOML key of a hub can clash with)
    fuses = fuse_ids(data)
    hubs = hubs + [fused_housing(f) for f in fuses]
    base_hub = base_sh + 3 * n_shell_nodes
    ntot = base_hub + 3 * len(hubs)

    def shell_node(ring, circ, layer):  # layer 0 inner, 1 outer
        return (ring * nc + circ % nc) * 2 + layer

    def gdof(body, node, d):
        if body == "hub":
            if node not in hubs:
                raise ValueError(f"rotor model: unknown hub {node!r} (known: {', '.join(hubs) or 'none'})")
            if d > 2:
                raise ValueError("rotor model: hubs have 3 DOF")
            return base_hub + 3 * hubs.index(node) + d
        if body in z:
            nn = len(z[body])
            if isinstance(node, bool) or not isinstance(node, (int, np.integer)) or not 0 <= int(node) < nn:
                raise ValueError(f"rotor model: {spools[body].get('name', body)} ({body}) node {node!r} out of "
                                 f"range 0-{nn - 1}")
            return base[body] + 6 * int(node) + d
        raise ValueError(f"rotor model: unknown body {body!r} (spools: {', '.join(names)}; or 'hub')")

    M = np.zeros((ntot, ntot))
    K = np.zeros((ntot, ntot))
    G = {s: np.zeros((ntot, ntot)) for s in names}
    C_shafts = np.zeros((ntot, ntot))   # the spools' own Rayleigh damping, element by element (ROSS's alpha, beta)

    # spools: Timoshenko shaft elements and disks
    for s in names:
        r = spools[s]
        E, Gmod, rho, _ = _material(data, r.get("material", "rotor"), f"spool.{s}")
        d_out, d_in = rotor_diameters(data, s)
        if len(d_out) != len(z[s]) - 1 or len(d_in) != len(z[s]) - 1:
            raise ValueError(f"rotor model: spool.{s} needs {len(z[s]) - 1} section diameters (one per element "
                             f"between its {len(z[s])} stations), got {len(d_out)} outer and {len(d_in)} inner")
        beam = element_options(r, s, len(z[s]) - 1)
        for e in range(len(z[s]) - 1):
            if not d_in[e] < d_out[e]:
                raise ValueError(f"rotor model: spool.{s} section {e}: inner diameter {d_in[e] * 1e3:g} mm is not "
                                 f"smaller than the outer {d_out[e] * 1e3:g} mm")
            ke, me, ge = shaft_element(z[s][e + 1] - z[s][e], E, Gmod, rho, d_out[e], d_in[e], beam.shear,
                                       beam.rotary)
            idx = np.arange(base[s] + 6 * e, base[s] + 6 * e + 12)
            K[np.ix_(idx, idx)] += ke
            M[np.ix_(idx, idx)] += me
            G[s][np.ix_(idx, idx)] += ge
            C_shafts[np.ix_(idx, idx)] += beam.alpha[e] * me + beam.beta[e] * ke
        _add_layers(data, s, z[s], base[s], K, M, G[s], C_shafts, beam)
        for dk in r.get("disks", []):
            m_d, Ip, Id = disk_inertia(data, dk)
            for k, v in (("mass", m_d), ("Ip", Ip), ("Id", Id)):
                if not (math.isfinite(v) and v >= 0):
                    raise ValueError(f"rotor model: spool.{s} disk {dk.get('name', '')!r} {k} must be a finite "
                                     f"number >= 0, got {v!r}")
            md, gd = disk(m_d, Ip, Id)
            n = dk["node"]
            if isinstance(n, bool) or not isinstance(n, int) or not 0 <= n < len(z[s]):
                raise ValueError(f"rotor model: spool.{s} disk {dk.get('name', '')!r} node {n!r} out of range "
                                 f"0-{len(z[s]) - 1}")
            idx = np.arange(base[s] + 6 * n, base[s] + 6 * n + 6)
            M[np.ix_(idx, idx)] += md
            G[s][np.ix_(idx, idx)] += gd

    # casing shell: 8-node solids, one through the thickness
    if cas is not None:
        Ec, _, rhoc, nuc = _material(data, cas.get("material", "casing"), "casing")
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
    C = C_shafts

    # casing hubs and struts (spring elements in the local radial / tangential / axial frame)
    if cas is not None:
        st = cas["struts"]
        for h, hv in cas["hubs"].items():
            # a hub may have its own bearing frame (``struts = {k_r, k_t, k_a}``), else the casing's common one
            sth = hv.get("struts", st)
            kr, kt, ka = (_positive(f"casing.hubs.{h}.struts.{k}" if "struts" in hv else f"casing.struts.{k}",
                                    sth[k]) for k in ("k_r", "k_t", "k_a"))
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
    # pedestals: hubs on springs to ground (no casing needed), each of some mass (M positive definite)
    for h, pv in peds.items():
        mh = _positive(f"pedestal.{h}.mass", pv["mass"])
        kxy = [_positive(f"pedestal.{h}.{k if k in pv else 'k'}", knob_value(data, pv[k] if k in pv else pv["k"]))
               for k in ("kxx", "kyy")]
        cxy = [_nonneg(f"pedestal.{h}.{k if k in pv else 'c'}", pv[k] if k in pv else pv.get("c", 0.0))
               for k in ("cxx", "cyy")]
        ka = _positive(f"pedestal.{h}.k_axial", knob_value(data, pv.get("k_axial", kxy[0])))
        for d, kd in ((0, kxy[0]), (1, kxy[1]), (2, ka)):
            i = gdof("hub", h, d)
            M[i, i] += mh
            _couple(K, i, None, kd)
            if d < 2:
                _couple(C, i, None, cxy[d])

    # fused housings: the mass, and the fuse's axial hold on the hub (its radial support is the co-simulated fuse)
    for f in fuses:
        spec = data["fuse"][f]
        entry = data.get("attach", {}).get(f"bearing{f}")
        if not isinstance(entry, dict) or "housing" not in entry:
            raise ValueError(f"rotor model: [fuse.{f}] is at bearing{f}, which [attach] does not have (a fuse "
                             "carries a bearing's housing)")
        mh = _positive(f"[fuse.{f}] housing_mass_kg", spec.get("housing_mass_kg"))
        i, j = gdof("hub", fused_housing(f), 2), gdof("hub", entry["housing"], 2)
        for d in range(3):
            M[gdof("hub", fused_housing(f), d), gdof("hub", fused_housing(f), d)] += mh
        _couple(K, i, j, _positive(f"[fuse.{f}] k_intact", spec.get("k_intact")))

    # mounts to ground
    for m_i, mt in enumerate(cas.get("mounts", ()) if cas is not None else ()):
        ring, node, d = int(mt["ring"]), int(mt["node"]), int(mt["dir"])
        if not (0 <= ring < len(rings) and 0 <= node < nc and 0 <= d < 3):
            raise ValueError(f"rotor model: casing mount {m_i} ({mt}) out of range")
        i = base_sh + 3 * shell_node(ring, node, 1) + d
        _couple(K, i, None, _positive(f"casing.mounts[{m_i}].k", knob_value(data, mt["k"])))
        _couple(C, i, None, _nonneg(f"casing.mounts[{m_i}].c", mt["c"]))

    # mounts to the airframe: each spring to ground here, the airframe's motion an input (mounts.py)
    mount_dofs = {}
    for mname, mt in mount_tables.mounts(data).items():
        mount_dofs[mname] = [_mount_dof(gdof, f"[mount.{mname}] springs[{s_i}].node", sp, rings, nc, base_sh,
                                        shell_node) for s_i, sp in enumerate(mt.springs)]
        for i, sp in zip(mount_dofs[mname], mt.springs):
            _couple(K, i, None, sp.k)
            _couple(C, i, None, sp.c)

    # linear supports and intermediate bearings (Table 2 for the paper's engine)
    tables = []
    w_first = abs(float(spools[names[0]]["speed_rpm"])) * RPM
    for s_i, s in enumerate(data.get("support", [])):
        a, b = s["a"], s["b"]
        label = f"support {s.get('name', '')!r}"
        if a == b:
            raise ValueError(f"rotor model: {label}: a and b are the same node {a} (a support between a node and "
                             "itself carries no force)")
        if is_speed_dependent(s):
            tables.append(_support_table(s, s_i, label, gdof(a[0], a[1], 0), gdof(a[0], a[1], 1),
                                         None if b == "ground" else (gdof(b[0], b[1], 0), gdof(b[0], b[1], 1))))
            kt, ct = support_matrices(tables[-1], w_first)
            _couple_2x2(K, tables[-1]["dofs"], kt)
            _couple_2x2(C, tables[-1]["dofs"], ct)
            if "k_axial" in s:
                j = None if b == "ground" else gdof(b[0], b[1], 2)
                _couple(K, gdof(a[0], a[1], 2), j, _positive("k_axial", s["k_axial"]))
            continue
        kxy = [_positive(f"{label} {k}", s[k] if k in s else s["k"]) for k in ("kxx", "kyy")]
        cxy = [_nonneg(f"{label} {k}", s[k] if k in s else s.get("c", 0.0)) for k in ("cxx", "cyy")]
        for d in range(2):
            i = gdof(a[0], a[1], d)
            j = None if b == "ground" else gdof(b[0], b[1], d)
            _couple(K, i, j, kxy[d])
            _couple(C, i, j, cxy[d])
        if "k_axial" in s:
            j = None if b == "ground" else gdof(b[0], b[1], 2)
            _couple(K, gdof(a[0], a[1], 2), j, _positive("k_axial", s["k_axial"]))

    # Rayleigh damping of the structure: zeta at f1 and f2
    dmp = data["damping"]
    zeta = _nonneg("damping.zeta", dmp["zeta"])
    w1, w2 = 2 * math.pi * _positive("f1_Hz", dmp["f1_Hz"]), 2 * math.pi * _positive("f2_Hz", dmp["f2_Hz"])
    alpha = 2 * zeta * w1 * w2 / (w1 + w2)
    beta = 2 * zeta / (w1 + w2)
    C += alpha * M + beta * K_struct

    # constant speed: the spin angle of each spool is prescribed at its drive node (torsion DOF held); an
    # ``axial_node`` holds the spool's axial DOF there too (a spool with no axial support, e.g. from ROSS)
    fixed = []
    for s in names:
        fixed.append(gdof(s, spools[s]["drive_node"], 5))
        if "axial_node" in spools[s]:
            fixed.append(gdof(s, spools[s]["axial_node"], 2))
    free = np.setdiff1d(np.arange(ntot), fixed)
    newidx = -np.ones(ntot, dtype=int)
    newidx[free] = np.arange(free.size)

    def dof(body, node, d):
        i = newidx[gdof(body, node, d)]
        if i < 0:
            raise ValueError(f"rotor model: DOF {body}:{node}:{d} is constrained")
        return int(i)

    sub = np.ix_(free, free)
    ports = _ports(data.get("attach", {}), dof, fuses)
    for mname, idx in mount_dofs.items():
        free_idx = newidx[np.asarray(idx)]
        if np.any(free_idx < 0):
            raise ValueError(f"rotor model: [mount.{mname}] a spring acts on a held DOF (a spool's drive_node "
                             "torsion or axial_node)")
        ports[mount_tables.port_group(mname)] = free_idx
    lateral = [dof(s, n, d) for s in names for n in range(len(z[s])) for d in range(2)]
    for s in names:
        # the speed ratio of the second spool to the first divides by the first (0 was a ZeroDivisionError); a
        # negative speed is a spool turning the other way, kept
        v = spools[s]["speed_rpm"]
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v != 0):
            raise ValueError(f"rotor model: spool.{s}.speed_rpm must be a finite, non-zero speed in rev/min, "
                             f"got {v!r}")
    w_pt = spools[names[0]]["speed_rpm"] * RPM if omega_pt is None else float(omega_pt)
    w_gg = (spools[names[1]]["speed_rpm"] * RPM if len(names) > 1 else w_pt) if omega_gg is None else float(omega_gg)
    for name, A in (("mass", M), ("stiffness", K), ("damping", C)):
        if not np.all(np.isfinite(A)):
            # a value so large that the element matrices overflow (casing.radius_mm = 1e300)
            raise ValueError(f"rotor model: the assembled {name} matrix is not finite: a length, modulus or mass "
                             "of the file is too large (lengths are in mm)")
    xs = base_sh + 3 * np.arange(n_shell_nodes)          # the shell's x DOFs: its translational mass
    for t in tables:
        t["dofs"] = tuple(None if i is None else int(newidx[i]) for i in t["dofs"])
        t["speed_rad_s"] = w_first
    info = {"speed_supports": tables, "dof": dof, "rayleigh": (alpha, beta), "n_shell_dof": 3 * n_shell_nodes, "n_hub_dof": 3 * len(hubs),
            "casing_mass_kg": float(M[np.ix_(xs, xs)].sum()) if n_shell_nodes else 0.0,
            "spools": {s: len(z[s]) for s in names}, "hubs": hubs,
            "pt_lateral": np.array([dof(names[0], n, d) for n in range(len(z[names[0]])) for d in range(2)])}
    G_gg = G[names[1]][sub] if len(names) > 1 else np.zeros((free.size, free.size))
    for s in names[2:]:
        # a third spool and later: their gyroscopic terms ride on the second spool's speed, at the files' ratio
        # (omega_gg G_gg = sum of w_i G_i at the files' speeds)
        G_gg = G_gg + (spools[s]["speed_rpm"] / spools[names[1]]["speed_rpm"]) * G[s][sub]
    return FullModel(M=M[sub], K=K[sub], C=C[sub], G_pt=G[names[0]][sub], G_gg=G_gg,
                     ports=ports, rotor_lateral=np.asarray(lateral),
                     omega_pt=w_pt, omega_gg=w_gg, data=data, digest=digest, info=info)


def _mount_dof(gdof, where: str, spring, rings, nc: int, base_sh: int, shell_node) -> int:
    """The global DOF a mount's spring acts on (mounts.py: a casing outer node, a spool node or a hub)."""
    node, d = spring.node, spring.dir
    if node[0] == mount_tables.CASING:
        if len(node) != 3 or not all(isinstance(v, int) and not isinstance(v, bool) for v in node[1:]):
            raise ValueError(f'{where}: a casing node is ["casing", ring, circ], got {list(node)!r}')
        if not len(rings):
            raise ValueError(f"{where}: the engine has no [casing]")
        ring, circ = node[1], node[2]
        if not (0 <= ring < len(rings) and 0 <= circ < nc):
            raise ValueError(f"{where}: casing node {list(node)!r} does not exist (rings 0-{len(rings) - 1}, "
                             f"circumferential nodes 0-{nc - 1})")
        if d > 2:
            raise ValueError(f"{where}: dir {d}: a casing node has translations only (dir 0-2)")
        return base_sh + 3 * shell_node(ring, circ, 1) + d
    if len(node) != 2:
        raise ValueError(f'{where}: must be ["casing", ring, circ], [spool, node] or ["hub", name], got '
                         f"{list(node)!r}")
    if node[0] == "hub" and d > 2:
        raise ValueError(f"{where}: dir {d}: a hub has translations only (dir 0-2)")
    try:
        return gdof(node[0], node[1], d)
    except ValueError as exc:
        raise ValueError(f"{where}: {str(exc).removeprefix('rotor model: ')}") from None


@dataclass(frozen=True)
class ElementOptions:
    """A spool's beam options (engine format: ``shear_effects``, ``rotary_inertia``, ``rayleigh``): Timoshenko
    (``shear``) or Euler-Bernoulli beams, with or without rotary inertia in the mass matrix (the gyroscopic terms
    stay), and each element's own Rayleigh damping C_e = alpha_e M_e + beta_e K_e (ROSS's ShaftElement alpha,
    beta), per element."""

    shear: bool
    rotary: bool
    alpha: tuple[float, ...]
    beta: tuple[float, ...]


def element_options(spool: dict, s: str, ne: int) -> ElementOptions:
    """The :class:`ElementOptions` of spool ``s`` (its table ``spool``, ``ne`` elements)."""
    ray = spool.get("rayleigh", {})

    def per_element(key):
        v = ray.get(key, 0.0)
        vals = list(v) if isinstance(v, list) else [v] * ne
        if len(vals) != ne:
            raise ValueError(f"rotor model: spool.{s}.rayleigh.{key} needs one value per element ({ne}), got "
                             f"{len(vals)}")
        return tuple(_nonneg(f"spool.{s}.rayleigh.{key}[{e}]", x) for e, x in enumerate(vals))

    return ElementOptions(bool(spool.get("shear_effects", True)), bool(spool.get("rotary_inertia", True)),
                          per_element("alpha"), per_element("beta"))


def _add_layers(data: dict, s: str, z, base: int, K, M, G, C, beam: ElementOptions) -> None:
    """The spool's ``layers``: a second (third...) shaft element between the nodes of an element, of its own
    section and material (a sleeve, a shrunk-on hub, ROSS's layered sections), added to the element's matrices
    (the beam's stiffness, mass, gyroscopic and Rayleigh damping terms are additive over concentric tubes; a
    layer takes its element's ``beam`` options)."""
    ne = len(z) - 1
    for i, layer in enumerate(data["spool"][s].get("layers", [])):
        where = f"spool.{s}.layers[{i}]"
        e = layer["element"]
        if isinstance(e, bool) or not isinstance(e, int) or not 0 <= e < ne:
            raise ValueError(f"rotor model: {where}.element {e!r} out of range 0-{ne - 1}")
        E, Gmod, rho, _ = _material(data, layer.get("material", data["spool"][s].get("material", "rotor")), where)
        d_out = _positive(f"{where}.d_out_mm", layer["d_out_mm"]) * 1e-3
        d_in = _nonneg(f"{where}.d_in_mm", layer["d_in_mm"]) * 1e-3
        if not d_in < d_out:
            raise ValueError(f"rotor model: {where}: inner diameter {d_in * 1e3:g} mm is not smaller than the outer "
                             f"{d_out * 1e3:g} mm")
        ke, me, ge = shaft_element(z[e + 1] - z[e], E, Gmod, rho, d_out, d_in, beam.shear, beam.rotary)
        idx = np.arange(base + 6 * e, base + 6 * e + 12)
        K[np.ix_(idx, idx)] += ke
        M[np.ix_(idx, idx)] += me
        G[np.ix_(idx, idx)] += ge
        C[np.ix_(idx, idx)] += beam.alpha[e] * me + beam.beta[e] * ke


#: the coefficients of a support, x y direct and cross-coupled
COEFFICIENTS = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")


def is_speed_dependent(support: dict) -> bool:
    """A [[support]] with coefficient tables over ``speed_rpm`` or cross-coupled coefficients: the linear
    engine takes its coefficients at each speed (:func:`support_matrices`)."""
    return "speed_rpm" in support or any(k in support for k in ("kxy", "kyx", "cxy", "cyx"))


def _support_table(s: dict, s_i: int, label: str, ix: int, iy: int, far) -> dict:
    """A speed-dependent support as data: its coefficients (arrays over ``speed_rpm``, or one value) and DOFs."""
    speeds = s.get("speed_rpm")
    if speeds is not None:
        speeds = np.asarray([_nonneg(f"{label} speed_rpm[{k}]", v) for k, v in enumerate(speeds)]) * RPM
        if speeds.size < 1 or not np.all(np.diff(speeds) > 0):
            raise ValueError(f"rotor model: {label} speed_rpm must increase strictly")
    out = {"name": s.get("name", f"support[{s_i}]"), "speeds": speeds, "dofs": (ix, iy) + (far or (None, None))}
    for k in COEFFICIENTS:
        default = s.get("k" if k in ("kxx", "kyy") else "c" if k in ("cxx", "cyy") else "", 0.0)
        v = s.get(k, default)
        vals = np.atleast_1d(np.asarray(v, float))
        if not np.all(np.isfinite(vals)):
            raise ValueError(f"rotor model: {label} {k} must be finite numbers, got {v!r}")
        if vals.size > 1 and (speeds is None or vals.size != speeds.size):
            raise ValueError(f"rotor model: {label} {k} has {vals.size} values; give one per speed_rpm "
                             f"({0 if speeds is None else speeds.size})")
        if k in ("kxx", "kyy") and not np.all(vals > 0):
            raise ValueError(f"rotor model: {label} {k} must be > 0, got {v!r}")
        out[k] = vals
    return out


def coefficient_at(speeds, values, w: float) -> float:
    """A support coefficient at the speed w [rad/s]: the one value, or the table through its speeds as ROSS
    (BearingElement) interpolates it, so that an imported ROSS rotor has ROSS's coefficients at every speed:
    scipy's UnivariateSpline (cubic, smoothing factor the number of points, extrapolated) for 4 values or more,
    a polynomial through 2 or 3."""
    if values.size == 1:
        return float(values[0])
    from scipy import interpolate

    if values.size >= 4:
        return float(interpolate.UnivariateSpline(speeds, values)(w))
    return float(interpolate.interp1d(speeds, values, kind=values.size - 1, fill_value="extrapolate")(w))


def support_matrices(table: dict, w: float) -> tuple[np.ndarray, np.ndarray]:
    """The 2x2 stiffness and damping of a speed-dependent support at the speed w [rad/s]:
    [[kxx, kxy], [kyx, kyy]] (force on node a = -K (u_a - u_b))."""
    v = {k: coefficient_at(table["speeds"], table[k], w) for k in COEFFICIENTS}
    return (np.array([[v["kxx"], v["kxy"]], [v["kyx"], v["kyy"]]]),
            np.array([[v["cxx"], v["cxy"]], [v["cyx"], v["cyy"]]]))


def _couple_2x2(A, dofs, k2) -> None:
    """Add a 2x2 (possibly unsymmetric) coupling k2 between (x, y) of node a and (x, y) of b (None: ground)."""
    a = [i for i in dofs[:2]]
    b = None if dofs[2] is None else list(dofs[2:])
    A[np.ix_(a, a)] += k2
    if b is not None:
        A[np.ix_(b, b)] += k2
        A[np.ix_(a, b)] -= k2
        A[np.ix_(b, a)] -= k2


def projected_support_delta(full: "FullModel", basis: np.ndarray, w: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`speed_support_delta` projected on ``basis`` (the full model's DOFs by the reduced ones), support
    by support: B^T dK B and B^T dC B with, for a support between nodes a and b (or ground), its 2x2 change
    acting on u_a - u_b: (B_a - B_b)^T dk (B_a - B_b). Zero matrices for an engine without such supports."""
    m = basis.shape[1]
    dK, dC = np.zeros((m, m)), np.zeros((m, m))
    for t in full.info.get("speed_supports", []):
        k1, c1 = support_matrices(t, w)
        k0, c0 = support_matrices(t, t["speed_rad_s"])
        D = basis[list(t["dofs"][:2])]
        if t["dofs"][2] is not None:
            D = D - basis[list(t["dofs"][2:])]
        dK += D.T @ (k1 - k0) @ D
        dC += D.T @ (c1 - c0) @ D
    return dK, dC


def speed_support_delta(full: "FullModel", w: float, n: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(dK, dC): what the speed-dependent supports add at the speed w [rad/s] of the first spool beyond what the
    assembled K and C hold (their coefficients at the file's speed); ``n`` the size of the matrices (the model's,
    or a larger one whose first DOFs are the model's)."""
    n = full.n if n is None else n
    dK, dC = np.zeros((n, n)), np.zeros((n, n))
    for t in full.info.get("speed_supports", []):
        k1, c1 = support_matrices(t, w)
        k0, c0 = support_matrices(t, t["speed_rad_s"])
        _couple_2x2(dK, t["dofs"], k1 - k0)
        _couple_2x2(dC, t["dofs"], c1 - c0)
    return dK, dC


def fuse_ids(data: dict) -> tuple[str, ...]:
    """The ids of an engine file's ``[fuse.ID]`` tables: the bearings whose housing sits on a support fuse."""
    fuses = data.get("fuse", {})
    return tuple(fuses) if isinstance(fuses, dict) else ()


def fused_housing(fid: str) -> str:
    """The body name of fused bearing ``fid``'s own housing (a hub of the model: ``dof("hub", name, d)``)."""
    return f"bearing{fid} housing"


def _ports(attach: dict, dof, fuses=()) -> dict:
    """The port groups of the [attach] entries the file gives (attach.groups: any number of bearings and rub
    rings; a fused bearing's housing is its own body, the fuse's structure side the hub of its entry)."""
    ports = {}
    for group, entry, what, n in attach_layout.groups(attach_layout.layout(attach, fuses)):
        if entry not in attach:
            continue
        a = attach[entry]
        if what in ("housing", "fuse"):
            fid = entry[len("bearing"):]
            body = fused_housing(fid) if fid in fuses else a["housing"]
            ports[group] = np.asarray([dof("hub", body, d) for d in range(n)])
        elif what == "fusehub":
            ports[group] = np.asarray([dof("hub", a["housing"], d) for d in range(n)])
        else:
            node = a["node"]
            if not (isinstance(node, list) and len(node) == 2):
                raise ValueError(f"rotor model: [attach] {entry}.node must be [spool, node], got {node!r}")
            ports[group] = np.asarray([dof(node[0], node[1], d) for d in range(n)])
    return ports


def require_ports(full: FullModel, groups) -> None:
    """A ValueError naming the [attach] entries the model lacks for the port groups ``groups``."""
    missing = [g for g in groups if g not in full.ports]
    if "unbalance" in missing:
        raise ValueError("rotor model: [attach] has no unbalance (the blade-loss rotor component needs it, and at "
                         "least one bearing<ID>; docs/reference/engine-format.md)")
    if not any(g.startswith("brg") for g in full.ports):
        raise ValueError("rotor model: [attach] has no bearing<ID> (the blade-loss rotor component needs at least "
                         "one co-simulated bearing; docs/reference/engine-format.md)")
    if missing:
        raise ValueError(f"rotor model: no port group {', '.join(missing)} (docs/reference/engine-format.md)")


def load(path: str | Path | None = None, **kw) -> FullModel:
    data, digest = load_data(path)
    return build(data, digest, source=path, **kw)
