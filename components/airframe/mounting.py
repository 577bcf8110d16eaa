"""An engine file's mounts on its airframe: the mounts and the reduced model read and checked together, and the
rows that tie each mount spring to the airframe's modes (the airframe component's and the installed engine's)."""
from __future__ import annotations

import numpy as np

from ..rotor.model import DEFAULT_FILE, load_data
from ..rotor.mounts import AXES, airframe_model, mounts
from .modal import ModalModel, read


def installed(model_file: str) -> tuple[dict, ModalModel | None]:
    """The mounts and the airframe model of an engine file (none: ``({}, None)``); a bad table, a missing file or
    a mount on an interface point the model lacks is a ValueError naming it."""
    data, _ = load_data(model_file or None)
    found = mounts(data)
    path = airframe_model(data, model_file or DEFAULT_FILE)
    if path is None:
        return found, None
    model = read(path)
    for m in found.values():
        if m.interface not in model.interface:
            raise ValueError(f"[mount.{m.name}] interface: {m.interface!r} is not an interface point of the "
                             f"airframe model {path} (its points: {', '.join(model.interface)})")
        width = model.interface[m.interface].shape[1]
        for i, s in enumerate(m.springs):
            if s.dir >= width:
                raise ValueError(f"[mount.{m.name}] springs[{i}].dir: {s.dir} ({AXES[s.dir]}) but the airframe "
                                 f"model's point {m.interface!r} has translations only")
            if s.offset is not None and width < 6:
                raise ValueError(f"[mount.{m.name}] springs[{i}].offset_mm: the spring ends off the point, but the "
                                 f"airframe model's point {m.interface!r} has translations only (its rotations "
                                 "carry the offset)")
    return found, model


def offset_row(shape: np.ndarray, d: int, r) -> np.ndarray:
    """The motion along axis d (0-2) of a point r [m] rigidly tied to an interface point of mass-normalised
    ``shape`` (modes x 6), per modal coordinate: e_d . (u + theta x r) = shape[:, d] + (r x e_d) . theta."""
    return shape[:, d] + shape[:, 3:6] @ np.cross(r, np.eye(3)[d])


def spring_rows(found: dict, model: ModalModel) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
    """(the mount of each spring, B: springs x modes, k, c) of the mounts ``found`` on ``model`` (kernel.py)."""
    names, rows, k, c = [], [], [], []
    for m in found.values():
        phi = model.interface[m.interface]
        for s in m.springs:
            names.append(m.name)
            rows.append(phi[:, s.dir] if s.offset is None else offset_row(phi, s.dir, s.offset))
            k.append(s.k)
            c.append(s.c)
    return names, np.vstack(rows), np.asarray(k), np.asarray(c)
