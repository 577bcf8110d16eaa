"""Shared, session-scoped FMU builds: building an FMU with pythonfmu takes about a second, so each is built once."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from fmu_helpers import export_toy  # noqa: E402


@pytest.fixture(scope="session")
def fmu_dir(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("fmus")


@pytest.fixture(scope="session")
def toy_fmus(fmu_dir) -> dict[str, Path]:
    """The toy thermo-mechanical scenario's components (osc, node) as FMUs with its parameters."""
    return export_toy(fmu_dir / "toy")


@pytest.fixture(scope="session")
def mass_fmu(fmu_dir) -> Path:
    from rotorcosim.fmus.export import export_component

    return export_component("testing.mass", fmu_dir / "mass.fmu", instance_name="m1",
                            parameters={"m": 1.0, "k": 40.0, "x0": 0.1})


@pytest.fixture(scope="session")
def damper_fmu(fmu_dir) -> Path:
    from rotorcosim.fmus.export import export_component

    # a coarse film mesh: the table of the fast damper is then built in about a second
    return export_component("damper.fast", fmu_dir / "damper5.fmu", instance_name="damper5",
                            parameters={"damper": 5, "n_theta": 32, "n_z": 8})
