"""``rotorcosim new-engine DIR``: a small, valid, commented engine of your own and its blade-loss and rundown
scenarios.

Writes ``DIR/engine.toml`` (a textbook single-spool rotor on two ball bearings with squeeze film dampers on
pedestals, a turbine disk overhung outboard of bearing 0 with the rub ring and the lost blade there, a
compressor disk between the bearings, and what each bearing, damper, rub ring and thermal network is;
docs/reference/engine-format.md), ``DIR/blade_loss.toml`` (the shipped blade-loss system with that engine) and
``DIR/rundown.toml`` (release, fuel cut, rundown, windmilling: the torque law's parameters explained), each of
which runs as it is::

    rotorcosim new-engine my_engine
    rotorcosim check-engine my_engine/engine.toml
    rotorcosim run my_engine/blade_loss.toml --duration 2 --out out
    rotorcosim run my_engine/rundown.toml --duration 20 --out rundown
"""
from __future__ import annotations

from pathlib import Path

#: the templates, package data of this case
TEMPLATES = {"engine.toml": Path(__file__).with_name("data") / "textbook_engine.toml",
             "blade_loss.toml": Path(__file__).with_name("data") / "textbook_blade_loss.toml",
             "rundown.toml": Path(__file__).with_name("data") / "textbook_rundown.toml"}


def new_engine(folder: str | Path) -> list[Path]:
    """Write the template engine and scenario into ``folder`` (created; it must not hold either file yet);
    returns the files written."""
    if not str(folder).strip():
        raise ValueError("new-engine: give the folder to write into (an empty name is the current folder's)")
    d = Path(folder)
    if d.exists() and not d.is_dir():
        raise NotADirectoryError(f"new-engine {folder}: exists and is not a folder")
    there = [name for name in TEMPLATES if (d / name).exists()]
    if there:
        raise FileExistsError(f"new-engine {folder}: {', '.join(there)} already there; choose an empty folder")
    new = [p for p in (d, *d.parents) if not p.exists()]   # the folders this call creates, deepest first
    out = []
    try:
        d.mkdir(parents=True, exist_ok=True)
        for name, src in TEMPLATES.items():
            out.append(d / name)
            (d / name).write_text(src.read_text())
    except OSError as exc:
        # nothing half-written is left: the files and the folders made here go again
        for f in out:
            f.unlink(missing_ok=True)
        for p in new:
            try:
                p.rmdir()
            except OSError:
                pass
        what = f"cannot write {out[-1].name} into it" if out else "the folder cannot be created"
        parent = next((p for p in d.parents if p.exists()), None)
        why = exc.strerror or str(exc)
        if not out and parent is not None:   # /proc/x: "No such file or directory" of a /proc that exists
            why += f" ({parent} does not take a new folder)"
        # the same class: a folder that does not exist stays bad input (exit 2), a permission the environment's
        raise type(exc)(f"new-engine {folder}: {what}: {why}; choose a folder you can write in") from None
    return out


def add_arguments(parser):
    """The options of ``rotorcosim new-engine`` on ``parser``."""
    parser.add_argument("folder", metavar="DIR", help="folder to write engine.toml, blade_loss.toml and rundown.toml "
                                                      "into (created if absent)")


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status."""
    files = new_engine(args.folder)
    print("written: " + ", ".join(str(f) for f in files))
    print(f"next: rotorcosim check-engine {files[0]} && rotorcosim run {files[1]} --duration 2 --out out && "
          f"rotorcosim run {files[2]} --duration 20 --out rundown")
    return 0
