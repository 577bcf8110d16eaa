"""Component implementations chosen by name in a scenario.

Built-in implementations are listed here by dotted import path (imported only when asked for). Third-party
packages add theirs through the entry-point group ``rotorcosim.components``::

    [project.entry-points."rotorcosim.components"]
    "bearing.mine" = "mypackage.bearing:MyBearing"
"""
from __future__ import annotations

import importlib
from importlib import metadata

from .contract import Component, ContractError

ENTRY_POINT_GROUP = "rotorcosim.components"

BUILTIN: dict[str, str] = {
    # test systems of the master (exact solutions known)
    "testing.mass": "rotorcosim.components.testing.mass_spring:Mass",
    "testing.spring": "rotorcosim.components.testing.mass_spring:Spring",
    "testing.damped_oscillator": "rotorcosim.components.testing.thermo_toy:DampedOscillator",
    "testing.thermal_node": "rotorcosim.components.testing.thermo_toy:ThermalNode",
    # the engine
    "rotor.mta": "rotorcosim.components.rotor.component:Rotor",
    "bearing.hertz": "rotorcosim.components.bearing.component:BallBearing",
    "damper.fe": "rotorcosim.components.damper.component:FEDamper",
    "damper.fast": "rotorcosim.components.damper.component:FastDamper",
    "thermal.network": "rotorcosim.components.thermal.component:ThermalNetwork",
    "rubring.contact": "rotorcosim.components.rubring.component:RubRing",
}

_extra: dict[str, type[Component]] = {}


def register(name: str):
    """Class decorator registering an implementation under ``name`` at run time."""

    def deco(cls):
        _extra[name] = cls
        return cls

    return deco


def _entry_points() -> dict[str, object]:
    try:
        eps = metadata.entry_points(group=ENTRY_POINT_GROUP)
    except TypeError:  # Python < 3.10
        eps = metadata.entry_points().get(ENTRY_POINT_GROUP, [])
    return {ep.name: ep for ep in eps}


def available() -> list[str]:
    return sorted(set(BUILTIN) | set(_extra) | set(_entry_points()))


def _load_path(path: str):
    module, _, attr = path.partition(":")
    return getattr(importlib.import_module(module), attr)


def lookup(name: str) -> type[Component]:
    """The class registered under ``name``; a clear error listing the known names otherwise."""
    if name in _extra:
        return _extra[name]
    if name in BUILTIN:
        cls = _load_path(BUILTIN[name])
    else:
        eps = _entry_points()
        if name not in eps:
            raise ContractError(f"unknown component implementation {name!r}; known: {', '.join(available())}")
        cls = eps[name].load()
    if not (isinstance(cls, type) and issubclass(cls, Component)) and not hasattr(cls, "do_step"):
        raise ContractError(f"implementation {name!r} ({cls!r}) does not follow the component contract")
    return cls


def create(name: str, instance_name: str, parameters=None) -> Component:
    return lookup(name)(instance_name, parameters or {})
