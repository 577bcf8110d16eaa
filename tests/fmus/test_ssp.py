"""The whole system as an SSP 1.0 archive: valid, read back into a scenario our master runs identically, and run
by a co-simulation engine that is not ours (Ecos) within 1 % of our master at the same fixed step."""
from __future__ import annotations

import os
import tempfile
import zipfile
from pathlib import Path

import numpy as np
import pytest

from rotorcosim.master.scenario.ssp import SSPError, read_ssp, write_ssp
from rotorcosim.master.scenario.build import load_scenario

from tests.helpers.fmus import TOY, max_rel_diff, run_intervals

TM = [("TM", 0.3, 1e-3)]           # the toy's thermo-mechanical interval


@pytest.fixture(scope="module")
def toy_ssp(fmu_dir) -> Path:
    return write_ssp(load_scenario(TOY), fmu_dir / "toy.ssp")


def test_ssd_is_valid_ssp_1_0(toy_ssp):
    from lxml import etree
    import fmpy.ssp.ssd as ssd

    schema = etree.XMLSchema(file=os.path.join(os.path.dirname(ssd.__file__), "schema",
                                               "SystemStructureDescription.xsd"))
    with zipfile.ZipFile(toy_ssp) as zf:
        assert sorted(zf.namelist()) == ["SystemStructure.ssd", "resources/node.fmu", "resources/osc.fmu"]
        root = etree.fromstring(zf.read("SystemStructure.ssd"))
    assert schema.validate(root), schema.error_log
    ns = {"ssd": ssd.ns["ssd"], "ssc": ssd.ns["ssc"], "ssv": ssd.ns["ssv"]}
    # connectors carry units, parameters carry the scenario's values, connections are there
    assert root.find(".//ssd:Component[@name='node']/ssd:Connectors/ssd:Connector[@name='T']/ssc:Real",
                     ns).get("unit") == "K"
    c = root.find(".//ssd:Component[@name='node']//ssv:Parameter[@name='C']/ssv:Real", ns)
    assert float(c.get("value")) == 10.0
    cons = {(e.get("startElement"), e.get("startConnector"), e.get("endElement"), e.get("endConnector"))
            for e in root.findall(".//ssd:Connection", ns)}
    assert cons == {("osc", "P", "node", "P"), ("node", "T", "osc", "T")}


def test_ssp_archive_is_deterministic(toy_ssp, tmp_path):
    again = write_ssp(load_scenario(TOY), tmp_path / "again.ssp")
    assert again.read_bytes() == toy_ssp.read_bytes()


def test_read_ssp_gives_back_the_scenario(toy_ssp):
    native = load_scenario(TOY)
    sc = read_ssp(toy_ssp)
    assert sc.name == native.name and list(sc.components) == list(native.components)
    assert all(Path(c.fmu).is_file() and c.implementation is None for c in sc.components.values())
    assert {n: c.parameters for n, c in sc.components.items()} == {n: c.parameters
                                                                   for n, c in native.components.items()}
    assert [(c.src, c.dst, c.average, c.hold) for c in sc.connections] == \
        [(c.src, c.dst, c.average, c.hold) for c in native.connections]
    assert sc.schedule == native.schedule and sc.algorithm == native.algorithm


def test_ssp_runs_in_our_master_like_the_toml(toy_ssp):
    intervals = [("TM", 0.1, 1e-3), ("TO", 0.5, 0.05), ("TM", 0.1, 1e-3)]
    a = run_intervals(load_scenario(TOY), intervals)
    b = run_intervals(read_ssp(toy_ssp), intervals)
    assert max_rel_diff(a, b, list(a.rows[0])) < 1e-9


def test_cli_export_fmus_export_ssp_and_run(tmp_path):
    from fmpy.validation import validate_fmu

    from rotorcosim.master.cli import main

    assert main(["export-fmus", str(tmp_path / "fmus"), "--scenario", str(TOY)]) == 0
    written = sorted(p.name for p in (tmp_path / "fmus").iterdir())
    assert written == ["node.fmu", "osc.fmu"]
    assert all(validate_fmu(str(p)) == [] for p in (tmp_path / "fmus").iterdir())
    assert main(["export-fmus", str(tmp_path / "one"), "--scenario", str(TOY), "--component", "node"]) == 0
    assert sorted(p.name for p in (tmp_path / "one").iterdir()) == ["node.fmu"]
    assert main(["export-ssp", str(tmp_path / "toy.ssp"), str(TOY)]) == 0
    assert main(["run", str(tmp_path / "toy.ssp"), "--out", str(tmp_path / "out"), "--quiet",
                 "--duration", "0.5"]) == 0
    assert (tmp_path / "out" / "summary.json").is_file()


