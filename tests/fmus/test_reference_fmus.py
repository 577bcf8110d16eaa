"""The Modelica Reference FMUs, FMI 2.0 and FMI 3.0 builds, every model with a co-simulation interface, run with
every input unconnected: our master's run equals fmpy's ``simulate_fmu`` sample for sample.

No package of a registry this project installs from ships the Reference FMUs or their sources, and the tests
fetch nothing: set ``ROTORCOSIM_REFERENCE_FMUS`` to a checkout of the modelica/Reference-FMUs repository (built
here into a temporary folder with cmake and a C compiler, once per FMI version; the checkout may be read-only) or
to a folder holding built FMUs (a release archive unpacked: ``2.0/`` and ``3.0/``). .ci/run points it at
``../shared/reference-fmus``. Without it the tests are skipped with that reason; test_unconnected_inputs.py runs
models after Feedthrough, StateSpace and Roberts, built from this repository's own sources, on every machine with
a C compiler.

Each model runs from t = 0 to its DefaultExperiment's stop time (at most 10 s) in steps of 1/64 s (a binary
fraction: fmpy's step is t_{k+1} - t_k, ours the nominal step; they are the same number only when exact).
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import zipfile
from pathlib import Path

import numpy as np
import pytest

from tests.fmus.test_unconnected_inputs import assert_same_as_fmpy, fmpy_alone, run_alone

ENV = "ROTORCOSIM_REFERENCE_FMUS"
#: the models of the Reference FMUs with a co-simulation interface, per FMI version (Clocks has scheduled
#: execution only; Roberts and StateSpace are FMI 3.0 models)
MODELS = {"2": ("BouncingBall", "Dahlquist", "Feedthrough", "Resource", "Stair", "VanDerPol"),
          "3": ("BouncingBall", "Dahlquist", "Feedthrough", "Resource", "Roberts", "Stair", "StateSpace",
                "VanDerPol")}
#: the models whose outputs move with every input left at its start value (the others pass their inputs or
#: a constant through): for these the comparison must not be between two constant series
MOVING = {"BouncingBall", "Dahlquist", "Roberts", "Stair", "VanDerPol"}
H = 1.0 / 64
LONGEST_S = 10.0


def _description(fmu: Path) -> bytes:
    with zipfile.ZipFile(fmu) as zf:
        return zf.read("modelDescription.xml")


def _version(fmu: Path) -> str | None:
    try:
        m = re.search(rb'fmiVersion="(\d)\.', _description(fmu))
    except (zipfile.BadZipFile, KeyError, OSError):
        return None
    return m.group(1).decode() if m else None


def _find(folder: Path, version: str) -> dict[str, Path]:
    found: dict[str, Path] = {}
    for fmu in sorted(folder.rglob("*.fmu")):
        if fmu.stem in MODELS[version] and fmu.stem not in found and _version(fmu) == version:
            found[fmu.stem] = fmu
    return found


def _build(source: Path, version: str, build: Path) -> Path:
    cmake, cc = shutil.which("cmake"), shutil.which("cc") or shutil.which("gcc")
    if cmake is None or cc is None:
        pytest.skip(f"{ENV} names the Reference FMUs' sources, but cmake and a C compiler are needed to build "
                    f"them (cmake: {cmake or 'absent'}, C compiler: {cc or 'absent'})")
    # the sources build with -Werror; GCC 12 at -O2 warns about a strncpy in Resource/model.c that fills its
    # buffer exactly (a warning about the missing terminator of a string that is terminated on the next line)
    for command in ([cmake, "-S", str(source), "-B", str(build), "-D", f"FMI_VERSION={version}",
                     "-D", "WITH_FMUSIM=OFF", "-D", "CMAKE_BUILD_TYPE=Release",
                     "-D", "CMAKE_C_FLAGS=-Wno-error=stringop-truncation"],
                    # the models only: the sources' examples (executables that compile every model again) are
                    # two thirds of the build and run nothing here
                    [cmake, "--build", str(build), "--parallel", "2", "--target", *MODELS[version]]):
        out = subprocess.run(command, capture_output=True, text=True, timeout=1200)
        assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    return build


@pytest.fixture(scope="module")
def reference_fmus(tmp_path_factory):
    """``get(version)``: model name -> built FMU of that FMI version (each version built once)."""
    where = os.environ.get(ENV)
    if not where:
        pytest.skip(f"the Modelica Reference FMUs are not on this machine (no registry package ships them): set {ENV} "
                    "to a checkout of modelica/Reference-FMUs (built with cmake and a C compiler) or to a folder of "
                    "the built FMUs")
    folder = Path(where)
    if not folder.is_dir():
        pytest.fail(f"{ENV}={where} is not a folder")
    built: dict[str, dict[str, Path]] = {}

    def get(version: str) -> dict[str, Path]:
        if version not in built:
            root = folder
            if (folder / "CMakeLists.txt").is_file():
                root = _build(folder, version, tmp_path_factory.mktemp(f"reference-fmus-fmi{version}"))
            found = _find(root, version)
            missing = [m for m in MODELS[version] if m not in found]
            assert not missing, f"no FMI {version}.0 {', '.join(missing)}.fmu under {root}"
            built[version] = found
        return built[version]

    return get


def _stop_time(fmu: Path) -> float:
    m = re.search(rb'<DefaultExperiment[^>]*stopTime="([^"]+)"', _description(fmu))
    return min(float(m.group(1)), LONGEST_S) if m else LONGEST_S


@pytest.mark.parametrize("version, name", [(v, m) for v in MODELS for m in MODELS[v]],
                         ids=[f"fmi{v}-{m}" for v in MODELS for m in MODELS[v]])
def test_reference_fmu_equals_fmpy_sample_for_sample(reference_fmus, version, name):
    fmu = reference_fmus(version)[name]
    duration = _stop_time(fmu)
    cap, report = run_alone(fmu, duration=duration, h=H)
    ref = fmpy_alone(fmu, duration=duration, h=H)
    # Stair asks to terminate at t = 9 s: both runs stop there (the times are compared below)
    assert report.status == ("stopped" if name == "Stair" else "complete"), report.status
    assert_same_as_fmpy(cap, ref, 1)
    if name in MOVING:
        names = [n for n in ref.dtype.names if n != "time"]
        assert any(np.ptp(np.asarray(ref[n], dtype=float)) > 0 for n in names), f"{name}: every output constant"
