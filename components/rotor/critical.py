"""Synchronous critical speeds and the Campbell diagram of the engine model.

At a synchronous critical speed the whirl frequency equals the power-turbine spin Omega (the gas generator turning
at r Omega, r = 15000/16000). With q = phi exp(i Omega t) the undamped equation of motion
M q'' + Omega (G_pt + r G_gg) q' + K q = 0 becomes

    K phi = Omega^2 (M - i G~) phi,     G~ = G_pt + r G_gg,

a linear generalized eigenproblem in s = Omega^2 with K symmetric positive definite and M - i G~ Hermitian
(G~ is real skew-symmetric), solved exactly as the Hermitian-definite problem (M - i G~) phi = (1/s) K phi.
Each real root s > 0 is a critical speed; its mode whirls forward (with the spin) or backward, classified by the
rotor nodes' orbit: x + i y = a_f exp(i Omega t) + a_b exp(-i Omega t), a_f = (X + iY)/2, a_b = conj(X - iY)/2.
Damping is left out (undamped critical speeds, the usual definition; Genta, Dynamics of Rotating Systems, 4.7).
Roots whose mode has almost no lateral rotor motion (torsional and axial rotor modes, casing-only modes: rotor
lateral share of the kinetic energy below ``min_share``) are not whirl modes and are not listed.
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla
from scipy.sparse.linalg import ArpackNoConvergence

from .model import RPM, FullModel, speed_support_delta


#: what the critical speeds of an engine with speed-dependent or cross-coupled supports are
DAMPED_DEFINITION = ("the speeds at which a natural frequency |lambda| of the damped engine, its supports' "
                     "coefficients taken at that speed, equals the speed (ROSS's run_critical_speed)")


def speed_ratio(model: FullModel) -> float:
    return model.omega_gg / model.omega_pt


def _system(model: FullModel, supports: dict | None) -> dict:
    """The matrices the eigenproblems use: the engine with its #0/#5 supports (:meth:`FullModel.coupled`), or
    the model alone (supports None: bearings #0/#5 absent, e.g. for the MTA basis)."""
    if supports is None:
        return {"M": model.M, "K": model.K, "G_pt": model.G_pt, "G_gg": model.G_gg,
                "rotor_lateral": model.rotor_lateral}
    return model.coupled(supports)


def _free_part(model: FullModel, A: np.ndarray) -> str:
    """The part of the engine that moves most in the null mode of the symmetric matrix ``A`` (the model's DOFs
    first, then the journals of :meth:`FullModel.coupled`): "spool 'hp'", "hub 'h0'", "the casing"."""
    w, v = np.linalg.eigh(0.5 * (A + A.T))
    u2 = v[:, 0] ** 2
    share = {}
    dof = model.info["dof"]
    for s, n_nodes in model.info.get("spools", {}).items():
        for node in range(n_nodes):
            for d in range(6):
                try:
                    share[f"spool {s!r}"] = share.get(f"spool {s!r}", 0.0) + u2[dof(s, node, d)]
                except ValueError:          # a DOF the spool's drive or axial node holds
                    pass
    for h in model.info.get("hubs", []):
        share[f"hub {h!r}"] = sum(u2[dof("hub", h, d)] for d in range(3))
    share["a co-simulated bearing's journal"] = float(u2[model.n:].sum())
    share["the casing"] = max(1.0 - sum(share.values()), 0.0)
    return max(share, key=share.get)


def _definite_eigh(a: np.ndarray, b: np.ndarray, model: FullModel, b_is: str, **kw):
    """``scipy.linalg.eigh(a, b)``, whose ``b`` must be positive definite: the engine's stiffness with its
    supports (``b_is`` "stiffness") or its mass ("mass"). A singular one (a spool nothing holds; a DOF without
    mass) is an input error naming the part, not LAPACK's 'leading minor of order 72 of B'."""
    try:
        return sla.eigh(a, b, **kw)
    except np.linalg.LinAlgError:
        part = _free_part(model, b.real)
    if b_is == "stiffness":
        raise ValueError(f"the engine's stiffness with its supports is singular: {part} moves freely, held by no "
                         "spring (a spool needs supports, pedestals, attached bearings or intershaft bearings at "
                         "two nodes or more)") from None
    raise ValueError(f"the engine's mass matrix is singular: {part} has a motion without mass") from None


def synchronous_critical_speeds(model: FullModel, supports: dict | None, n: int = 12,
                                max_rpm: float = 60000.0, min_share: float = 0.05) -> dict:
    """Forward and backward synchronous critical speeds (rev/min of the power turbine), ascending, of the model
    with the supports of :meth:`FullModel.coupled` (None: without bearings #0/#5)."""
    if model.info.get("speed_supports"):
        rows = speed_dependent_critical_speeds(model, supports, max_rpm, min_share=min_share)
        out = {k: sorted(r["rpm"] for r in rows if r["whirl"] == w)[:n]
               for k, w in (("forward_synchronous_rpm", "forward"), ("backward_synchronous_rpm", "backward"))}
        out["definition"] = DAMPED_DEFINITION
        return out
    sysm = _system(model, supports)
    K, Mm = sysm["K"], sysm["M"]
    Gt = sysm["G_pt"] + speed_ratio(model) * sysm["G_gg"]
    B = Mm - 1j * Gt
    nn = K.shape[0]
    # an engine on an airframe (components/airframe/installed.py): its modes come on top of the engine's
    take = 4 * n + int(model.info.get("airframe_modes", 0))
    mu, vec = _definite_eigh(B, K, model, "stiffness", subset_by_index=[max(nn - take, 0), nn - 1])
    out = {"forward_synchronous_rpm": [], "backward_synchronous_rpm": []}
    lat = sysm["rotor_lateral"]
    Mlat = Mm[np.ix_(lat, lat)]
    for rpm, forward in _whirl_roots(mu[::-1], vec[:, ::-1].T, Mm, lat, Mlat, max_rpm, min_share):
        out["forward_synchronous_rpm" if forward else "backward_synchronous_rpm"].append(rpm)
    for k in out:
        out[k] = sorted(out[k])[:n]
    return out


def campbell(model: FullModel, rpm_values, supports: dict | None, n_modes: int = 80, n_show: int = 24,
             min_share: float = 0.05):
    """Undamped whirl frequencies (Hz) vs PT speed on a modal basis of the lowest ``n_modes`` non-spinning modes,
    with a flag per frequency: +1 forward, -1 backward, 0 not a rotor whirl (lateral rotor share < min_share)."""
    sysm = _system(model, supports)
    K, Mm = sysm["K"], sysm["M"]
    tables = bool(model.info.get("speed_supports"))
    # a basis of the non-spinning modes (of the symmetric part, for supports with cross-coupled coefficients)
    w2, Phi = _definite_eigh(0.5 * (K + K.T) if tables else K, Mm, model, "mass",
                             subset_by_index=[0, n_modes - 1])
    Gt = Phi.T @ (sysm["G_pt"] + speed_ratio(model) * sysm["G_gg"]) @ Phi
    lat = sysm["rotor_lateral"]
    # the kinetic-energy shares in the modal basis: q = Phi v gives q^H M q = v^H (Phi^T M Phi) v and the rotor's
    # lateral part v^H (Phi_l^T M_ll Phi_l) v, small matrices built once (the full M per mode and speed cost
    # O(n^2) each)
    Pl = Phi[lat]
    M_all = Phi.T @ Mm @ Phi
    M_lat = Pl.T @ Mm[np.ix_(lat, lat)] @ Pl
    Px, Py = Phi[lat[0::2]], Phi[lat[1::2]]
    freqs, kind = [], []
    for rpm in rpm_values:
        Om = rpm * RPM
        Kr = np.diag(w2)
        if tables:       # the supports' coefficients at this speed, cross-coupled terms included
            Kr = Phi.T @ (K + speed_support_delta(model, Om, K.shape[0])[0]) @ Phi
        A = np.block([[np.zeros((n_modes, n_modes)), np.eye(n_modes)], [-Kr, -Om * Gt]])
        lam, V = np.linalg.eig(A)
        keep = lam.imag > 1e-6
        lam, V = lam[keep], V[:n_modes, keep]
        order = np.argsort(lam.imag)[:n_show]
        lam, V = lam[order], V[:, order]
        share = (np.real(np.einsum("ij,ij->j", V.conj(), M_lat @ V))
                 / np.real(np.einsum("ij,ij->j", V.conj(), M_all @ V)))
        X, Y = Px @ V, Py @ V
        fwd = np.sum(np.abs(X + 1j * Y) ** 2, axis=0) >= np.sum(np.abs(X - 1j * Y) ** 2, axis=0)
        freqs.append(lam.imag / (2 * np.pi))
        kind.append(np.where(share < min_share, 0, np.where(fwd, 1, -1)))
    return np.asarray(freqs), np.asarray(kind)


def every_synchronous_critical_speed(model: FullModel, supports: dict | None, max_rpm: float, excited: float = 1.0,
                                     min_share: float = 0.05) -> list[dict]:
    """Every synchronous critical speed up to ``max_rpm`` with the whirl direction of its mode, ascending:
    ``[{"rpm", "whirl": "forward" | "backward"}]``. ``excited``: the exciting spool's speed over the first
    spool's (1: the first spool's unbalance; the speed ratio of the file for another spool's), the speeds in that
    spool's rev/min. Whirl at the exciting spool's speed w = excited Omega_1 with every spool turning in the
    file's ratios: K phi = w^2 (M - i G~ / excited) phi (G~ of :func:`synchronous_critical_speeds`), as many
    eigenpairs taken as reach past ``max_rpm``."""
    if model.info.get("speed_supports"):
        return speed_dependent_critical_speeds(model, supports, max_rpm, excited, min_share)
    sysm = _system(model, supports)
    K, Mm = sysm["K"], sysm["M"]
    B = Mm - 1j * (sysm["G_pt"] + speed_ratio(model) * sysm["G_gg"]) / excited
    nn = K.shape[0]
    lat = sysm["rotor_lateral"]
    Mlat = Mm[np.ix_(lat, lat)]
    take = min(24, nn)
    while True:
        mu, vec = _definite_eigh(B, K, model, "stiffness", subset_by_index=[nn - take, nn - 1])
        # mu = 1/w^2 descending from the top: the smallest taken is the highest speed reached
        if take == nn or mu[0] <= 0 or 1.0 / np.sqrt(mu[0]) / RPM > max_rpm:
            break
        take = min(2 * take, nn)
    out = [{"rpm": rpm, "whirl": "forward" if forward else "backward"}
           for rpm, forward in _whirl_roots(mu, vec.T, Mm, lat, Mlat, max_rpm, min_share)]
    return sorted(out, key=lambda r: r["rpm"])


def _whirl_roots(mu, modes, Mm, lat, Mlat, max_rpm: float, min_share: float):
    """The critical speeds among the roots ``mu`` = 1 / Omega^2 of the eigenproblem and their ``modes``, in their
    order: ``(rpm, forward)`` of each root mu > 0 up to ``max_rpm`` whose mode's rotor lateral share of the
    kinetic energy is at least ``min_share``; ``forward``: the mode whirls with the spin, |a_f|^2 >= |a_b|^2
    summed over the rotor nodes (module docstring)."""
    for m, v in zip(mu, modes):
        if m <= 0:
            continue
        rpm = 1.0 / np.sqrt(m) / RPM
        if rpm > max_rpm:
            continue
        share = np.real(v[lat].conj() @ Mlat @ v[lat]) / np.real(v.conj() @ Mm @ v)
        if share < min_share:
            continue
        X, Y = v[lat[0::2]], v[lat[1::2]]
        yield float(rpm), bool(np.sum(np.abs(X + 1j * Y) ** 2) >= np.sum(np.abs(X - 1j * Y) ** 2))


def damping_ratios(model: FullModel, supports: dict | None, criticals: list[dict], excited: float = 1.0,
                   min_share: float = 0.05) -> list[dict]:
    """Each synchronous critical speed of :func:`every_synchronous_critical_speed` (rows ``{"rpm", "whirl"}``,
    speeds of the exciting spool) with the damping ratio ``zeta = -Re lambda / |lambda|`` of its mode in the damped
    engine (the model's damping, the supports' film damping and the gyroscopic terms) at that speed: of the rotor
    whirl modes of the same whirl at the exciting spool's speed w = rpm (the first spool at w / ``excited``), the
    eigenvalue lambda whose natural frequency |lambda| is nearest w. A row that has ``damping_ratio`` already (the
    fixed points of :func:`speed_dependent_critical_speeds`) is kept; None where no mode of that whirl is found."""
    if all("damping_ratio" in r for r in criticals):
        return [dict(r) for r in criticals]
    sysm = _system(model, supports)
    if "C" not in sysm:
        sysm = {**sysm, "C": model.C}
    sysm["whirl_dofs"] = _whirl_dofs(sysm, model)
    out = []
    for r in criticals:
        if "damping_ratio" in r:
            out.append(dict(r))
            continue
        w = r["rpm"] * RPM
        try:
            modes = _modes_near(sysm, model, w / excited, w, min_share)
        except (ArpackNoConvergence, np.linalg.LinAlgError):
            # an engine far from the usual (a file in the wrong unit): every eigenvalue, the sure way
            modes = _damped_modes(sysm, model, w / excited, min_share)
        same = [lam for lam, whirl in modes if whirl == r["whirl"]]
        if not same:          # none of that whirl among the nearest few: every eigenvalue
            same = [lam for lam, whirl in _damped_modes(sysm, model, w / excited, min_share) if whirl == r["whirl"]]
        lam = min(same, key=lambda x: abs(abs(x) - w)) if same else None
        out.append({**r, "damping_ratio": damping_ratio(lam, sysm, model, w / excited) if lam is not None else None})
    return out


#: damping ratios below this are the eigensolvers' round-off, not damping: reported as 0 (an undamped mode, no
#: amplification factor). Measured: the modes of ROSS's undamped example rotors (rotor_example, coaxrotor_example:
#: no damping anywhere) came out at 1e-31-1e-27, of either sign, from the shift-invert search; the least damped
#: mode of the shipped engines and examples is at 1.8e-2 (docs/examples/three_spools).
ZETA_RESOLUTION = 1e-9


def damping_ratio(lam: complex, sysm: dict, model: FullModel, w: float) -> float:
    """The damping ratio zeta = -Re lambda / |lambda| of the eigenvalue ``lam`` of the engine ``sysm`` at the
    first spool's speed w [rad/s]: 0 where the engine dissipates nothing at that speed (its damping matrix with
    the supports' coefficients at w is zero: the gyroscopic terms conserve energy, so zeta is exactly 0 whatever
    the solver leaves in Re lambda) or where |zeta| is below :data:`ZETA_RESOLUTION`."""
    C = sysm["C"]
    if model.info.get("speed_supports"):
        C = C + speed_support_delta(model, w, C.shape[0])[1]
    if not np.any(C):
        return 0.0
    zeta = float(-lam.real / abs(lam))
    return 0.0 if abs(zeta) < ZETA_RESOLUTION else zeta


def whirl_modes(model: FullModel, supports: dict | None, rpm: float, max_hz: float,
                min_share: float = 0.05) -> list[dict]:
    """The rotor whirl modes of the damped engine (:func:`damping_ratios`' engine) with the first spool at ``rpm``
    [rev/min], every spool in the file's ratio and the speed-dependent supports' coefficients at that speed, up to
    ``max_hz``: ``[{"frequency_Hz": |lambda| / 2 pi, "whirl", "damping_ratio", "log_dec"}]`` ascending, the
    logarithmic decrement 2 pi zeta / sqrt(1 - zeta^2) (None at zeta >= 1: no oscillation). Every eigenvalue
    (a dense solve): for engines of a few hundred DOFs."""
    sysm = _system(model, supports)
    if "C" not in sysm:
        sysm = {**sysm, "C": model.C}
    sysm["whirl_dofs"] = _whirl_dofs(sysm, model)
    w = abs(float(rpm)) * RPM
    out = []
    for lam, whirl in _damped_modes(sysm, model, w, min_share):
        f = abs(lam) / (2.0 * np.pi)
        if f > max_hz:
            continue
        z = damping_ratio(lam, sysm, model, w)
        out.append({"frequency_Hz": float(f), "whirl": whirl, "damping_ratio": z,
                    "log_dec": float(2.0 * np.pi * z / np.sqrt(1.0 - z * z)) if abs(z) < 1.0 else None})
    return sorted(out, key=lambda r: r["frequency_Hz"])


#: how many eigenvalues of the damped engine :func:`_modes_near` takes around its target frequency
NEAR_MODES = 4
#: the shift-invert search's restarts at most (measured: at most 76 operator applications on the engines of the
#: tests and examples, the paper's, the three-bearing example, ROSS's coaxial rotor, a file written in metres)
MAX_ITER = 100


def _modes_near(sysm: dict, model: FullModel, w: float, target: float, min_share: float):
    """The rotor whirl modes (eigenvalue, whirl) of the damped engine at the first spool's speed w [rad/s] whose
    eigenvalues lie nearest i ``target`` [rad/s]: the :data:`NEAR_MODES` of (lambda^2 M + lambda D + K) x = 0
    (D = C + w G~, the supports' coefficients at w) nearest the shift sigma = i target, by shift-invert Arnoldi
    on its first-order form, one complex LU of K + sigma D + sigma^2 M (no inverse of M: a massless hub is
    fine), where the full eigenproblem of :func:`_damped_modes` costs ~100 x as much on an engine with a casing."""
    from scipy.sparse.linalg import LinearOperator, eigs

    keep, lat = sysm["whirl_dofs"]
    K, Mm, C = (sysm[k][np.ix_(keep, keep)] for k in ("K", "M", "C"))
    n = K.shape[0]
    dK, dC = (A[np.ix_(keep, keep)] for A in speed_support_delta(model, w, sysm["K"].shape[0]))
    K = K + dK
    D = C + dC + w * (sysm["G_pt"] + speed_ratio(model) * sysm["G_gg"])[np.ix_(keep, keep)]
    sigma = 1j * target
    lu = sla.lu_factor(K + sigma * D + sigma ** 2 * Mm)
    E = D + sigma * Mm

    def solve(b):
        # (A - sigma) [x1; x2] = [b1; b2] for A = [[0, I], [-M^-1 K, -M^-1 D]], multiplied through by M
        b1, b2 = b[:n], b[n:]
        x1 = sla.lu_solve(lu, -(Mm @ b2) - E @ b1)
        return np.concatenate([x1, b1 + sigma * x1])

    op = LinearOperator((2 * n, 2 * n), matvec=solve, dtype=complex)
    k = min(NEAR_MODES, 2 * n - 2)
    # nu = 1 / (lambda - sigma); a search that has not converged in MAX_ITER restarts is handed to the full solve
    nu, vec = eigs(op, k=k, which="LM", v0=np.ones(2 * n, complex), maxiter=MAX_ITER)
    return _whirl_modes(sigma + 1.0 / nu, vec[:n], Mm, lat, min_share)


def _whirl_modes(lam, vec, Mm, lat, min_share: float) -> list:
    """(eigenvalue, "forward" | "backward") of the eigenpairs (``vec``: the displacement part, one column each)
    with Im lambda > 0 that are rotor whirl modes: lateral rotor share of the kinetic energy at least
    ``min_share``, the whirl from the rotor nodes' orbit (the module docstring)."""
    Mlat = Mm[np.ix_(lat, lat)]
    out = []
    for k in np.nonzero(lam.imag > 1e-6)[0]:
        v = vec[:, k]
        share = np.real(v[lat].conj() @ Mlat @ v[lat]) / np.real(v.conj() @ Mm @ v)
        if share < min_share:
            continue
        X, Y = v[lat[0::2]], v[lat[1::2]]
        forward = np.sum(np.abs(X + 1j * Y) ** 2) >= np.sum(np.abs(X - 1j * Y) ** 2)
        out.append((lam[k], "forward" if forward else "backward"))
    return out


def _whirl_dofs(sysm: dict, model: FullModel) -> tuple[np.ndarray, np.ndarray]:
    """The DOFs coupled to the rotor's lateral ones (by M, K, C, G or a support at any speed) and, among them,
    the positions of the rotor's lateral DOFs: the beams' axial and torsional DOFs drop out (uncoupled from
    whirl), a casing's shell stays."""
    pattern = sum(np.abs(sysm[k]) for k in ("M", "K", "C", "G_pt", "G_gg")) != 0
    for t in model.info.get("speed_supports", []):
        d = [i for i in t["dofs"] if i is not None]
        pattern[np.ix_(d, d)] = True
    reach = np.zeros(pattern.shape[0], bool)
    reach[sysm["rotor_lateral"]] = True
    while True:
        grown = reach | pattern[reach].any(axis=0)
        if grown.sum() == reach.sum():
            break
        reach = grown
    keep = np.nonzero(reach)[0]
    pos = np.searchsorted(keep, sysm["rotor_lateral"])
    return keep, pos


def _damped_modes(sysm: dict, model: FullModel, w: float, min_share: float):
    """Eigenvalues (Im > 0, ascending in Im, as ROSS sorts them) and whirl of the rotor whirl modes of the damped
    engine at the first spool's speed w [rad/s], the speed-dependent supports' coefficients at w:
    lambda [I 0; 0 M] x = [0 I; -K(w) -(C(w) + w G~)] x."""
    keep, lat = sysm["whirl_dofs"]
    K, Mm, C = (sysm[k][np.ix_(keep, keep)] for k in ("K", "M", "C"))
    n = K.shape[0]
    dK, dC = (A[np.ix_(keep, keep)] for A in speed_support_delta(model, w, sysm["K"].shape[0]))
    Gt = (sysm["G_pt"] + speed_ratio(model) * sysm["G_gg"])[np.ix_(keep, keep)]
    D = C + dC + w * Gt
    try:                 # M positive definite: the standard eigenproblem of M^-1 [K D], ~5 x faster than QZ
        cf = sla.cho_factor(Mm)
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-sla.cho_solve(cf, K + dK), -sla.cho_solve(cf, D)]])
        lam, vec = sla.eig(A)
    except np.linalg.LinAlgError:          # a massless hub: the generalized problem
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-(K + dK), -D]])
        B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), Mm]])
        lam, vec = sla.eig(A, B)
    out = _whirl_modes(lam, vec[:n], Mm, lat, min_share)
    out.sort(key=lambda t: (t[0].imag, abs(t[0])))
    return out


