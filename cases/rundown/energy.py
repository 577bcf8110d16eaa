"""The spools' energy balance, from the torques the components report (``summary.json`` ``energy``).

A spool of polar inertia J obeys ``J dOmega/dt = T_drive - T_drag - T_rub - T_aero``; over the run the kinetic
energy it loses equals the work of the torques acting on it:

    0.5 J (Omega_0^2 - Omega_1^2) = W_drag + W_rub + W_aero - W_drive,    W = integral of T Omega dt.

The spool integrates its speed from its torque inputs (components/spool/kernel.py); here each work is integrated
apart from it (over the base steps, coupled and held alike: each torque reported after a step acts over that step
at its mean speed, each power over its step) from what the torque's producer reports:
the bearings' drag torques (``bearing<ID>.T_drag``, their drag model), the rub rings' friction torques
(``rubring<ID>.T_rub``), the spool's aerodynamic and drive torques (``T_aero``, ``T_drive``) and its own viscous
drag ``drag_coefficient Omega``, each times the spool's speed. The residual, the kinetic energy lost less the net
work, is what the coupling (a torque held over a step, a hold's mean over a thermal-only interval) and the spool's
integration lost or created: it is not zero by construction, and a torque the spool integrates otherwise than its
producer reports moves it (tests/cases/test_rundown_energy.py). In a held (thermal-only) interval a frozen
producer's report is what the master hands on for it, the hold's value (the spool's input; a power at its
consumer's input).

Separately, the energy the rub rings and bearings dissipate, the integral of their power outputs (``P_rub``,
``P_drag``): a rub ring's power exceeds its torque's work on the spool by the whirl's share of the sliding speed
(``Omega R + w.t``: the journal's whirl velocity ``w`` along the contact's tangent ``t`` adds to the surface speed
``Omega R``), reported as ``rub_whirl_share_J``.

Per spool: ``inertia_kg_m2``, ``kinetic_energy_lost_J``, ``work_J`` {drive, drag, rub, aero} (the viscous drag in
``drag``), ``residual_J``, ``residual_pct`` (of the energy the torques exchanged, the sum of the works' magnitudes: a
governed spool's drive and drag exchange far more than it loses), ``residual_of_lost_pct`` (of the kinetic energy
lost; None when none was),
``rub_dissipated_J``, ``rub_whirl_share_J`` (None without a rub ring's power), ``drag_dissipated_J`` (the bearings'
``P_drag``; None without one).
"""
from __future__ import annotations

import numpy as np

from rotorcosim.components.contract import HELD
from rotorcosim.components.spool.ports import kind_of
from rotorcosim.master.observer.observer import Observer

#: the power output of a torque's producer that it dissipates, by kind
POWERS = {"drag": "P_drag", "rub": "P_rub"}
KINDS = ("drive", "drag", "rub", "aero")