def test_cli_errors_name_the_problem(tmp_path, capsys, monkeypatch):
    from rotorcosim.components import registry
    from rotorcosim.master.cli import main

    assert main(["export-fmus", str(tmp_path / "x"), "--scenario", str(TOY), "--component", "nope"]) == 2
    assert "has no component 'nope'; its components: osc, node" in capsys.readouterr().err
    # a registered component whose code has not landed yet (as the engine's were while they were written)
    monkeypatch.setitem(registry.BUILTIN, "thermal.future_model",
                        "rotorcosim.components.thermal.not_written_yet:Future")
    sc = tmp_path / "future.toml"
    sc.write_text(TOY.read_text().replace('implementation = "testing.thermal_node"',
                                          'implementation = "thermal.future_model"'))
    assert main(["export-fmus", str(tmp_path / "y"), "--scenario", str(sc)]) == 2
    err = capsys.readouterr().err
    assert "cannot export component(s): node (thermal.future_model: its implementation cannot be imported yet" in err
    assert not (tmp_path / "y").exists()     # checked before anything was written
    assert main(["export-ssp", str(tmp_path / "toy.zip"), str(TOY)]) == 2
    assert "must end in .ssp" in capsys.readouterr().err
    # an empty name was read as the folder "." (". must end in .ssp")
    assert main(["export-ssp", "--out", "", str(TOY)]) == 2
    assert capsys.readouterr().err == ("rotorcosim export-ssp: error: --out is empty: give the SSP archive to write "
                                       "(FILE.ssp)\n")


def test_export_fmus_leaves_no_half_written_folder(tmp_path, capsys, monkeypatch):
    """A name in the folder taken by a folder is refused before anything is written (it failed after the FMUs
    before it were, with a bare "[Errno 21] Is a directory: '.node.fmu.xxxx.part' -> ..."); a write that fails
    (no space left) removes what the export wrote."""
    import errno

    from rotorcosim.master.cli import main
    from rotorcosim.master.scenario import export

    out = tmp_path / "fmus"
    (out / "node.fmu").mkdir(parents=True)
    assert main(["export-fmus", str(out), "--scenario", str(TOY)]) == 2
    assert capsys.readouterr().err == (f"rotorcosim export-fmus: error: output folder {out}: {out / 'node.fmu'} is "
                                       "not a file (a folder?): remove it or give another --out\n")
    assert sorted(p.name for p in out.iterdir()) == ["node.fmu"]
    (out / "node.fmu").rmdir()
    real = export.export_component

    def full_disk(implementation, target, **kw):
        if kw.get("instance_name") == "node":
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(implementation, target, **kw)

    monkeypatch.setattr(export, "export_component", full_disk)
    assert main(["export-fmus", str(out), "--scenario", str(TOY)]) == 2
    assert capsys.readouterr().err == (f"rotorcosim export-fmus: error: {out / 'node.fmu'}: cannot write the FMU "
                                       "(No space left on device); nothing of this export is left in the folder\n")
    assert list(out.iterdir()) == []


def test_bad_ssp_archives(tmp_path, toy_ssp):
    bad = tmp_path / "text.ssp"
    bad.write_text("no zip")
    with pytest.raises(SSPError, match="not a zip archive"):
        read_ssp(bad)
    empty = tmp_path / "empty.ssp"
    with zipfile.ZipFile(empty, "w") as zf:
        zf.writestr("readme.txt", "x")
    with pytest.raises(SSPError, match="no SystemStructure.ssd"):
        read_ssp(empty)
    slip = tmp_path / "slip.ssp"
    with zipfile.ZipFile(toy_ssp) as zin, zipfile.ZipFile(slip, "w") as zout:
        for i in zin.infolist():
            zout.writestr(i, zin.read(i))
        zout.writestr("../../evil.txt", "x")
    with pytest.raises(SSPError, match="climbs out of the folder"):
        read_ssp(slip)
    outside = tmp_path / "outside.ssp"
    with zipfile.ZipFile(toy_ssp) as zin, zipfile.ZipFile(outside, "w") as zout:
        for i in zin.infolist():
            data = zin.read(i)
            if i.filename == "SystemStructure.ssd":
                data = data.replace(b'source="resources/osc.fmu"', b'source="/etc/passwd"')
            zout.writestr(i, data)
    with pytest.raises(SSPError, match="source '/etc/passwd' is not an FMU inside the archive"):
        read_ssp(outside)



