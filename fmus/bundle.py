"""Copy a component's code into an FMU's resources under a private package name.

An exported FMU must run without an installed rotorcosim (only the third-party packages its code imports), and
two FMUs loaded in one Python process must not see each other's code. So the sources of ``components/`` that
the component needs are copied under a package name private to the FMU (``_rcs_<id>_<hash>``):
``__init__``, ``contract``, ``value_types``, ``registry``, the component's own sub-package (with its data files) and, found by
reading the imports, every sibling sub-package it uses. Absolute imports of ``rotorcosim.components`` are
rewritten to the private name; an import of another part of rotorcosim (master, fmus) cannot be bundled and
is a clear error naming the file and line.
"""
from __future__ import annotations

import ast
import hashlib
import re
import shutil
from pathlib import Path

import rotorcosim.components as _components_pkg

COMPONENTS_ROOT = Path(_components_pkg.__file__).resolve().parent
COMPONENTS_PACKAGE = "rotorcosim.components"
#: modules of components/ every bundle carries (the contract the component subclasses)
CORE = ("__init__.py", "contract.py", "value_types.py", "registry.py", "cache.py")
_SKIP_DIRS = {"__pycache__"}
_SKIP_SUFFIXES = {".pyc", ".pyo", ".nbi", ".nbc"}


class BundleError(ValueError):
    """A component whose code cannot be bundled into an FMU."""


def component_location(cls: type) -> tuple[str, str]:
    """``(module path inside components/, class name)``, e.g. ``("damper.component", "FastDamper")``."""
    module = cls.__module__
    if not module.startswith(COMPONENTS_PACKAGE + "."):
        raise BundleError(f"component class {cls.__qualname__} lives in module {module!r}, outside "
                          f"{COMPONENTS_PACKAGE}: only rotorcosim's own components can be bundled into an FMU")
    return module[len(COMPONENTS_PACKAGE) + 1:], cls.__qualname__


def _files(folder: Path) -> list[Path]:
    return sorted(p for p in folder.rglob("*") if p.is_file()
                  and not (set(p.relative_to(folder).parts) & _SKIP_DIRS) and p.suffix not in _SKIP_SUFFIXES)


def _subpackage_of(parts: list[str]) -> str | None:
    """The sub-package of components/ named by the first element of ``parts``, if it is one, or a module of
    components/ itself (``kernels``, ``speeds``: returned as ``name.py``)."""
    if parts and (COMPONENTS_ROOT / parts[0] / "__init__.py").is_file():
        return parts[0]
    if parts and (COMPONENTS_ROOT / f"{parts[0]}.py").is_file():
        return f"{parts[0]}.py"
    return None


def _imports(path: Path) -> tuple[set[str], list[tuple[int, str]]]:
    """Sibling sub-packages ``path`` imports, and its imports of rotorcosim outside components (line, name)."""
    rel = path.relative_to(COMPONENTS_ROOT)
    package_parts = list(rel.parts[:-1])          # the package the module is in, relative to components/
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    subs, foreign = set(), []
    for node in ast.walk(tree):
        targets = []
        if isinstance(node, ast.ImportFrom):
            if node.level:
                up = node.level - 1
                if up > len(package_parts):
                    foreign.append((node.lineno, "." * node.level + (node.module or "")))
                    continue
                base = package_parts[:len(package_parts) - up]
                mod = base + (node.module.split(".") if node.module else [])
                targets = [mod] if node.module else [base + [a.name] for a in node.names]
            elif node.module:
                targets = [None if not node.module.startswith("rotorcosim") else node.module.split(".")]
        elif isinstance(node, ast.Import):
            targets = [a.name.split(".") if a.name.startswith("rotorcosim") else None for a in node.names]
        for t in targets:
            if t is None:
                continue
            if t[:1] == ["rotorcosim"]:
                if t[:2] != ["rotorcosim", "components"]:
                    foreign.append((node.lineno, ".".join(t)))
                    continue
                t = t[2:]
            sub = _subpackage_of(t)
            if sub:
                subs.add(sub)
    return subs, foreign


#: modules of components/ that read another sub-package's data files (not seen in their imports)
DATA_DEPENDENCIES = {"speeds.py": ("rotor",)}   # speeds.py reads rotor/data/engine.toml


def _sources(sub: str) -> list[Path]:
    """The files of a sub-package, or the one file of a module of components/ (``name.py``)."""
    return [COMPONENTS_ROOT / sub] if sub.endswith(".py") else _files(COMPONENTS_ROOT / sub)


def needed_subpackages(kind: str) -> list[str]:
    """``kind`` plus every sibling sub-package reachable through its imports, sorted."""
    todo, seen = [kind], set()
    while todo:
        sub = todo.pop()
        if sub in seen:
            continue
        seen.add(sub)
        todo.extend(d for d in DATA_DEPENDENCIES.get(sub, ()) if d not in seen)
        for f in _sources(sub):
            if f.suffix == ".py":
                subs, foreign = _imports(f)
                if foreign:
                    line, name = foreign[0]
                    raise BundleError(f"{f}:{line} imports {name!r}, outside {COMPONENTS_PACKAGE}: "
                                      "a component bundled into an FMU may only import components/ code")
                todo.extend(subs - seen)
    for f in CORE:
        _, foreign = _imports(COMPONENTS_ROOT / f)
        if foreign:
            raise BundleError(f"components/{f}:{foreign[0][0]} imports {foreign[0][1]!r}: cannot be bundled")
    return sorted(seen)


def bundle_files(module_path: str) -> list[tuple[str, Path]]:
    """``(relative path, source)`` of every file to bundle for a component in ``components/<module_path>``."""
    first = module_path.split(".")[0]
    out = [(f, COMPONENTS_ROOT / f) for f in CORE]
    if (COMPONENTS_ROOT / first).is_dir():
        for sub in needed_subpackages(first):
            out += [(f.relative_to(COMPONENTS_ROOT).as_posix(), f) for f in _sources(sub)
                    if f.relative_to(COMPONENTS_ROOT).as_posix() not in CORE]
    elif not (COMPONENTS_ROOT / f"{first}.py").is_file():
        raise BundleError(f"cannot find the source of components/{module_path}")
    else:
        out.append((f"{first}.py", COMPONENTS_ROOT / f"{first}.py"))
    return out


def digest(files: list[tuple[str, Path]]) -> str:
    h = hashlib.sha256()
    for rel, src in files:
        h.update(rel.encode())
        h.update(b"\0")
        h.update(src.read_bytes())
        h.update(b"\0")
    return h.hexdigest()


_ABS_IMPORT = re.compile(r"\brotorcosim\.components\b")


def write_bundle(files: list[tuple[str, Path]], dest: Path, package: str) -> Path:
    """Copy ``files`` under ``dest/package``, rewriting absolute component imports to ``package``."""
    root = dest / package
    for rel, src in files:
        target = root / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        if src.suffix == ".py":
            target.write_text(_ABS_IMPORT.sub(package, src.read_text(encoding="utf-8")), encoding="utf-8")
        else:
            shutil.copyfile(src, target)
    return root
