"""The scenario files shipped with rotorcosim (TOML); installed as package data so `rotorcosim run` finds them."""
from pathlib import Path

FOLDER = Path(__file__).parent
#: the scenario ``rotorcosim run`` and ``load_scenario()`` run when none is named: the shipped case's main job
DEFAULT = "blade_loss_2850"


def path(name: str) -> Path:
    """The shipped scenario ``name`` (with or without .toml)."""
    p = FOLDER / (name if name.endswith(".toml") else name + ".toml")
    if not p.is_file():
        known = ", ".join(sorted(q.stem for q in FOLDER.glob("*.toml")))
        raise FileNotFoundError(f"no shipped scenario {name!r}; shipped: {known}")
    return p