def test_ssp_connection_to_a_component_the_system_does_not_have(tmp_path, toy_ssp):
    """A dangling connection names the missing component and the system's components (it said "nodeX.P is not a
    variable of its FMU", as if an FMU nodeX were there); an unknown connector of a component keeps its message."""
    def edited(name, old, new):
        dst = tmp_path / name
        with zipfile.ZipFile(toy_ssp) as zin, zipfile.ZipFile(dst, "w") as zout:
            for i in zin.infolist():
                data = zin.read(i)
                if i.filename == "SystemStructure.ssd":
                    assert old in data
                    data = data.replace(old, new)
                zout.writestr(i, data)
        return dst

    dangling = edited("dangling.ssp", b'endElement="node" endConnector="P"', b'endElement="nodeX" endConnector="P"')
    with pytest.raises(SSPError) as exc:
        read_ssp(dangling)
    assert str(exc.value) == (f"{dangling}: connection osc.P -> nodeX.P: the system has no component 'nodeX' (its "
                              "components: osc, node)")
    unknown = edited("unknown.ssp", b'endElement="node" endConnector="P"', b'endElement="node" endConnector="Q"')
    with pytest.raises(SSPError, match=r"connection osc.P -> node.Q: node.Q is not a variable of its FMU$"):
        read_ssp(unknown)

# -- Ecos ---------------------------------------------------------------------------------------------------
@pytest.fixture
def ecospy_loaded():
    """ecospy (in the test extra: imported plainly). Its native library needs Debian's libtbb12, which pip cannot
    install: only that skips."""
    try:
        import ecospy
    except OSError as exc:   # ecospy loads its native library at import: OSError when libtbb12 is missing
        pytest.skip(f"ecospy's native library does not load (Debian's libtbb12 missing? apt-get install libtbb12): "
                    f"{exc}")
    return ecospy


def ecos_run(ssp: Path, step: float, n: int, signals: list[str]) -> dict[str, np.ndarray]:
    """Run ``ssp`` in Ecos for ``n`` fixed steps, sampling ``signals`` ("comp.var") after every step."""
    from ecospy import EcosSimulation   # after the ``ecospy_loaded`` fixture

    out = {s: np.empty(n) for s in signals}
    with EcosSimulation(ssp_path=str(ssp), step_size=step) as sim:
        sim.init(parameter_set="initialValues")
        for k in range(n):
            sim.step()
            for s in signals:
                out[s][k] = sim.get_real(s.replace(".", "::", 1))
        sim.terminate()
    return out


def test_ecos_runs_the_exported_ssp_like_our_master(toy_ssp, ecospy_loaded, tmp_path, monkeypatch):
    # Ecos extracts the archive into the temporary folder (ecos_ssp_<uuid>) and leaves it there: into tmp_path
    tempfile.gettempdir()   # Python's own temporary folder is read once, before: it stays /tmp for the other tests
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    (phase, duration, step), = TM
    n = round(duration / step)
    signals = ["osc.x", "osc.v", "osc.P", "node.T"]
    ecos = ecos_run(toy_ssp, step, n, signals)
    sc = read_ssp(toy_ssp)
    sc.algorithm = {"kind": "jacobi", "order": ["osc", "node"]}   # Ecos exchanges values Jacobi-style
    ours = run_intervals(sc, TM)
    assert len(ours.rows) == n
    # the oscillator swings through several periods and the node warms: the comparison is not trivial
    assert np.ptp(ecos["osc.x"]) > 1e-3 and np.ptp(ecos["node.T"]) > 0.5
    for s in signals:
        mine = ours.series(s).reshape(n)
        assert np.max(np.abs(mine - ecos[s])) <= 0.01 * np.max(np.abs(mine)), s


