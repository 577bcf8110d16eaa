"""Bad FMUs, each built here from a good one, each refused with a clear error naming the file and the problem."""
from __future__ import annotations

import re
import stat
import sys
import tempfile
import zipfile
from pathlib import Path

import numpy as np
import pytest

from rotorcosim.fmus.importer import FMUError, load_fmu_component
from rotorcosim.master.scenario.build import build_system, parse
from rotorcosim.master.core.system import SystemError_


def rewrite(src: Path, dst: Path, replace: dict | None = None, extra: list | None = None) -> Path:
    """Copy the zip ``src`` to ``dst``, replacing (bytes) or dropping (None) entries, adding ZipInfo/bytes pairs."""
    replace = replace or {}
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w") as zout:
        for info in zin.infolist():
            if info.filename in replace:
                if replace[info.filename] is not None:
                    zout.writestr(info.filename, replace[info.filename])
            else:
                zout.writestr(info, zin.read(info))
        for info, data in extra or []:
            zout.writestr(info, data)
    return dst


def description(fmu: Path) -> str:
    with zipfile.ZipFile(fmu) as zf:
        return zf.read("modelDescription.xml").decode()


@pytest.fixture
def private_tmp(tmp_path, monkeypatch):
    """Temporary folders of the importer go under tmp_path/t and its cache under tmp_path/cache, so the test
    can see what is left behind."""
    t = tmp_path / "t"
    t.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(t))
    monkeypatch.setenv("ROTORCOSIM_CACHE", str(tmp_path / "cache"))
    return t


def test_not_a_zip(tmp_path):
    bad = tmp_path / "text.fmu"
    bad.write_text("this is not an FMU")
    with pytest.raises(FMUError, match=r"text\.fmu is not a zip archive"):
        load_fmu_component(bad, "c")


def test_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="nothing.fmu not found"):
        load_fmu_component(tmp_path / "nothing.fmu", "c")


def test_no_model_description(mass_fmu, tmp_path):
    bad = rewrite(mass_fmu, tmp_path / "nomd.fmu", {"modelDescription.xml": None})
    with pytest.raises(FMUError, match="no modelDescription.xml"):
        load_fmu_component(bad, "c")


def test_model_exchange_only(mass_fmu, tmp_path):
    xml = re.sub(r"<CoSimulation [^>]*/>", '<ModelExchange modelIdentifier="m1" />', description(mass_fmu))
    bad = rewrite(mass_fmu, tmp_path / "me.fmu", {"modelDescription.xml": xml.encode()})
    with pytest.raises(FMUError, match="model exchange only"):
        load_fmu_component(bad, "c")


def test_binary_that_does_not_load(mass_fmu, tmp_path, private_tmp):
    bad = rewrite(mass_fmu, tmp_path / "badbin.fmu", {"binaries/linux64/m1.so": b"\x7fELF garbage"})
    with pytest.raises(FMUError, match=r"binary \(model identifier 'm1'\) does not load"):
        load_fmu_component(bad, "c")
    nobin = rewrite(mass_fmu, tmp_path / "nobin.fmu", {"binaries/linux64/m1.so": None})
    with pytest.raises(FMUError, match="does not load.*binaries in the FMU: binaries/win64/m1.dll"):
        load_fmu_component(nobin, "c")
    assert list(private_tmp.iterdir()) == []     # the extraction folders were removed
    cache = tmp_path / "cache" / "fmu"
    assert not cache.exists() or list(cache.iterdir()) == []   # nor kept in the cache


@pytest.mark.parametrize("entry, why", [
    ("../evil.txt", "climbs out of the folder"),
    ("resources/../../evil.txt", "climbs out of the folder"),
    ("/tmp/evil_rotorcosim.txt", "is an absolute path"),
    ("resources\\..\\..\\evil.txt", "contains a backslash"),
])
def test_entries_escaping_the_extraction_folder(mass_fmu, tmp_path, private_tmp, entry, why):
    info = zipfile.ZipInfo(entry)
    bad = rewrite(mass_fmu, tmp_path / "slip.fmu", extra=[(info, b"owned")])
    with pytest.raises(FMUError, match=re.escape(why)):
        load_fmu_component(bad, "c")
    assert not (tmp_path / "evil.txt").exists() and not Path("/tmp/evil_rotorcosim.txt").exists()
    assert list(private_tmp.iterdir()) == []


