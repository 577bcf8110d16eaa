"""The results a run of a scenario reports, known before it runs: a study's SPEC names them, and a name that no run
could give (a misspelt key) is refused before the first run rather than failing every one.

A result is a dotted path into summary.json (:func:`rotorcosim.master.study.targets.lookup`). A run reports

* the master's own figures of every run (:data:`MASTER`) and each component's step count
  (``component_steps.<component>``);
* with a case (``[results] kind``), the paths its results module declares with ``result_paths(sc)``; a path ending
  in a dot stands for anything below it (a list whose length the run decides);
* without a case, ``final_outputs.<component>.<output>`` for every output its implementation declares (and
  ``.<i>``, an element of a vector output); an FMU's outputs are known once it is opened, so anything below
  ``final_outputs.<fmu component>.`` is taken.

A case whose results module declares nothing (a plug-in case without ``result_paths``) is not checked.

>>> from rotorcosim.master.api import load_scenario
>>> sc = load_scenario("toy_thermomechanical")
>>> unknown(sc, ["final_outputs.node.T", "final_outputs.node.Tx", "wall_time_s"])
{'final_outputs.node.Tx': 'final_outputs.node.T'}
"""
from __future__ import annotations

import difflib

from rotorcosim.master import case as cases

#: the numbers every run's summary holds, whatever its case
MASTER = ("duration_s", "t_end_s", "wall_time_s", "cpu_time_s", "peak_memory_MB", "step_cost_us", "estimate.steps",
          "estimate.wall_s", "hold.")


def paths(sc) -> list[str] | None:
    """The results a run of ``sc`` reports (see the module's docstring), or None when its case declares none."""
    out = [*MASTER, *(f"component_steps.{n}" for n in sc.components)]
    kind = sc.extra.get("results", {}).get("kind")
    if kind:
        declare = getattr(cases.results_of(kind), "result_paths", None)
        if declare is None:
            return None
        return out + list(declare(sc))
    from rotorcosim.components import registry

    for name, spec in sc.components.items():
        if spec.fmu is not None or spec.implementation is None:
            out.append(f"final_outputs.{name}.")
            continue
        cls = registry.lookup(spec.implementation, spec.folder)
        out += [f"final_outputs.{name}.{v.name}" for v in getattr(cls, "variables", ()) if v.causality == "output"]
    return out


def _matches(path: str, declared: list[str]) -> bool:
    for d in declared:
        if d.endswith("."):
            if path.startswith(d) and len(path) > len(d):
                return True
        elif path == d or (path.startswith(d + ".") and path[len(d) + 1:].isdigit()):
            return True
    return False


def unknown(sc, results) -> dict[str, str | None]:
    """``{result: the nearest declared one (or None)}`` for each of ``results`` a run of ``sc`` does not report;
    empty when all are reported or the case declares nothing."""
    declared = paths(sc)
    if declared is None:
        return {}
    out = {}
    for r in results:
        if not _matches(r, declared):
            near = difflib.get_close_matches(r, [d.rstrip(".") for d in declared], n=1, cutoff=0.6)
            out[r] = near[0] if near else None
    return out


def refusal(sc, results, where: str) -> str | None:
    """The one-line refusal of the first result of ``results`` a run of ``sc`` does not report, or None."""
    bad = unknown(sc, results)
    if not bad:
        return None
    r, near = next(iter(bad.items()))
    hint = f" (did you mean {near!r}?)" if near else \
        f" (its results: {', '.join(d for d in (paths(sc) or [])[:6])}, ...)"
    more = f"; {len(bad) - 1} more unknown" if len(bad) > 1 else ""
    return f"{where}: result {r!r} is not one a run of scenario {sc.name!r} reports{hint}{more}"