def test_parameter_values_from_an_ssv_file(toy_ssp, tmp_path):
    """Parameter bindings may point at an .ssv file instead of carrying the values inline."""
    import xml.etree.ElementTree as ET

    from rotorcosim.master.scenario.ssp import NS

    with zipfile.ZipFile(toy_ssp) as zf:
        entries = {n: zf.read(n) for n in zf.namelist()}
    root = ET.fromstring(entries["SystemStructure.ssd"])
    binding = root.find(".//ssd:Component[@name='node']/ssd:ParameterBindings/ssd:ParameterBinding", NS)
    values = binding.find("ssd:ParameterValues", NS)
    pset = values.find("ssv:ParameterSet", NS)
    for p in pset.iter(f"{{{NS['ssv']}}}Real"):
        p.set("value", str(2 * float(p.get("value"))))        # C = 20, R = 2: not the scenario's values
    binding.remove(values)
    binding.set("source", "resources/node.ssv")
    entries["resources/node.ssv"] = ET.tostring(pset, encoding="UTF-8", xml_declaration=True)
    entries["SystemStructure.ssd"] = ET.tostring(root, encoding="UTF-8", xml_declaration=True)
    out = tmp_path / "ssv.ssp"
    with zipfile.ZipFile(out, "w") as zf:
        for n, data in entries.items():
            zf.writestr(n, data)
    assert read_ssp(out).components["node"].parameters == {"C": 20.0, "R": 2.0}


# -- hostile or careless SystemStructure.ssd ------------------------------------------------------------------
def _edited(toy_ssp: Path, dest: Path, edit) -> Path:
    """A copy of the toy archive with its SystemStructure.ssd text passed through ``edit``."""
    with zipfile.ZipFile(toy_ssp) as zin, zipfile.ZipFile(dest, "w") as zout:
        for i in zin.infolist():
            data = zin.read(i)
            if i.filename == "SystemStructure.ssd":
                data = edit(data.decode()).encode()
            zout.writestr(i, data)
    return dest


def _payload(**changes):
    """An edit of the rotorcosim annotation's JSON: ``key=value`` replaced (``value`` None: key removed)."""
    import json
    import re

    def edit(text):
        m = re.search(r"<rc:Scenario>(.*)</rc:Scenario>", text)
        p = json.loads(m.group(1))
        for k, v in changes.items():
            p[k] = v
        return text.replace(m.group(1), json.dumps(p).replace("&", "&amp;").replace("<", "&lt;"))
    return edit


_C10 = '<ssv:Real value="10.0" />'


@pytest.mark.parametrize("edit, message", [
    # the annotation's JSON, each a crash (AttributeError, TypeError) or a silent misreading before
    (_payload(steps=5), "annotation org.rotorcosim.scenario: 'steps' must be a JSON object, got a JSON number"),
    (_payload(steps={"osc": "abc"}), "steps['osc'] = 'abc' is not a positive step"),
    (_payload(connections=[1]), "'connections' must be a list of JSON objects"),
    (_payload(inputs=[1]), "'inputs' must be a JSON object, got a JSON array"),
    (_payload(schedule="abc"), "'schedule' must be a JSON object"),
    (_payload(algorithm={"kind": "gauss-seidel", "order": ["osc", "nod"]}), "no component 'nod'"),
    (_payload(outputs={"record": ["osc.x"], "record_step": -1}), "record_step: must be a positive number"),
    (_payload(connections=[{"from": "osc.P", "to": "node.P", "average": "sideways"}]), "'sideways' is not one of"),
    (_payload(name=5), "'name' must be a JSON string, got a JSON number"),
    (_payload(bogus=1), "unknown key 'bogus'"),
    # the experiment's times when the annotation gives no schedule
    (lambda t: _payload(schedule=None)(t).replace('stopTime="30.0"', 'stopTime="-5"'), "stopTime -5.0 is not after"),
    (lambda t: _payload(schedule=None)(t).replace('stopTime="30.0"', 'stopTime="inf"'), "is not a finite number"),
    # component names the rest of the archive cannot tell apart or refer to
    (lambda t: t.replace('<ssd:Component name="node"', '<ssd:Component name="osc"'), "two components have this name"),
    (lambda t: t.replace('<ssd:Component name="node"', '<ssd:Component name=""'), "must be non-empty"),
    (lambda t: t.replace('name="node"', 'name="no.de"').replace('Element="node"', 'Element="no.de"'),
     "contain no '.'"),
    # a parameter value written in a unit: converted, or refused, never read as the variable's own unit
    (lambda t: t.replace(_C10, '<ssv:Real value="10.0" unit="kJ/K" />'), "given in 'kJ/K', which cannot be converted"),
    (lambda t: t.replace(_C10, '<ssv:Real value="10.0" unit="m" />'), "given in 'm', not a unit of the variable's"),
])
def test_careless_or_hostile_system_structure(tmp_path, toy_ssp, edit, message):
    with pytest.raises(SSPError) as err:
        read_ssp(_edited(toy_ssp, tmp_path / "edited.ssp", edit))
    assert message in str(err.value) and "\n" not in str(err.value)


