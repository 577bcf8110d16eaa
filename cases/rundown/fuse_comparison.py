"""A run with a support fuse beside the same scenario without it: ``casing_force_peak_N`` and ``fuse_comparison``
of ``summary.json``.

``[results] casing_force_peak = true`` records, per co-simulated bearing id, the largest force into the casing
hub under it over the run's coupled steps (:class:`CasingForce`): with a fuse at that bearing (a ``fuse<ID>``
component) the force the fuse carries, ``fuse<ID>.F_support``; else the damper's and the rub ring's reactions on
the hub, ``damper<ID>.F_housing`` + ``rubring<ID>.F_housing`` (those present).

``[results] without_fuse`` (a scenario: a shipped name or a path) with ``without_fuse_set`` (parameter values
set on it, ``{ "rotor.F_unbalance" = 14252.0 }``) names the comparison: after the run, that scenario runs over the
same duration (no files, no figures, its casing force recorded too) and ``fuse_comparison`` holds

* ``without_fuse_scenario``, ``duration_s``;
* ``settings_carried``: what was set on this run (``--set``, ``--unbalance``) and set on the comparison too, so
  that both runs differ by the fuse alone; ``settings_not_carried``: those of components the comparison lacks
  (the fuse's own);
* ``bearings`` -> bearing id -> per quantity ``{"with_fuse": ..., "without_fuse": ...}``: ``casing_force_peak_N``,
  ``max_contact_load_peak_N``, ``max_contact_stress_peak_MPa`` and ``rub_power_peak_W`` (the blade-loss results
  of that name);
* ``crossings`` -> ``with_fuse`` / ``without_fuse``: each run's crossings as ``critical_speed_rpm``,
  ``peak_speed_rpm``, ``configuration`` (a run with a break) and ``peak_whirl_mm`` per bearing id.
"""
from __future__ import annotations

import numpy as np

from rotorcosim.components.contract import COUPLED, ContractError
from rotorcosim.master.observer.observer import Observer
from rotorcosim.master.scenario.overrides import edited_values

#: the blade-loss results compared, per bearing id
RESULTS = ("max_contact_load_peak_N", "max_contact_stress_peak_MPa", "rub_power_peak_W")


def settings(v) -> str | None:
    """The checker of ``[results] without_fuse_set``: a table of parameter names and numbers."""
    if not isinstance(v, dict) or not all(isinstance(k, str) and "." in k and isinstance(x, (int, float))
                                          and not isinstance(x, bool) for k, x in v.items()):
        return f"must be a table of \"component.parameter\" = number, got {v!r}"
    return None


class CasingForce(Observer):
    """The largest force into the casing hub under each co-simulated bearing over the coupled steps (module
    docstring)."""

    def start(self, sim, schedule):
        comps = sim.system.components
        ids = [n[len("bearing"):] for n in comps if n.startswith("bearing") and f"damper{n[7:]}" in comps]
        self.refs = {}
        for b in ids:
            if f"fuse{b}" in comps:
                self.refs[b] = [f"fuse{b}.F_support"]
            else:
                self.refs[b] = [r for r in (f"damper{b}.F_housing", f"rubring{b}.F_housing")
                                if r.split(".")[0] in comps]
        self.peak = {b: 0.0 for b in self.refs}

    def interval_start(self, sim, phase, step):
        self.active = phase == COUPLED

    def block_signals(self, sim):
        return [r for refs in self.refs.values() for r in refs]

    def _take(self, value, n) -> None:
        for b, refs in self.refs.items():
            f = sum(np.asarray(value(r), dtype=float).reshape(n, -1)[:, :2] for r in refs)
            self.peak[b] = max(self.peak[b], float(np.max(np.hypot(f[:, 0], f[:, 1]))))

    def step_block(self, sim, ks, ts, data):
        if getattr(self, "active", False) and len(ts) and self.refs:
            self._take(lambda r: data[r], len(ts))

    def step(self, sim, t):
        if getattr(self, "active", False) and self.refs:
            self._take(lambda r: np.asarray(sim.value(r))[None, :], 1)