def test_symlink_entry(mass_fmu, tmp_path, private_tmp):
    info = zipfile.ZipInfo("resources/link")
    info.create_system = 3
    info.external_attr = (stat.S_IFLNK | 0o777) << 16
    bad = rewrite(mass_fmu, tmp_path / "link.fmu", extra=[(info, b"/etc")])
    with pytest.raises(FMUError, match="is a symbolic link"):
        load_fmu_component(bad, "c")
    assert list(private_tmp.iterdir()) == []


def test_unknown_or_mismatched_parameters(mass_fmu):
    with pytest.raises(FMUError, match=r"mass\.fmu \(component 'c'\): no parameter 'mass'; its parameters: m, k, c"):
        load_fmu_component(mass_fmu, "c", {"mass": 1.0})
    with pytest.raises(FMUError, match=r"input \(not a parameter\) 'F'"):
        load_fmu_component(mass_fmu, "c", {"F": 1.0})
    with pytest.raises(FMUError, match=r"expected 1 value\(s\), got 2"):
        load_fmu_component(mass_fmu, "c", {"k": [1.0, 2.0]})


def _system(mass_fmu, src="m1.x", dst="m2.x_in"):
    return parse({
        "components": {"m1": {"fmu": str(mass_fmu)}, "m2": {"implementation": "testing.spring"}},
        "connections": [{"from": src, "to": dst}, {"from": "m1.v", "to": "m2.v_in"},
                        {"from": "m2.F", "to": "m1.F"}],
    })


def test_variables_missing_from_the_fmu_are_named(mass_fmu):
    with pytest.raises(SystemError_, match=r"m1\.pos: component 'm1' \(<FMUComponent 'm1' .*\.fmu.*\) has no output "
                                            r"'pos' \(its outputs: x, v\)"):
        build_system(_system(mass_fmu, src="m1.pos"))


def test_ports_of_the_wrong_size_are_named(damper_fmu):
    sc = parse({
        "components": {"m": {"implementation": "testing.mass"}, "d": {"fmu": str(damper_fmu)}},
        "connections": [{"from": "m.x", "to": "d.X_journal"}],
    })
    with pytest.raises(SystemError_, match=r"m\.x \(size 1\) -> d\.X_journal \(size 2\): sizes differ"):
        build_system(sc)


def test_scalars_that_do_not_form_a_vector(damper_fmu, tmp_path):
    xml = description(damper_fmu).replace('name="X_journal[2]"', 'name="X_journal[3]"')
    bad = rewrite(damper_fmu, tmp_path / "gap.fmu", {"modelDescription.xml": xml.encode()})
    with pytest.raises(FMUError, match=r"elements of 'X_journal' are not numbered 1\.\.n \(or 0\.\.n-1\) without "
                                       r"gaps \(found indices \[1, 3\]\)"):
        load_fmu_component(bad, "d")


def test_scalars_numbered_from_0_form_a_vector(damper_fmu, tmp_path):
    """A C or C++ tool's arrays (libcosim's test FMU vector.fmu: input[0]..input[2]): the same port as 1-based
    names, element by element: the damper FMU with X_journal[1], [2] renamed [0], [1] gives the same outputs."""
    xml = description(damper_fmu).replace('name="X_journal[1]"', 'name="X_journal[0]"').replace(
        'name="X_journal[2]"', 'name="X_journal[1]"')
    zero = rewrite(damper_fmu, tmp_path / "zero.fmu", {"modelDescription.xml": xml.encode()})
    outs = []
    for fmu in (damper_fmu, zero):
        c = load_fmu_component(fmu, "d")
        assert c.variable("X_journal").size == 2
        c.setup(0.0)
        c.set_inputs({"X_journal": np.array([1e-4, -2e-4])})
        c.do_step(0.0, 1e-5)
        outs.append({k: np.array(v, dtype=float) for k, v in c.y.items()})
        c.terminate()
    assert outs[0].keys() == outs[1].keys() and any(np.any(v) for v in outs[0].values())
    for k in outs[0]:
        np.testing.assert_array_equal(outs[1][k], outs[0][k], err_msg=k)


