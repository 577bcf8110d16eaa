"""Every public class and function of the master (rotorcosim.master) and of the paper's case
(rotorcosim.cases.blade_loss) carries a docstring; the main public classes also name their parameters and show
a short example."""
from __future__ import annotations

import importlib
import importlib.util
import inspect
import pkgutil

import pytest

import rotorcosim.cases.blade_loss
import rotorcosim.master

PACKAGES = (rotorcosim.master, rotorcosim.cases.blade_loss)

#: the classes a newcomer meets first: their docstring names every parameter of the constructor and shows an example
MAIN_CLASSES = {
    "rotorcosim.master.simulation": "Simulation",
    "rotorcosim.master.core.system": "System",
    "rotorcosim.master.scenario.build": "Scenario",
    "rotorcosim.master.observer.observer": "Observer",
    "rotorcosim.master.api": "Result",
    "rotorcosim.master.schedule.timeline": ("Timeline", "Interval"),
    "rotorcosim.master.core.algorithm": "Engine",
}


def _public_modules() -> list[str]:
    names = []
    for pkg in PACKAGES:
        names.append(pkg.__name__)
        for info in pkgutil.walk_packages(pkg.__path__, pkg.__name__ + "."):
            last = info.name.rsplit(".", 1)[-1]
            if last.startswith("_"):   # private modules and __main__
                continue
            names.append(info.name)
    return names


def _doc(obj) -> str:
    """The docstring of ``obj`` as help() shows it (inherited for methods), without the default ones Python
    writes: a dataclass's signature, an exception's or enumeration's generic text."""
    doc = inspect.getdoc(obj) or ""
    name = getattr(obj, "__name__", "")
    if inspect.isclass(obj):
        own = obj.__dict__.get("__doc__") or ""
        if not own.strip() or own.startswith(f"{name}("):   # none, or the signature a dataclass writes
            return ""
    return doc.strip()


def _members(cls) -> list[tuple[str, object]]:
    """The public methods and properties ``cls`` defines itself."""
    out = []
    for name, value in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(value, (staticmethod, classmethod)):
            value = value.__func__
        if isinstance(value, property) or inspect.isfunction(value):
            out.append((name, getattr(cls, name) if isinstance(value, property) else value))
    return out


def _undocumented() -> list[str]:
    missing = []
    for modname in _public_modules():
        mod = importlib.import_module(modname)
        if not (mod.__doc__ or "").strip():
            missing.append(f"{modname} (module)")
        for name, obj in vars(mod).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != modname:
                continue
            if not (inspect.isclass(obj) or inspect.isfunction(obj)):
                continue
            if not _doc(obj):
                missing.append(f"{modname}.{name}")
            if inspect.isclass(obj):
                for member, value in _members(obj):
                    if isinstance(value, property):
                        doc = (value.__doc__ or "").strip() or _inherited_property_doc(obj, member)
                    else:
                        doc = inspect.getdoc(getattr(obj, member)) or ""
                    if not doc.strip():
                        missing.append(f"{modname}.{name}.{member}")
    return missing


def _inherited_property_doc(cls, member: str) -> str:
    for base in cls.__mro__[1:]:
        value = base.__dict__.get(member)
        if isinstance(value, property) and (value.__doc__ or "").strip():
            return value.__doc__
    return ""


def test_every_public_class_and_function_has_a_docstring():
    missing = _undocumented()
    assert not missing, f"{len(missing)} public names without a docstring:\n" + "\n".join(missing)


def _main_classes():
    for modname, names in MAIN_CLASSES.items():
        for name in (names,) if isinstance(names, str) else names:
            yield pytest.param(modname, name, id=name)


@pytest.mark.parametrize("modname, name", _main_classes())
def test_the_main_classes_name_their_parameters_and_show_an_example(modname, name):
    cls = getattr(importlib.import_module(modname), name)
    doc = " ".join(filter(None, [cls.__doc__, cls.__init__.__doc__ if "__init__" in vars(cls) else None]))
    assert ">>>" in doc, f"{modname}.{name}: no example (>>> lines) in its docstring"
    params = [p for p in inspect.signature(cls).parameters.values()
              if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    unnamed = [p.name for p in params if p.name not in doc]
    assert not unnamed, f"{modname}.{name}: the docstring does not name the parameter(s) {unnamed}"


@pytest.mark.parametrize("modname", [m for m in _public_modules()
                                     if ">>>" in (importlib.util.find_spec(m).loader.get_source(m) or "")])
def test_the_examples_run(modname, tmp_path, monkeypatch):
    """Every example of the docstrings runs as shown (those marked ``+SKIP`` aside: they need a long run)."""
    import doctest
    import tempfile

    # the examples make their folders with tempfile.mkdtemp(), as a reader would: here, inside tmp_path (they
    # were left in /tmp by every run of the suite)
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))

    result = doctest.testmod(importlib.import_module(modname),
                             optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0


def test_this_check_finds_a_missing_docstring(monkeypatch):
    """The walk sees a public function without a docstring (it can fail)."""
    from rotorcosim.master.schedule import budget

    def undocumented_helper():
        pass

    undocumented_helper.__module__ = budget.__name__
    monkeypatch.setattr(budget, "undocumented_helper", undocumented_helper, raising=False)
    assert "rotorcosim.master.schedule.budget.undocumented_helper" in _undocumented()
