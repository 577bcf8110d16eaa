"""The scenario files shipped with rotorcosim (TOML); installed as package data so `rotorcosim run` finds them."""
import re
from pathlib import Path

FOLDER = Path(__file__).parent
#: the scenario ``rotorcosim run`` and ``load_scenario()`` run when none is named: the shipped case's main job
DEFAULT = "blade_loss_2850"


def natural_key(name: str) -> list:
    """Sort key reading the digits of ``name`` as numbers: blade_loss_1425 before blade_loss_11401.

    >>> sorted(["blade_loss_11401", "blade_loss_1425", "blade_loss"], key=natural_key)
    ['blade_loss', 'blade_loss_1425', 'blade_loss_11401']
    """
    return [(0, int(part), "") if part.isdigit() else (1, 0, part) for part in re.split(r"(\d+)", name) if part]


def names() -> list[str]:
    """The shipped scenarios' names (the file names without .toml), in natural order (:func:`natural_key`)."""
    return sorted((p.stem for p in FOLDER.glob("*.toml")), key=natural_key)


def path(name: str) -> Path:
    """The shipped scenario ``name`` (with or without .toml)."""
    p = FOLDER / (name if name.endswith(".toml") else name + ".toml")
    if not p.is_file():
        known = ", ".join(names())
        raise FileNotFoundError(f"no shipped scenario {name!r}; shipped: {known}")
    return p
