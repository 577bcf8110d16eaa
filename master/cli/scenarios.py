"""``rotorcosim scenarios``: the shipped scenarios, one line each (name and description), for
``rotorcosim run NAME`` and ``rotorcosim.load_scenario(NAME)``."""
from __future__ import annotations

from rotorcosim import scenarios
from rotorcosim.master.scenario.build import load_scenario


def add_arguments(p):
    """No options."""


def listing() -> list[tuple[str, str]]:
    """(name, description) of each shipped scenario, in natural order (case_9 before
    case_10)."""
    out = []
    for name in scenarios.names():
        sc = load_scenario(scenarios.path(name))
        out.append((name, sc.description or "(no description)"))
    return out


def run(args) -> int:
    """Print the listing; returns 0."""
    rows = listing()
    width = max(len(n) for n, _ in rows)
    for name, text in rows:
        print(f"{name:<{width}}  {text}")
    return 0
