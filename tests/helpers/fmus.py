"""Builders shared by the FMI-boundary tests (not tests themselves)."""
from __future__ import annotations

import re
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np

from rotorcosim import scenarios
from rotorcosim.master.observer.observer import Observer
from rotorcosim.master.scenario.build import build_simulation, load_scenario
from rotorcosim.master.schedule import Interval, Timeline

TOY = Path(scenarios.__file__).with_name("toy_thermomechanical.toml")


def export_toy(dest: Path) -> dict[str, Path]:
    from rotorcosim.master.scenario.export import export_scenario

    return export_scenario(load_scenario(TOY), dest)


class Capture(Observer):
    """Every output of every component at every base step: the full trajectory of a run."""

    def __init__(self):
        self.t: list[float] = []
        self.rows: list[dict[str, np.ndarray]] = []

    def step(self, sim, t):
        self.t.append(t)
        self.rows.append({f"{n}.{k}": np.array(v, dtype=float) for n, c in sim.system.components.items()
                          for k, v in c.y.items()})

    def series(self, ref: str) -> np.ndarray:
        return np.array([r[ref] for r in self.rows])


def run_intervals(sc, intervals: list[tuple[str, float, float]]) -> Capture:
    """Run scenario ``sc`` through the given (phase, duration, step) intervals, capturing every output."""
    cap = Capture()
    sim = build_simulation(sc, [cap])
    try:
        sim.run(Timeline([Interval(p, d, h) for p, d, h in intervals]))
    finally:
        for c in sim.system.components.values():
            c.terminate()
    return cap


def max_rel_diff(a: Capture, b: Capture, refs) -> float:
    """Largest |a - b| / max(|a|, |b|, tiny) over all captured outputs ``refs`` and times (same length runs)."""
    assert len(a.rows) == len(b.rows) and a.rows, "the two runs took different numbers of steps"
    worst = 0.0
    for ref in refs:
        x, y = a.series(ref), b.series(ref)
        scale = np.maximum(np.max(np.abs(x)), np.max(np.abs(y)))
        if scale == 0:
            continue
        worst = max(worst, float(np.max(np.abs(x - y)) / scale))
    return worst


MODELS = Path(__file__).resolve().parents[1] / "fmus" / "models"


def build_python_fmu(model: str, dest: Path, fmi3: bool) -> Path:
    """Build ``models/<model>.py`` into ``dest/<model>.fmu`` with pythonfmu (FMI 2.0) or pythonfmu3 (FMI 3.0)."""
    dest.mkdir(parents=True, exist_ok=True)
    tool = "pythonfmu3" if fmi3 else "pythonfmu"
    out = subprocess.run([sys.executable, "-m", tool, "build", "-f", str(MODELS / f"{model}.py"), "-d", str(dest)],
                         cwd=dest, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    return dest / f"{model}.fmu"


def model_description(fmu: Path) -> str:
    with zipfile.ZipFile(fmu) as zf:
        return zf.read("modelDescription.xml").decode()


def with_model_description(src: Path, dst: Path, xml: str) -> Path:
    """A copy of the FMU ``src`` at ``dst`` whose modelDescription.xml is ``xml`` (the binary is unchanged)."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for info in zin.infolist():
            data = xml.encode() if info.filename == "modelDescription.xml" else zin.read(info)
            zout.writestr(info, data)
    return dst


def rebuild(src: Path, dst: Path, edit=None, extra=()) -> Path:
    """Copy the zip ``src`` (an FMU or SSP archive) to ``dst``; ``edit(name, data) -> data | None`` changes or
    drops entries, ``extra`` is ``(name, data)`` pairs added at the end."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for info in zin.infolist():
            data = zin.read(info)
            if edit is not None:
                data = edit(info.filename, data)
            if data is not None:
                zout.writestr(info.filename, data)
        for name, data in extra:
            zout.writestr(name, data)
    return dst


def set_attributes(xml: str, name: str, tag: str, attrs: str, new_tag: str | None = None) -> str:
    """Add ``attrs`` (text) to the type element ``tag`` of the FMI 2.0 variable ``name`` (optionally renaming
    the element), or to the FMI 3.0 variable element ``tag name="..."``."""
    fmi2 = re.compile(rf'(<ScalarVariable name="{re.escape(name)}"[^>]*>\s*)<{tag}([ />])')
    if fmi2.search(xml):
        return fmi2.sub(lambda m: f"{m[1]}<{new_tag or tag} {attrs}{m[2]}", xml, count=1)
    fmi3 = re.compile(rf'<{tag} name="{re.escape(name)}"')
    assert fmi3.search(xml), f"no variable {name} in the model description"
    return fmi3.sub(f'<{new_tag or tag} name="{name}" {attrs}', xml, count=1)


class CaptureAll(Observer):
    """Every output of every component at every base step, the first sample (after initialisation) included."""

    def __init__(self):
        self.t: list[float] = []
        self.rows: list[dict[str, np.ndarray]] = []

    def start(self, sim, schedule):
        self.step(sim, sim.t)

    def step(self, sim, t):
        self.t.append(t)
        self.rows.append({f"{n}.{k}": np.array(v) for n, c in sim.system.components.items() for k, v in c.y.items()})

    def series(self, ref: str) -> np.ndarray:
        return np.array([r[ref] for r in self.rows])
