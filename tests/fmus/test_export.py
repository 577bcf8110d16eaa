"""Every registered, importable component exported as an FMU: valid for fmpy, simulates alone, same interface.

Parametrised over the registry, so components that land later are covered without touching this file. Every
shipped component (``registry.BUILTIN``) is a case: one whose implementation cannot be imported fails with the
import error, it is not skipped.
"""
from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest

from rotorcosim.components import registry
from rotorcosim.components.contract import ContractError
from rotorcosim.components.rotor.model import DEFAULT_FILE
from rotorcosim.fmus.export import ExportError, export_component
from rotorcosim.fmus.description import describe, ports_of
from rotorcosim.fmus.model_description import read_annotation

#: parameters that keep the export tests quick (a coarse damper mesh) and the machine's values a component has no
#: default for (a bearing's, damper's, ring's, network's: the paper's Table 3 record #0; a spool's inertia, the
#: paper's power turbine's); everything else at its defaults
QUICK = {"damper.fast": {"damper": 0, "n_theta": 32, "n_z": 8}, "damper.fe": {"damper": 0, "n_theta": 32, "n_z": 8},
         **{k: {"bearing": 0} for k in ("bearing.hertz", "bearing.hertz_spinning", "rubring.contact",
                                         "rubring.contact_spinning", "thermal.network", "thermal.network_spinning")},
         "spool.speed": {"inertia": 0.0396}, "fuse.support": {"k_intact": 4.0e6, "break_load": 1500.0},
         # the airframe's ports are its engine file's mounts (the paper engine on the example pylon and wing)
         "airframe.modal": {"model_file": str(Path(DEFAULT_FILE).with_name("engine_on_pylon.toml"))}}
#: inputs held at typical non-zero values where the start values would leave the component idle
TYPICAL = {"damper.fast": {"X_journal[1]": 1e-4, "V_journal[2]": 0.05},
           "damper.fe": {"X_journal[1]": 1e-4, "V_journal[2]": 0.05},
           "testing.mass": {"F": 1.0}, "testing.thermal_node": {"P": 100.0}, "fuse.support": {"X[1]": 1e-4},
           "airframe.modal": {"X_mount_aft[1]": 1e-5}}


def _importable():
    """The shipped components, and those registered otherwise whose class is one of rotorcosim's components."""
    out = [pytest.param(name, id=name) for name in sorted(registry.BUILTIN)]
    for name in registry.available():
        if name in registry.BUILTIN:
            continue
        try:
            cls = registry.lookup(name)
        except (ImportError, ContractError):
            continue   # a plug-in or another test's component (not shipped): not bundled, not this file's concern
        if cls.__module__.startswith("rotorcosim.components."):
            out.append(pytest.param(name, id=name))
    return out


def test_every_shipped_component_imports():
    """A shipped component whose implementation cannot be imported is an error, named here."""
    broken = {}
    for name in registry.BUILTIN:
        try:
            registry.lookup(name)
        except ImportError as exc:
            broken[name] = f"{type(exc).__name__}: {exc}"
    assert broken == {}


_cache: dict = {}


@pytest.fixture
def exported(request, fmu_dir):
    name = request.param
    if name not in _cache:
        _cache[name] = export_component(name, fmu_dir / f"{name.replace('.', '_')}.fmu",
                                        parameters=QUICK.get(name, {}))
    return name, _cache[name]


@pytest.mark.parametrize("exported", _importable(), indirect=True)
def test_exported_fmu_passes_fmpy_validation(exported):
    from fmpy.validation import validate_fmu

    name, path = exported
    assert validate_fmu(str(path)) == []


@pytest.mark.parametrize("exported", _importable(), indirect=True)
def test_exported_fmu_declares_the_component_interface(exported):
    name, path = exported
    xml, md = describe(path)
    hidden = read_annotation(xml).hidden
    assert hidden == {"_rcs_phase", "_rcs_phases"}      # the schedule's phase crosses the boundary too
    variables, _ = ports_of(md, str(path), hidden)
    native = registry.create(name, name, QUICK.get(name, {}))
    got = {v.name: (v.causality, v.size, v.unit, v.description, v.type) for v in variables}
    want = {v.name: (v.causality, v.size, v.unit, v.description, v.type) for v in native.variables}
    assert got == want
    assert md.coSimulation.canGetAndSetFMUstate
    assert float(md.defaultExperiment.stepSize) == native.preferred_step


@pytest.mark.parametrize("exported", _importable(), indirect=True)
def test_exported_fmu_simulates_alone_in_fmpy(exported):
    from fmpy import read_model_description, simulate_fmu

    name, path = exported
    md = read_model_description(str(path))
    h = float(md.defaultExperiment.stepSize)
    outputs = [v.name for v in md.modelVariables if v.causality == "output"]
    res = simulate_fmu(str(path), stop_time=20 * h, output_interval=h, start_values=TYPICAL.get(name, {}),
                       output=outputs)
    assert len(res) >= 20
    for n in outputs:
        assert np.all(np.isfinite(res[n])), n
    # with non-zero inputs something must respond (not a dead FMU returning its start values)
    if name in TYPICAL:
        assert any(np.any(res[n] != res[n][0]) or np.any(res[n] != 0.0) for n in outputs)


