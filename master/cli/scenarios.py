"""``rotorcosim scenarios``: the shipped scenarios, one line each (name and description), for
``rotorcosim run NAME`` and ``rotorcosim.load_scenario(NAME)``."""
from __future__ import annotations

from rotorcosim import scenarios
from rotorcosim.master.scenario.build import load_scenario


def add_arguments(p):
    pass


def listing() -> list[tuple[str, str]]:
    """(name, description) of each shipped scenario, by name."""
    out = []
    for path in sorted(scenarios.FOLDER.glob("*.toml")):
        sc = load_scenario(path)
        out.append((path.stem, sc.description or "(no description)"))
    return out


def run(args) -> int:
    rows = listing()
    width = max(len(n) for n, _ in rows)
    for name, text in rows:
        print(f"{name:<{width}}  {text}")
    return 0