def speed_dependent_critical_speeds(model: FullModel, supports: dict | None, max_rpm: float, excited: float = 1.0,
                                    min_share: float = 0.05, natural: str = "wn", rtol: float = 1e-10) -> list[dict]:
    """Critical speeds of an engine whose supports have coefficients over speed or cross-coupled ones (ROSS's
    bearing and seal tables), as ROSS's ``run_critical_speed`` defines them: the speeds w at which a natural
    frequency of the damped engine, its supports' coefficients taken at w, equals w. For the mode of rank i
    (ascending damped frequency Im lambda among the rotor whirl modes) the fixed point
    w = |lambda_i(w)| (``natural`` "wn") or w = Im lambda_i(w) ("wd"), solved by secant iterations from the
    non-spinning frequency, as ROSS does (scipy's newton). ``excited``: the exciting spool's speed over the
    first spool's (the fixed point in its speed). Ascending ``[{"rpm", "whirl", "damping_ratio"}]`` up to
    ``max_rpm`` (rev/min of the exciting spool)."""
    from scipy.optimize import newton

    sysm = _system(model, supports)
    if "C" not in sysm:
        sysm = {**sysm, "C": model.C}
    sysm["whirl_dofs"] = _whirl_dofs(sysm, model)
    cache: dict = {}

    def modes(w):
        key = float(w)
        if key not in cache:
            cache[key] = _damped_modes(sysm, model, key / excited, min_share)
        return cache[key]

    def freq(lam):
        return abs(lam) if natural == "wn" else lam.imag

    start = modes(0.0)
    top = max_rpm * RPM
    out = []
    for i, (lam0, _) in enumerate(start):
        if freq(lam0) > 2.0 * top:
            break

        def f(w, i=i):
            m = modes(w)
            return w - freq(m[i][0]) if i < len(m) else w

        try:
            w = float(newton(f, freq(lam0), rtol=rtol, maxiter=100))
        except RuntimeError:
            continue           # no fixed point for this rank (a mode that leaves the whirl modes' list)
        m = modes(w)
        if i >= len(m) or not 0.0 < w <= top:
            continue
        lam, whirl = m[i]
        out.append({"rpm": w / RPM, "whirl": whirl, "damping_ratio": damping_ratio(lam, sysm, model, w / excited)})
    return sorted(out, key=lambda r: r["rpm"])