def test_export_is_deterministic(tmp_path):
    a = export_component("testing.spring", tmp_path / "a.fmu", instance_name="s", parameters={"kc": 3.0})
    b = export_component("testing.spring", tmp_path / "b.fmu", instance_name="s", parameters={"kc": 3.0})
    assert a.read_bytes() == b.read_bytes()
    with zipfile.ZipFile(a) as zf:
        names = zf.namelist()
        assert names == sorted(names)
        assert {i.date_time for i in zf.infolist()} == {(1980, 1, 1, 0, 0, 0)}
        # the code travels with the FMU: the component's class under the private package, not rotorcosim
        assert any(n.endswith("/testing/mass_spring.py") for n in names)
        assert not any("rotorcosim.components" in zf.read(n).decode("utf-8", "replace")
                       for n in names if n.endswith(".py") and "/testing/" in n)


def test_export_errors_name_the_problem(tmp_path):
    with pytest.raises(ExportError, match="unknown component implementation 'nope.nothing'"):
        export_component("nope.nothing", tmp_path)
    with pytest.raises(ExportError, match="no variable 'mass'"):
        export_component("testing.mass", tmp_path, parameters={"mass": 1.0})
    with pytest.raises(ExportError, match="does not exist"):
        export_component("testing.mass", tmp_path / "missing" / "m.fmu")
    assert list(tmp_path.iterdir()) == []   # nothing half-written


def test_export_refuses_an_airframe_without_mounts(tmp_path):
    """The airframe on an engine file without [airframe] and [mount.NAME] tables (the default engine's rigid ground)
    has no ports and could not initialise as an FMU: refused, naming the missing tables, nothing written."""
    with pytest.raises(ExportError) as info:
        export_component("airframe.modal", tmp_path)
    msg = str(info.value)
    assert "\n" not in msg
    assert "cannot export airframe.modal (airframe.modal): airframe.modal.model_file: the engine file " in msg
    assert "has no [airframe] and [mount.NAME] tables" in msg
    assert list(tmp_path.iterdir()) == []


def test_export_fmus_refuses_a_scenarios_airframe_without_mounts(tmp_path, capsys):
    """The same through ``rotorcosim export-fmus``: one line, exit status 2, no output folder."""
    from rotorcosim.master.cli.program import main

    scenario = tmp_path / "on_ground.toml"
    base = Path(registry.__file__).parents[1] / "scenarios" / "blade_loss_2850.toml"
    scenario.write_text(f'[scenario]\nextends = "{base.as_posix()}"\nname = "on_ground"\n\n'
                        '[components.airframe]\nimplementation = "airframe.modal"\n')
    assert main(["export-fmus", str(scenario), "--component", "airframe", "--out", str(tmp_path / "fmus")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert "airframe (airframe.modal: airframe.model_file: the engine file " in err
    assert "has no [airframe] and [mount.NAME] tables" in err
    assert not (tmp_path / "fmus").exists()


_NO_ROTORCOSIM = r"""
import sys
class Block:
    def find_spec(self, name, path=None, target=None):
        if name == "rotorcosim" or name.startswith("rotorcosim."):
            raise ImportError("rotorcosim is blocked in this process")
sys.meta_path.insert(0, Block())
import fmpy, numpy as np
res = fmpy.simulate_fmu(sys.argv[1], stop_time=0.1, output_interval=1e-3, start_values={"F": 1.0})
assert not any(m == "rotorcosim" or m.startswith("rotorcosim.") for m in sys.modules)
print(float(np.max(np.abs(res["x"] - 0.1))))
"""


def test_exported_fmu_needs_no_rotorcosim(mass_fmu, tmp_path):
    """The FMU carries its code: it runs in a process where importing rotorcosim is impossible."""
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-I", "-c", _NO_ROTORCOSIM, str(mass_fmu)], cwd=tmp_path,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert float(out.stdout.strip().splitlines()[-1]) > 1e-3    # the mass (x0 = 0.1 m, k = 40 N/m) moved


def test_exported_files_get_the_usual_mode(mass_fmu, tmp_path):
    """An exported FMU (and any archive written the same way, SSP included) is readable by others: 0666 less
    the umask (0644 under the usual 022), not mkstemp's 0600."""
    import os
    import stat

    from rotorcosim.fmus.export import write_deterministic_zip

    old = os.umask(0o022)
    try:
        p = write_deterministic_zip({"a.txt": b"x"}, tmp_path / "a.zip")
    finally:
        os.umask(old)
    assert stat.S_IMODE(p.stat().st_mode) == 0o644
    assert stat.S_IMODE(mass_fmu.stat().st_mode) == 0o666 & ~old