def observers(sc) -> list:
    """[CasingForce()] for a scenario that asks for it (or names a comparison), else []."""
    res = sc.extra.get("results", {})
    return [CasingForce()] if res.get("casing_force_peak") or res.get("without_fuse") else []


def _crossings(summary: dict) -> list[dict]:
    out = []
    for c in summary.get("crossings", []):
        if not c.get("peak_found"):
            continue
        e = {"critical_speed_rpm": c["critical_speed_rpm"], "peak_speed_rpm": c["peak_speed_rpm"],
             "peak_whirl_mm": {b: v.get("peak_whirl_mm") for b, v in c.get("bearings", {}).items()}}
        if "configuration" in c:
            e["configuration"] = c["configuration"]
        out.append(e)
    return out


def comparison_scenario(sc):
    """The scenario ``[results] without_fuse`` names, with ``without_fuse_set`` set on it, then what was set on
    ``sc`` itself (``--set``, ``--unbalance``, ``Scenario.set``: overrides.edited_values) where the comparison
    has that component; a one-line ValueError naming the key when it cannot be loaded or set. Returns ``(scenario, {"component.parameter": value} carried over,
    [names the comparison lacks the component of])``. :func:`check` calls it before the run: the comparison runs
    it only after the run, which a wrong name would otherwise fail at its end."""
    from rotorcosim.master.api import load_scenario

    res = sc.extra.get("results", {})
    try:
        plain = load_scenario(res["without_fuse"])
    except (ContractError, ValueError, OSError) as exc:
        raise ValueError(f"[results] without_fuse: {exc}") from None
    if res.get("without_fuse_set"):
        try:
            plain = plain.set(dict(res["without_fuse_set"]))
        except (ContractError, ValueError, OSError) as exc:
            raise ValueError(f"[results] without_fuse_set: {exc}") from None
    carried, lacking = {}, []
    # a release moved, another unbalance: the comparison differs from the run by the fuse alone
    for ref, value in edited_values(sc).items():
        if ref.partition(".")[0] not in plain.components:   # the fuse's own parameters
            lacking.append(ref)
            continue
        try:
            plain = plain.set({ref: value})
        except (ContractError, ValueError, OSError) as exc:
            raise ValueError(f"[results] without_fuse: the run's setting {ref} = {value!r} does not apply to "
                             f"{res['without_fuse']}: {exc}") from None
        carried[ref] = value
    return plain, carried, lacking


def check(sc) -> None:
    """``[results] without_fuse`` and ``without_fuse_set`` name a scenario and values it takes
    (:func:`comparison_scenario`); ``without_fuse_set`` without ``without_fuse`` is refused (nothing would use it)."""
    res = sc.extra.get("results", {})
    if res.get("without_fuse"):
        comparison_scenario(sc)
    elif res.get("without_fuse_set"):
        raise ValueError("[results] without_fuse_set: given without [results] without_fuse (the scenario it sets)")


def compare(sc, duration: float, fused: dict) -> dict:
    """``fuse_comparison`` (module docstring) of the run of ``sc`` over ``duration`` [s] whose summary entries are
    ``fused`` (``bearings``, ``crossings``, ``casing_force_peak_N``): runs the comparison scenario."""
    from rotorcosim.master.api import simulate

    res = sc.extra["results"]
    plain, carried, lacking = comparison_scenario(sc)
    plain.extra.setdefault("results", {})["casing_force_peak"] = True
    other = simulate(plain, duration=duration, figures=False, progress=False).summary
    bearings = {}
    for b in sorted(set(fused.get("bearings", {})) & set(other.get("bearings", {}))):
        row = {"casing_force_peak_N": {"with_fuse": fused.get("casing_force_peak_N", {}).get(b),
                                       "without_fuse": other.get("casing_force_peak_N", {}).get(b)}}
        for k in RESULTS:
            row[k] = {"with_fuse": fused["bearings"][b].get(k), "without_fuse": other["bearings"][b].get(k)}
        bearings[b] = row
    return {"without_fuse_scenario": str(res["without_fuse"]), "duration_s": duration,
            "settings_carried": carried, "settings_not_carried": lacking, "bearings": bearings,
            "crossings": {"with_fuse": _crossings(fused), "without_fuse": _crossings(other)}}
