"""The Modelica Reference FMUs (FMI 3.0) Feedthrough, StateSpace and Roberts, run with every input unconnected,
equal fmpy's ``simulate_fmu`` sample for sample.

No package of a registry this project installs from ships the Reference FMUs or their sources, and the tests
fetch nothing: set ``ROTORCOSIM_REFERENCE_FMUS`` to a checkout of the modelica/Reference-FMUs repository (built
here with cmake and a C compiler, ``-D FMI_VERSION=3``) or to a folder holding the built FMI 3.0 FMUs (a release
archive unpacked). Without it the test is skipped with that reason; test_unconnected_inputs.py runs models after
the same three, built from this repository's own sources, on every machine with a C compiler.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest

from tests.fmus.test_unconnected_inputs import assert_same_as_fmpy, fmpy_alone, run_alone

ENV = "ROTORCOSIM_REFERENCE_FMUS"
MODELS = ("Feedthrough", "StateSpace", "Roberts")


def _fmi3(fmu: Path) -> bool:
    try:
        with zipfile.ZipFile(fmu) as zf:
            return b'fmiVersion="3.' in zf.read("modelDescription.xml")
    except (zipfile.BadZipFile, KeyError, OSError):
        return False


def _find(folder: Path) -> dict[str, Path]:
    found: dict[str, Path] = {}
    for fmu in sorted(folder.rglob("*.fmu")):
        if fmu.stem in MODELS and fmu.stem not in found and _fmi3(fmu):
            found[fmu.stem] = fmu
    return found


@pytest.fixture(scope="module")
def reference_fmus(tmp_path_factory) -> dict[str, Path]:
    where = os.environ.get(ENV)
    if not where:
        pytest.skip(f"the Modelica Reference FMUs are not on this machine (no registry package ships them): set {ENV} "
                    "to a checkout of modelica/Reference-FMUs (built with cmake and a C compiler) or to a folder of "
                    "the built FMI 3.0 FMUs")
    folder = Path(where)
    if not folder.is_dir():
        pytest.fail(f"{ENV}={where} is not a folder")
    if (folder / "CMakeLists.txt").is_file():
        cmake, cc = shutil.which("cmake"), shutil.which("cc") or shutil.which("gcc")
        if cmake is None or cc is None:
            pytest.skip(f"{ENV} names the Reference FMUs' sources, but cmake and a C compiler are needed to build "
                        f"them (cmake: {cmake or 'absent'}, C compiler: {cc or 'absent'})")
        build = tmp_path_factory.mktemp("reference-fmus")
        for command in ([cmake, "-S", str(folder), "-B", str(build), "-D", "FMI_VERSION=3", "-D", "WITH_FMUSIM=OFF",
                         "-D", "CMAKE_BUILD_TYPE=Release"],
                        [cmake, "--build", str(build), "--parallel", "2"]):
            out = subprocess.run(command, capture_output=True, text=True, timeout=1200)
            assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
        folder = build
    found = _find(folder)
    missing = [m for m in MODELS if m not in found]
    assert not missing, f"no FMI 3.0 {', '.join(missing)}.fmu under {folder}"
    return found


@pytest.mark.parametrize("name", MODELS)
def test_reference_fmu_equals_fmpy_sample_for_sample(reference_fmus, name):
    fmu = reference_fmus[name]
    cap, report = run_alone(fmu)
    assert report.status in ("complete", "stopped")
    assert_same_as_fmpy(cap, fmpy_alone(fmu), 1)