def test_parameter_value_in_another_unit_is_converted(tmp_path, toy_ssp):
    """C = 0.01 kJ/K with kJ defined in ssd:Units (factor 1000) is the scenario's 10 J/K."""
    def edit(text):
        text = text.replace(_C10, '<ssv:Real value="0.01" unit="kJ/K" />')
        return text.replace("<ssd:Units>", '<ssd:Units><ssc:Unit name="kJ/K"><ssc:BaseUnit kg="1" m="2" s="-2" '
                                           'K="-1" factor="1000" /></ssc:Unit>')
    sc = read_ssp(_edited(toy_ssp, tmp_path / "kj.ssp", edit))
    assert sc.components["node"].parameters["C"] == pytest.approx(10.0, rel=1e-12)


_NS = ('xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues" '
       'xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon"')
_KJ = 'kg="1" m="2" s="-2" K="-1" factor="1000"'


def _ssv(value: str, unit: str, base: str) -> str:
    """A parameter file (.ssv) giving node's C in ``unit``, which it defines itself (ssv:Units) as ``base``."""
    return (f'<?xml version="1.0" encoding="UTF-8"?><ssv:ParameterSet {_NS} version="1.0" name="p"><ssv:Parameters>'
            f'<ssv:Parameter name="C"><ssv:Real value="{value}" unit="{unit}" /></ssv:Parameter></ssv:Parameters>'
            f'<ssv:Units><ssc:Unit name="{unit}"><ssc:BaseUnit {base} /></ssc:Unit></ssv:Units></ssv:ParameterSet>')


def _with_parameter_file(toy_ssp: Path, dest: Path, ssv: str, binding_extra: str = "") -> Path:
    """The toy archive with resources/p.ssv bound to node after its inline values (a later binding wins)."""
    def edit(text):
        close = "</ssd:ParameterBindings>\n      </ssd:Component>\n    </ssd:Elements>"
        assert close in text
        return text.replace(close, f'<ssd:ParameterBinding type="application/x-ssp-parameter-set" '
                                   f'source="resources/p.ssv">{binding_extra}</ssd:ParameterBinding>' + close)
    path = _edited(toy_ssp, dest, edit)
    with zipfile.ZipFile(path, "a") as z:
        z.writestr("resources/p.ssv", ssv)
    return path


@pytest.mark.parametrize("value, unit, base", [
    ("0.01", "kJperK", _KJ),      # a unit only the parameter file defines (was refused as unreadable)
    ("0.01", "J/K", _KJ),         # the file's own "J/K" is 1000 J/K: was read as the FMU's J/K (0.01, silently)
    ("10", "mine", 'kg="1" m="2" s="-2" K="-1"'),
])
def test_parameter_file_units_are_read(tmp_path, toy_ssp, value, unit, base):
    sc = read_ssp(_with_parameter_file(toy_ssp, tmp_path / "u.ssp", _ssv(value, unit, base)))
    assert sc.components["node"].parameters["C"] == pytest.approx(10.0, rel=1e-12)