def test_rollback_needs_fmu_state(mass_fmu, tmp_path):
    xml = description(mass_fmu).replace('canGetAndSetFMUstate="true"', 'canGetAndSetFMUstate="false"')
    fmu = rewrite(mass_fmu, tmp_path / "nostate.fmu", {"modelDescription.xml": xml.encode()})
    c = load_fmu_component(fmu, "c")
    try:
        c.setup(0.0)
        c.do_step(0.0, 1e-3)        # stepping still works
        with pytest.raises(FMUError, match="cannot get/set its state.*rollback"):
            c.get_state()
    finally:
        c.terminate()


def test_state_rollback_and_clean_up(mass_fmu, private_tmp):
    c = load_fmu_component(mass_fmu, "c", {"c": 0.3})
    folder = c._handle.folder
    cache = private_tmp.parent / "cache" / "fmu"
    assert folder.is_dir() and folder.parent == cache       # the first instance uses the cached extraction
    twin = load_fmu_component(mass_fmu, "twin")              # a second live instance gets a fresh folder
    twin_folder = twin._handle.folder
    assert twin_folder.parent == private_tmp
    twin.terminate()
    assert not twin_folder.exists()
    c.setup(0.0)
    c.set_inputs({"F": [2.0]})
    snap = c.get_state()
    for k in range(5):
        c.do_step(k * 1e-3, 1e-3)
    first = c.y["x"].copy()
    c.set_state(snap)
    c.set_inputs({"F": [2.0]})
    for k in range(5):
        c.do_step(k * 1e-3, 1e-3)
    np.testing.assert_array_equal(c.y["x"], first)
    assert first[0] != 0.1          # it moved away from x0
    c.terminate()
    assert folder.is_dir()                                   # kept for the next run (extraction_cache.py)
    assert not any(str(p).startswith(str(folder)) for p in sys.path)
    again = load_fmu_component(mass_fmu, "again")            # ... which reuses it
    assert again._handle.folder == folder
    again.terminate()


def test_unreadable_model_description(mass_fmu, tmp_path):
    bad = rewrite(mass_fmu, tmp_path / "garbled.fmu", {"modelDescription.xml": b"<fmiModelDescription fmiVer"})
    with pytest.raises(FMUError, match="modelDescription.xml cannot be read"):
        load_fmu_component(bad, "c")


def test_component_errors_inside_the_fmu_reach_the_user(damper_fmu):
    """A bad parameter value is found by the component inside the FMU: its own message must come out."""
    c = load_fmu_component(damper_fmu, "damper_x", {"damper": 7})
    try:
        with pytest.raises(FMUError, match=r"initialisation failed.*damper_x\.damper must be one of \[0, 5\]"):
            c.setup(0.0)
    finally:
        c.terminate()


def test_component_errors_in_a_step_reach_the_user(damper_fmu):
    """The journal pushed through the film (wall contact switched off): the damper's own error comes out."""
    c = load_fmu_component(damper_fmu, "damper_y", {"k_wall": 0.0})
    try:
        c.setup(0.0)
        c.set_inputs({"X_journal": [1e-3, 0.0]})        # beyond the 0.635 mm clearance
        with pytest.raises(FMUError, match=r"DoStep\(t = 0 s.*damper_y.*wall"):
            c.do_step(0.0, 1e-5)
    finally:
        c.terminate()
