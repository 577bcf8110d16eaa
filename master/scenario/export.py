"""A scenario's components as FMI 2.0 co-simulation FMUs (``rotorcosim export-fmus``; :mod:`.ssp` packs them into
an SSP archive). The FMU of one component is :func:`rotorcosim.fmus.export.export_component`'s.
"""
from __future__ import annotations

from pathlib import Path

from rotorcosim.components import registry
from rotorcosim.components.contract import ContractError
from rotorcosim.fmus.export import ExportError, export_component, fmu_entries, write_deterministic_zip


def export_scenario(sc, dest_dir: str | Path, only: str | None = None) -> dict[str, Path]:
    """Export the components of scenario ``sc`` (all, or the one named ``only``) into ``dest_dir`` as
    ``<component>.fmu``, each with the scenario's parameters. A component already given as an FMU is copied.

    Every selected component is checked first (implementation importable, parameters valid), so a scenario
    naming components that do not exist yet fails before anything is written, naming all of them."""
    dest_dir = Path(dest_dir)
    names = list(sc.components)
    if only is not None:
        if only not in sc.components:
            raise ExportError(f"scenario {sc.name!r} has no component {only!r}; its components: {', '.join(names)}")
        names = [only]
    problems = []
    for n in names:
        spec = sc.components[n]
        if spec.fmu is not None:
            if not Path(spec.fmu).is_file():
                problems.append(f"{n} (FMU {spec.fmu} not found)")
            continue
        cls = None
        try:
            cls = registry.lookup(spec.implementation)
            problem = cls(n, dict(spec.parameters)).standalone_problem()
            if problem is not None:
                problems.append(f"{n} ({spec.implementation}: {problem})")
        except ImportError as exc:
            problems.append(f"{n} ({spec.implementation}: its implementation cannot be imported yet: {exc})")
        except (ContractError, TypeError, ValueError) as exc:
            problems.append(f"{n} ({spec.implementation}: {exc})")
        except Exception as exc:
            if cls is None or not registry.is_plugin_class(cls):
                raise
            problems.append(f"{n} ({spec.implementation}: {type(exc).__name__}: {exc})")   # the user's code
    if problems:
        raise ExportError(f"scenario {sc.name!r}: cannot export component(s): " + "; ".join(problems))
    # a name taken by something that is not a file (a folder NAME.fmu) fails before anything is written: it
    # failed after the FMUs before it were, with the rename's bare "[Errno 21] Is a directory: '.NAME.fmu...'"
    taken = [dest_dir / f"{n}.fmu" for n in names
             if (dest_dir / f"{n}.fmu").exists() and not (dest_dir / f"{n}.fmu").is_file()]
    if taken:
        raise ExportError(f"output folder {dest_dir}: {', '.join(str(t) for t in taken)} "
                          f"{'is not a file' if len(taken) == 1 else 'are not files'} (a folder?): remove "
                          f"{'it' if len(taken) == 1 else 'them'} or give another --out")
    try:
        dest_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:  # a file on the path, no permission: one line naming the folder
        raise ExportError(f"output folder {dest_dir}: cannot create the folder ({exc.strerror or exc})") from None
    out = {}
    for n in names:
        spec = sc.components[n]
        target = dest_dir / f"{n}.fmu"
        try:
            if spec.fmu is not None:
                write_deterministic_zip(fmu_entries(Path(spec.fmu)), target)
            else:
                export_component(spec.implementation, target, instance_name=n, parameters=spec.parameters,
                                 model_identifier=n)
        except OSError as exc:   # no space left, no permission: the FMUs of this export are not left half done
            for path in out.values():
                path.unlink(missing_ok=True)
            raise ExportError(f"{target}: cannot write the FMU ({exc.strerror or exc}); nothing of this export "
                              "is left in the folder") from None
        out[n] = target
    return out