@pytest.mark.parametrize("base, extra, message", [
    ('kg="1" factor="1000"', "", "parameter 'C': given in 'X', not a unit of the variable's quantity ('J/K')"),
    ('kg="1" m="2" s="-2" K="-1" factor="abc"', "", "unit 'X': a BaseUnit exponent is not a whole number, or its "
                                                    "factor or offset not a number"),
    ('kg="1" m="2" s="-2" K="-1" factor="0"', "", "unit 'X': factor must be a finite number > 0"),
    ('kg="1" furlong="2"', "", "unit 'X': unknown BaseUnit attribute(s) furlong"),
    (_KJ, '<ssd:ParameterMapping source="resources/m.ssm" />', "ParameterMapping (.ssm) are not supported"),
])
def test_parameter_file_units_that_cannot_be_read(tmp_path, toy_ssp, base, extra, message):
    with pytest.raises(SSPError) as err:
        read_ssp(_with_parameter_file(toy_ssp, tmp_path / "u.ssp", _ssv("0.01", "X", base), extra))
    assert message in str(err.value) and "\n" not in str(err.value)


def _as_osp_archive(toy_ssp: Path, dst: Path, base_step: str | None) -> Path:
    """The toy's archive as another tool writes it: without our annotation, its DefaultExperiment carrying the
    Open Simulation Platform's algorithm annotation (libcosim's demo.ssp) when ``base_step`` is given."""
    import xml.etree.ElementTree as ET

    from rotorcosim.master.scenario.ssp import ANNOTATION, NS, OSP_ANNOTATION, OSP_NS

    with zipfile.ZipFile(toy_ssp) as zf:
        entries = {n: zf.read(n) for n in zf.namelist()}
    root = ET.fromstring(entries["SystemStructure.ssd"])
    anns = root.find("ssd:Annotations", NS)
    for a in anns.findall("ssc:Annotation", NS):
        if a.get("type") == ANNOTATION:
            anns.remove(a)
    de = root.find("ssd:DefaultExperiment", NS)
    if base_step is not None:
        a = ET.SubElement(ET.SubElement(de, f"{{{NS['ssd']}}}Annotations"), f"{{{NS['ssc']}}}Annotation",
                          {"type": OSP_ANNOTATION})
        ET.SubElement(ET.SubElement(a, f"{{{OSP_NS}}}Algorithm"), f"{{{OSP_NS}}}FixedStepAlgorithm",
                      {"baseStepSize": base_step})
    entries["SystemStructure.ssd"] = ET.tostring(root, encoding="UTF-8", xml_declaration=True)
    with zipfile.ZipFile(dst, "w") as zf:
        for n, data in entries.items():
            zf.writestr(n, data)
    return dst


def test_another_tools_archive_runs_at_its_osp_base_step(toy_ssp, tmp_path):
    """libcosim's SSP systems give their step as osp:FixedStepAlgorithm baseStepSize (its demo.ssp: 1e-4 s, which
    our master ran at its FMUs' 1e-3 s before): read as the schedule's step; without it, the FMUs' smallest
    DefaultExperiment stepSize; a step that is no positive number is named."""
    plain = read_ssp(_as_osp_archive(toy_ssp, tmp_path / "plain.ssp", None)).schedule["step"]
    osp = read_ssp(_as_osp_archive(toy_ssp, tmp_path / "osp.ssp", "2.5e-4")).schedule
    assert osp["kind"] == "monolithic" and osp["step"] == 2.5e-4 != plain
    with pytest.raises(SSPError, match=r"FixedStepAlgorithm baseStepSize='-1' is not a positive number"):
        read_ssp(_as_osp_archive(toy_ssp, tmp_path / "bad.ssp", "-1"))


def _read_in_child(path: str, tmp: str) -> None:
    tempfile.tempdir = tmp
    read_ssp(path)


def test_a_child_process_removes_what_it_extracted(toy_ssp, tmp_path):
    """A multiprocessing child (a sweep's worker) that read an archive ends with os._exit, which runs no atexit
    handler: its extraction folder (rcs_ssp_*) stayed in /tmp."""
    import multiprocessing

    child = multiprocessing.get_context("fork").Process(target=_read_in_child, args=(str(toy_ssp), str(tmp_path)))
    child.start()
    child.join(120)
    assert child.exitcode == 0
    assert list(tmp_path.iterdir()) == []
