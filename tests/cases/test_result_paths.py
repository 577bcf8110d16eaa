"""A case's declared results (``result_paths``, which a study's SPEC is checked against before its first run) are
exactly the numbers its runs report: every number of a short run's summary below the case's keys is declared,
and every declared path is in the summary (a list, declared by a path ending in a dot, may hold anything)."""
from __future__ import annotations

import pytest

import rotorcosim
from rotorcosim.master import case as cases
from rotorcosim.master.study import declared


def leaves(node, prefix=""):
    """Every dotted path to a value of ``node`` that is not a table."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield from leaves(v, f"{prefix}{k}.")
    else:
        yield prefix[:-1]


@pytest.mark.parametrize("name, duration", [("blade_loss_2850", 0.02), ("jeffcott_rundown", 0.05)])
def test_declared_results_are_the_reported_ones(name, duration):
    sc = rotorcosim.load_scenario(name)
    summary = rotorcosim.simulate(sc, duration=duration, record=[], figures=False).summary
    kind = sc.extra["results"]["kind"]
    paths = cases.results_of(kind).result_paths(sc)
    exact = {p for p in paths if not p.endswith(".")}
    lists = tuple(p for p in paths if p.endswith("."))
    tops = {p.split(".")[0] for p in paths}
    reported = {p for top in tops if top in summary for p in leaves({top: summary[top]})}
    undeclared = sorted(p for p in reported if p not in exact and not p.startswith(lists) and p + "." not in lists)
    assert not undeclared, f"{name}: reported but not declared by {kind}.result_paths: {undeclared}"
    missing = sorted(p for p in exact if p not in reported)
    assert not missing, f"{name}: declared but not reported: {missing}"
    assert not declared.unknown(sc, sorted(exact))   # and the study's check takes every one of them
