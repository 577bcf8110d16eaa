"""Component implementations chosen by name in a scenario.

Built-in implementations are listed here by dotted import path (imported only when asked for). Third-party
packages add theirs through the entry-point group ``rotorcosim.components``::

    [project.entry-points."rotorcosim.components"]
    "bearing.mine" = "mypackage.bearing:MyBearing"

Without packaging, a scenario names a plug-in class directly as ``"module:Class"``: the module is imported from
the scenario file's folder first, then from ``sys.path`` (docs/how-to/plugins.md).
"""
from __future__ import annotations

import importlib
import sys
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
    # a support that breaks at a load (an event the master locates)
    "fuse.support": "rotorcosim.components.fuse.component:SupportFuse",
    # the airframe on the engine's mounts (a reduced linear model)
    "airframe.modal": "rotorcosim.components.airframe.component:Airframe",
    # speed as a state: the spool, and the speed-following variants of the rotor, bearing, rub ring
    "spool.speed": "rotorcosim.components.spool.component:Spool",
    "rotor.mta_spinning": "rotorcosim.components.rotor.spinning:SpinningRotor",
    "bearing.hertz_spinning": "rotorcosim.components.bearing.spinning:SpinningBearing",
    "rubring.contact_spinning": "rotorcosim.components.rubring.spinning:SpinningRubRing",
    "thermal.network_spinning": "rotorcosim.components.thermal.spinning:SpinningThermalNetwork",
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


def is_plugin_class(cls) -> bool:
    """Whether ``cls`` is a user's component (a ``module:Class`` plug-in or an installed entry point), not one the
    project ships: what it raises is a mistake of the user's code, named with its component as an input error,
    where the project's own exception would be a bug."""
    return str(getattr(cls, "__module__", "")).split(".")[0] != "rotorcosim"


def is_plugin_path(name: str) -> bool:
    """True for an implementation written ``"module:Class"`` (a plug-in imported directly)."""
    module, colon, attr = str(name).partition(":")
    return bool(colon)


def load_plugin(path: str, folder: str | None = None) -> type:
    """The class ``"module:Class"``, its module imported from ``folder`` first, then from ``sys.path``."""
    module, _, attr = path.partition(":")
    if not module or not attr or not all(p.isidentifier() for p in module.split(".")) or not attr.isidentifier():
        raise ContractError(f"plug-in implementation {path!r} must be written 'module:Class'")
    added = folder is not None and folder not in sys.path
    if added:
        sys.path.insert(0, folder)
    try:
        mod = importlib.import_module(module)
    except ModuleNotFoundError as exc:
        if exc.name != module.split(".")[0] and exc.name != module:
            raise ContractError(f"plug-in {path!r}: importing module {module!r} failed: {exc}") from None
        where = f"the folder {folder} nor " if folder else ""
        raise ContractError(f"plug-in {path!r}: no module {module!r} in {where}sys.path") from None
    except Exception as exc:  # a plug-in's own error at import: say whose it is
        raise ContractError(f"plug-in {path!r}: importing module {module!r} failed: "
                            f"{type(exc).__name__}: {exc}") from None
    except SystemExit as exc:  # sys.exit() at import ended the command with the plug-in's status and no word
        raise ContractError(f"plug-in {path!r}: module {module!r} called sys.exit({exc.code!r}) while imported") \
            from None
    finally:
        if added:
            sys.path.remove(folder)
    try:
        return getattr(mod, attr)
    except AttributeError:
        raise ContractError(f"plug-in {path!r}: module {module!r} ({mod.__file__}) has no {attr!r}") from None


def lookup(name: str, folder: str | None = None) -> type[Component]:
    """The class registered under ``name`` (or the plug-in ``"module:Class"``, imported from ``folder`` first);
    a clear error listing the known names otherwise."""
    if is_plugin_path(name):
        cls = load_plugin(name, folder)
    elif name in _extra:
        return _extra[name]
    elif name in BUILTIN:
        cls = _load_path(BUILTIN[name])
    else:
        eps = _entry_points()
        if name not in eps:
            raise ContractError(f"unknown component implementation {name!r}; known: {', '.join(available())}")
        cls = eps[name].load()
    if not (isinstance(cls, type) and (issubclass(cls, Component) or hasattr(cls, "do_step"))):
        raise ContractError(f"implementation {name!r} ({cls!r}) does not follow the component contract "
                            f"(a class derived from rotorcosim.components.contract.Component)")
    return cls


def create(name: str, instance_name: str, parameters=None, folder: str | None = None) -> Component:
    return lookup(name, folder)(instance_name, parameters or {})