class SpoolEnergy(Observer):
    """Integrates, per spool, the work of each torque its producers report and their dissipated powers (module
    docstring); :meth:`summary` gives ``summary.json``'s ``energy``."""

    def __init__(self, spools):
        self.spools = list(spools)

    def start(self, sim, schedule):
        comps = sim.system.components
        by_dst = {c.dst: c.src for c in sim.system.connections}
        # per spool: [(kind, source ref or None, constant)], [(kind, power ref)]
        self.torques, self.powers = {}, {}
        for sp in self.spools:
            tq, pw = [], []
            for port in self._torque_ports(comps[sp]):
                kind = kind_of(port)
                ref = f"{sp}.{port}"
                src = by_dst.get(ref)
                if src is None:
                    tq.append((kind, None, float(np.asarray(comps[sp].u[port]).reshape(-1)[0])))
                    continue
                tq.append((kind, src, 0.0))
                comp = src.partition(".")[0]
                if POWERS[kind] in comps[comp].y:
                    pw.append((kind, f"{comp}.{POWERS[kind]}"))
            self.torques[sp], self.powers[sp] = tq, pw
        # in a held interval a frozen producer reports what the master hands on for it (the hold's value): the
        # torque at the spool's input, a power at the input of its first consumer
        self.handed = {ref: dst for dst, ref in reversed(list(by_dst.items()))}
        self.held = False
        self._ports_of = {sp: self._torque_ports(comps[sp]) for sp in self.spools}
        self.J = {sp: float(getattr(comps[sp], "J", np.nan)) for sp in self.spools}
        self.c_visc = {sp: float(comps[sp].p.get("drag_coefficient", 0.0)) for sp in self.spools}
        self.omega0 = {sp: self._omega(sim, sp) for sp in self.spools}
        self.work = {sp: dict.fromkeys(KINDS, 0.0) for sp in self.spools}
        self.dissipated = {sp: {"drag": 0.0, "rub": 0.0} for sp in self.spools}
        self._prev = {sp: self._sample(lambda ref: sim.value(ref), sp) for sp in self.spools}
        self._t = float(sim.t)

    @staticmethod
    def _omega(sim, sp) -> float:
        return float(np.asarray(sim.value(f"{sp}.Omega")).reshape(-1)[0])

    def _sample(self, value, sp, inputs=None) -> np.ndarray:
        """[Omega, torque of each kind in KINDS, dissipated drag power, dissipated rub power] now; ``inputs``: the
        system's components, whose inputs give the held values in a held interval."""
        w = float(np.asarray(value(f"{sp}.Omega")).reshape(-1)[0])
        out = np.zeros(7)
        out[0] = w
        out[1] = float(np.asarray(value(f"{sp}.T_drive")).reshape(-1)[0])
        out[4] = float(np.asarray(value(f"{sp}.T_aero")).reshape(-1)[0])
        out[2] = self.c_visc[sp] * w
        for port, (kind, src, const) in zip(self._ports(sp), self.torques[sp]):
            if src is None:
                out[1 + KINDS.index(kind)] += const
            else:
                v = value(src) if inputs is None else inputs[sp].u[port]
                out[1 + KINDS.index(kind)] += float(np.asarray(v).reshape(-1)[0])
        for kind, ref in self.powers[sp]:
            dst = self.handed.get(ref)
            if inputs is None or dst is None:
                v = value(ref)
            else:
                comp, _, port = dst.partition(".")
                v = inputs[comp].u[port]
            out[5 if kind == "drag" else 6] += float(np.asarray(v).reshape(-1)[0])
        return out

    @staticmethod
    def _torque_ports(comp) -> list[str]:
        """A spool's torque inputs (components/spool/ports.py: its drag torques, then its rub torques)."""
        return [p for p in comp.u if kind_of(p) is not None]

    def _ports(self, sp) -> list[str]:
        """The spool's torque inputs in the order of ``self.torques[sp]``."""
        return self._ports_of[sp]

    def _add(self, sp, prev, rows, dt):
        """The steps ``rows`` (one per step, the values each reports after it; steps ``dt`` long) after ``prev``:
        a torque acts over the step it is reported for, at the step's mean speed (the spool's own rule); a power
        over its step."""
        w = np.concatenate([[prev[0]], rows[:, 0]])
        wm = 0.5 * (w[1:] + w[:-1]) * dt
        for n, kind in enumerate(KINDS, start=1):
            self.work[sp][kind] += float(np.dot(rows[:, n], wm))
        self.dissipated[sp]["drag"] += float(np.dot(rows[:, 5], dt))
        self.dissipated[sp]["rub"] += float(np.dot(rows[:, 6], dt))
        return rows[-1]

    def interval_start(self, sim, phase, step):
        self.held = phase == HELD

    def step(self, sim, t):
        dt = np.array([t - self._t])
        self._t = t
        if not dt[0] > 0.0:
            return
        comps = sim.system.components if self.held else None
        for sp in self.spools:
            row = self._sample(lambda ref: sim.value(ref), sp, comps)
            self._prev[sp] = self._add(sp, self._prev[sp], row[None, :], dt)

    def block_signals(self, sim):
        refs = []
        for sp in self.spools:
            refs += [f"{sp}.Omega", f"{sp}.T_drive", f"{sp}.T_aero"]
            refs += [src for _, src, _ in self.torques[sp] if src is not None]
            refs += [ref for _, ref in self.powers[sp]]
        return list(dict.fromkeys(refs))

    def step_block(self, sim, ks, ts, data):
        ts = np.asarray(ts, dtype=float)
        if not len(ts):
            return
        dt = np.diff(np.concatenate([[self._t], ts]))
        self._t = float(ts[-1])
        n = len(ts)

        def col(ref):
            return np.asarray(data[ref]).reshape(n, -1)[:, 0]

        for sp in self.spools:
            w = col(f"{sp}.Omega")
            rows = np.zeros((n, 7))
            rows[:, 0] = w
            rows[:, 1] = col(f"{sp}.T_drive")
            rows[:, 4] = col(f"{sp}.T_aero")
            rows[:, 2] = self.c_visc[sp] * w
            for kind, src, const in self.torques[sp]:
                rows[:, 1 + KINDS.index(kind)] += const if src is None else col(src)
            for kind, ref in self.powers[sp]:
                rows[:, 5 if kind == "drag" else 6] += col(ref)
            self._prev[sp] = self._add(sp, self._prev[sp], rows, dt)

    def summary(self, sim) -> dict:
        """``energy`` of summary.json (module docstring), per spool."""
        out = {}
        for sp in self.spools:
            J, w0, w1 = self.J[sp], self.omega0[sp], self._omega(sim, sp)
            lost = 0.5 * J * (w0 * w0 - w1 * w1)
            work = dict(self.work[sp])
            residual = lost - (work["drag"] + work["rub"] + work["aero"] - work["drive"])
            exchanged = sum(abs(v) for v in work.values())
            rub = self.dissipated[sp]["rub"] if any(k == "rub" for k, _ in self.powers[sp]) else None
            drag = self.dissipated[sp]["drag"] if any(k == "drag" for k, _ in self.powers[sp]) else None
            out[sp] = {"inertia_kg_m2": J, "kinetic_energy_lost_J": lost, "work_J": work, "residual_J": residual,
                       "residual_pct": 100.0 * residual / exchanged if exchanged else 0.0,
                       "residual_of_lost_pct": 100.0 * residual / lost if lost else None,
                       "rub_dissipated_J": rub, "rub_whirl_share_J": None if rub is None else rub - work["rub"],
                       "drag_dissipated_J": drag}
        return out
