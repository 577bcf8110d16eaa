"""A corpus of careless and hostile inputs, each run through the command line as a user would.

Every input here is wrong. Each must end with exit status 1 or 2, exactly one line on stderr naming the problem
(no traceback, no "unexpected ... it may be a bug", no warning text), and nothing half-written: no ``*.part``
file, no temporary extraction folder left, and an output folder only if the run had started (then holding its
summary with status "failed"). The classes: scenario files (every numeric key of the toy scenario given NaN,
inf, text, a boolean, a list or a table; broken TOML), ``--set`` values, FMU and SSP archives (truncated, not a
zip, zip-slip and absolute entry names, a zip bomb, no or a hostile model description, missing binaries),
checkpoints (truncated, garbage, of another scenario), output places, and the number options of every command.
Only fast cases (the toy scenario, failures found before or at set-up): the whole file runs in about a minute.
"""
from __future__ import annotations

import io
import os
import re
import shutil
import tempfile
import warnings
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest

from rotorcosim import scenarios
from rotorcosim.master.cli import main

from tests.helpers.fmus import rebuild

TOY = Path(scenarios.__file__).with_name("toy_thermomechanical.toml")
TOY_TEXT = TOY.read_text()
RUN = ["run", "--quiet", "--no-figures", "--duration", "0.05"]


def cli(argv: list[str]) -> tuple[int, list[str]]:
    """Exit status and the non-empty stderr lines of ``rotorcosim argv``; every Python warning is made an error
    (a warning would be a stray line of text on the command line)."""
    err = io.StringIO()
    with warnings.catch_warnings(), redirect_stderr(err), redirect_stdout(io.StringIO()):
        warnings.simplefilter("error")
        try:
            rc = main(list(argv))
        except SystemExit as exc:   # argparse
            rc = exc.code
    return rc, [line for line in err.getvalue().splitlines() if line.strip()]


@pytest.fixture
def tmp(tmp_path, monkeypatch):
    """tmp_path, with the process's temporary folder inside it (so that a leftover extraction is seen)."""
    t = tmp_path / "systemtmp"
    t.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(t))
    return tmp_path


def refused(tmp: Path, argv: list[str], message: str | None = None, out: Path | None = None) -> str:
    rc, lines = cli(argv)
    text = "\n".join(lines)
    assert rc in (1, 2), f"exit {rc} for {argv}: {text}"
    assert len(lines) == 1, f"{len(lines)} lines for {argv}:\n{text}"
    assert "Traceback" not in text and "unexpected" not in text and "Warning" not in text, text
    if message is not None:
        assert re.search(message, lines[0]), lines[0]
    assert not list(tmp.rglob("*.part")), list(tmp.rglob("*.part"))
    assert list((tmp / "systemtmp").iterdir()) == [], "a temporary folder was left"
    if out is not None and out.exists():
        present = sorted(p.name for p in out.iterdir() if p.name != ".rotorcosim.lock")
        assert present == ["summary.json"], present
        assert '"status": "failed"' in (out / "summary.json").read_text()
    return lines[0]


# -- scenario files ----------------------------------------------------------------------------------------
#: every numeric key written in the toy scenario, as (table header, key); the values below are never numbers
NUMERIC_KEYS = [("[schedule]", k) for k in ("step", "thermal_step", "speed_rpm", "hold_cycles")] + [
    ("[outputs]", "record_step"),
    ("[components.node]", "parameters.C"), ("[components.node]", "parameters.R")]
NOT_NUMBERS = ["nan", "inf", "-inf", '"10"', "true", "[1, 2]", "{ a = 1 }", "1e999"]


def _set_key(text: str, header: str, key: str, value: str) -> str:
    if key.startswith("parameters."):
        name = key.split(".", 1)[1]
        new = re.sub(rf"\b{name} = [^,}}]+", f"{name} = {value}", text, count=1)
    else:
        new = re.sub(rf"(?m)^{key} = .*$", f"{key} = {value}", text, count=1)
    assert new != text, (header, key)
    return new


@pytest.mark.parametrize("value", NOT_NUMBERS)
@pytest.mark.parametrize("header, key", NUMERIC_KEYS)
def test_scenario_numbers_that_are_not(tmp, header, key, value):
    f = tmp / "s.toml"
    f.write_text(_set_key(TOY_TEXT, header, key, value))
    out = tmp / "o"
    line = refused(tmp, [*RUN, str(f), "--out", str(out)], out=out)
    assert str(f) in line or "s.toml" in line, line   # the file is named
    assert not out.exists()


#: case -> (scenario text, what the one line must say)
STRUCTURE = {
    "empty": ("", r"no components"),
    "binary": ("\x00\x01\x02garbage\xff", r"s\.toml:1: not valid TOML"),
    "truncated": (TOY_TEXT[: len(TOY_TEXT) // 2], r"s\.toml: not valid TOML"),
    "unknown table": (TOY_TEXT + "\n[shedule]\nstep = 1e-3\n", r"\[shedule\]: unknown table \(did you mean 'schedule'"),
    "duplicate key": (TOY_TEXT.replace("step = 1e-3", "step = 1e-3\nstep = 2e-3", 1), r"s\.toml:\d+: not valid TOML"),
    "extends a missing file": ('[scenario]\nextends = "nope.toml"\nname = "x"\n', r"nope\.toml not found"),
    "extends itself": ('[scenario]\nextends = "s.toml"\nname = "x"\n', r"'extends' loops back on itself"),
    "unknown implementation": (TOY_TEXT.replace("testing.thermal_node", "testing.thermal_nod"),
                               r"unknown component implementation 'testing\.thermal_nod'"),
    "implementation and fmu": (TOY_TEXT.replace('implementation = "testing.thermal_node"',
                                                'implementation = "testing.thermal_node"\nfmu = "x.fmu"'),
                               r"give exactly one of 'implementation'"),
    "missing fmu": (TOY_TEXT.replace('implementation = "testing.thermal_node"', 'fmu = "nowhere.fmu"'),
                    r"nowhere\.fmu not found"),
    "fmu is a folder": (TOY_TEXT.replace('implementation = "testing.thermal_node"', 'fmu = "."'),
                        r"is a folder, not an FMU file"),
    "unknown port": (TOY_TEXT.replace('from = "osc.P"', 'from = "osc.Power"'), r"has no output 'Power'"),
    "unknown component in a connection": (TOY_TEXT.replace('to = "node.P"', 'to = "nod.P"'),
                                          r"no component 'nod' \(did you mean 'node'"),
    "input used as an output": (TOY_TEXT.replace('from = "osc.P"', 'from = "osc.T"'),
                                r"osc\.T is an input of component 'osc'"),
    "dangling input": (TOY_TEXT.replace('from = "node.T"\nto = "osc.T"', 'from = "node.T"\nto = "node.P"'),
                       r"node\.T -> node\.P: units differ"),
    "unknown parameter": (TOY_TEXT.replace("C = 10.0", "Cap = 10.0"), r"has no parameter 'Cap'"),
    "negative record step": (TOY_TEXT.replace("record_step = 1e-3", "record_step = -1e-3"),
                             r"\[outputs\] record_step: must be a positive number"),
    "no intervals": (TOY_TEXT.replace("intervals = [", "intervals_ = ["),
                     r"intervals_: unknown key \(did you mean 'intervals'"),
    "hold window longer than every TM interval": (TOY_TEXT.replace("hold_cycles = 5", "hold_cycles = 1e12"),
                                                  r"\[schedule\] hold_cycles: .* could never fill"),
    "restart ramp that never ends": (TOY_TEXT.replace("hold_cycles = 5", "hold_cycles = 5\nrestart_cycles = 1e12"),
                                     r"\[schedule\] restart_cycles: 1e\+12 cycles"),
    "record an unknown signal": (TOY_TEXT.replace('"node.T"]', '"node.Tx"]'), r"unknown signal 'node\.Tx'"),
    "speed no step can sample": (TOY_TEXT.replace("speed_rpm = 2700.0", "speed_rpm = 1e12"),
                                 r"\[schedule\] speed_rpm: .* no cycle can be sampled"),
    "fractional hold window": (TOY_TEXT.replace("hold_cycles = 5", "hold_cycles = 2.5"),
                               r"\[schedule\] hold_cycles: must be a whole number of rotor cycles, got 2\.5"),
    "fractional result window": (TOY_TEXT.replace("[results]", "[results]\ncycles = 4.5"),
                                 r"\[results\] cycles: must be a whole number of rotor cycles, got 4\.5"),
    "auto hold window beyond tm_max": (TOY_TEXT.replace('kind = "timeline"', 'kind = "auto"').replace(
        "hold_cycles = 5", "hold_cycles = 1e308"), r"\[schedule\] hold_cycles: 1e\+308 cycles"),
    "coupling passes that hang": (TOY_TEXT.replace("[algorithm]", "[algorithm]\niterations = 1000000000000"),
                                  r"iterations must be within \[1, 1000\]"),
    "unknown schedule kind": (TOY_TEXT.replace('kind = "timeline"', 'kind = "staggered"'),
                              r"\[schedule\] kind: 'staggered' is not one of"),
    "unknown algorithm": (TOY_TEXT.replace('kind = "gauss-seidel"', 'kind = "gauss"'),
                          r"\[algorithm\] kind: 'gauss' is not one of"),
    "component named with a dot": (TOY_TEXT.replace("[components.node]", '[components."no.de"]'),
                                   r"component names must be non-empty and contain no '\.'"),
}


@pytest.mark.parametrize("case", sorted(STRUCTURE))
def test_scenario_structure(tmp, case):
    text, says = STRUCTURE[case]
    f = tmp / "s.toml"
    f.write_text(text)
    out = tmp / "o"
    line = refused(tmp, [*RUN, str(f), "--out", str(out)], out=out)
    assert re.search(says, line), line   # the problem is named, not only refused


def test_a_record_step_longer_than_the_run_records_its_first_sample(tmp):
    """Not a mistake (one sample per interval), but 1e308 overflowed the recorder's stride (exit 1, "unexpected")."""
    f = tmp / "s.toml"
    f.write_text(TOY_TEXT.replace("record_step = 1e-3", "record_step = 1e308"))
    rc, lines = cli([*RUN, str(f), "--out", str(tmp / "o")])
    assert rc == 0 and lines == [], lines
    import h5py

    with h5py.File(tmp / "o" / "timeseries.h5") as h:
        assert h["time"][()].tolist() == [0.0]


def test_scenario_paths(tmp):
    line = refused(tmp, [*RUN, str(tmp / "missing.toml"), "--out", str(tmp / "o")])
    assert re.search(r"missing\.toml not found", line), line
    line = refused(tmp, [*RUN, str(tmp), "--out", str(tmp / "o")])
    assert re.search(r"is a folder, not a TOML file", line), line
    (tmp / "x.ssp").write_text("not a zip")
    line = refused(tmp, [*RUN, str(tmp / "x.ssp"), "--out", str(tmp / "o")])
    assert re.search(r"x\.ssp is not a zip archive", line), line
    assert not (tmp / "o").exists()   # refused before any run: no output folder


# -- --set values ------------------------------------------------------------------------------------------
SET_VALUES = ["nan", "inf", "-inf", "abc", "true", "[1,2]", "", "1e999"]


@pytest.mark.parametrize("value", SET_VALUES)
@pytest.mark.parametrize("param", ["osc.m", "osc.k", "osc.max_substep", "node.C", "node.R", "node.Ta"])
def test_set_values(tmp, param, value):
    out = tmp / "o"
    line = refused(tmp, [*RUN, "toy_thermomechanical", "--set", f"{param}={value}", "--out", str(out)], out=out)
    assert param in line, line   # the parameter is named
    assert re.search(r"not a finite number|expected a number|expected 1 value|an empty value", line), line


@pytest.mark.parametrize("text, message", [
    ("osc", "expected COMP.PARAM=VALUE"), ("=1", "expected COMP.PARAM=VALUE"), ("nope.m=1", "nope"),
    ("osc.nope=1", "nope"), ("osc.m", "expected COMP.PARAM=VALUE"), ("node.T=300", "no parameter 'T'"),
    ("osc.m=-1", "osc.m"), ("osc.m=0", "osc.m"), ("osc.max_substep=0", "max_substep"),
])
def test_set_mistakes(tmp, text, message):
    out = tmp / "o"
    line = refused(tmp, [*RUN, "toy_thermomechanical", "--set", text, "--out", str(out)], out=out)
    assert re.search(message, line), line


def test_a_parameter_set_twice(tmp):
    """``--set node.C=10 --set node.C=20``: the last was taken without a word (sweep refused it already)."""
    out = tmp / "o"
    line = refused(tmp, [*RUN, "toy_thermomechanical", "--set", "node.C=10", "--set", "node.C=20", "--out", str(out)])
    assert "--set node.C is given twice (10 and 20): give it once" in line, line
    assert not out.exists()


# -- FMU and SSP archives ----------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def archives(tmp_path_factory):
    """The toy's node as an FMU and the toy system as an SSP archive (built once)."""
    from rotorcosim.fmus.export import export_component
    from rotorcosim.master.scenario.ssp import write_ssp
    from rotorcosim.master.scenario.build import load_scenario

    d = tmp_path_factory.mktemp("corpus_archives")
    fmu = export_component("testing.thermal_node", d / "node.fmu", instance_name="node",
                           parameters={"C": 10.0, "R": 1.0})
    ssp = write_ssp(load_scenario(TOY), d / "toy.ssp")
    return fmu, ssp


def _write(dst: Path, data: bytes) -> Path:
    dst.write_bytes(data)
    return dst


def _declared_huge(src: Path, dst: Path) -> Path:
    """``src`` plus a 10-byte entry whose headers declare 4 GB uncompressed (central directory and local header)."""
    import struct

    rebuild(src, dst, extra=[("resources/big.bin", b"0123456789")])
    data = bytearray(dst.read_bytes())
    name = b"resources/big.bin"
    for sig, offset in ((b"PK\x01\x02", 24), (b"PK\x03\x04", 22)):
        at = data.find(sig)
        while at >= 0:
            n = struct.unpack_from("<H", data, at + (28 if sig == b"PK\x01\x02" else 26))[0]
            start = at + (46 if sig == b"PK\x01\x02" else 30)
            if bytes(data[start:start + n]) == name:
                struct.pack_into("<I", data, at + offset, 0xFFFFFFF0)
            at = data.find(sig, at + 4)
    dst.write_bytes(bytes(data))
    return dst


def _md(fn):
    return lambda name, data: fn(data.decode()).encode() if name == "modelDescription.xml" else data


FMU_FAULTS = {
    "truncated": lambda src, dst: _write(dst, src.read_bytes()[: src.stat().st_size // 2]),
    "empty": lambda src, dst: _write(dst, b""),
    "not a zip": lambda src, dst: _write(dst, b"modelDescription.xml"),
    "zip slip": lambda src, dst: rebuild(src, dst, extra=[("../../escaped.txt", b"x")]),
    "absolute entry": lambda src, dst: rebuild(src, dst, extra=[("/tmp/absolute_corpus.txt", b"x")]),
    "zip bomb": lambda src, dst: rebuild(src, dst, extra=[("resources/zeros.bin", bytes(64 * 1024 ** 2))]),
    "huge declared size": _declared_huge,
    "no model description": lambda src, dst: rebuild(src, dst, lambda n, d: None if n == "modelDescription.xml"
                                                    else d),
    "garbage model description": lambda src, dst: rebuild(src, dst, _md(lambda t: "<fmiModelDescription")),
    "entity bomb": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(
        r"^(<\?xml[^>]*\?>)?", lambda m: (m.group(0) or "") + '<!DOCTYPE fmiModelDescription [<!ENTITY a '
        '"aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;">]>', t, count=1))),
    "FMI 4.0": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(r'fmiVersion="[^"]*"', 'fmiVersion="4.0"',
                                                                      t, count=1))),
    "FMI 2.0 labelled 1.0": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(
        r'fmiVersion="[^"]*"', 'fmiVersion="1.0"', t, count=1))),
    "no binaries": lambda src, dst: rebuild(src, dst, lambda n, d: None if n.startswith("binaries/") else d),
    "model exchange only": lambda src, dst: rebuild(src, dst, _md(lambda t: t.replace("<CoSimulation",
                                                                                     "<ModelExchange"))),
    # the binary is binaries/<platform>/<modelIdentifier>.so: a path there loaded a library outside the archive
    "model identifier climbing out": lambda src, dst: rebuild(src, dst, _md(lambda t: t.replace(
        'modelIdentifier="node"', 'modelIdentifier="../../../../lib/x86_64-linux-gnu/libc"'))),
    "model identifier absolute": lambda src, dst: rebuild(src, dst, _md(lambda t: t.replace(
        'modelIdentifier="node"', 'modelIdentifier="/lib/x86_64-linux-gnu/libc.so.6"'))),
    "no model identifier": lambda src, dst: rebuild(src, dst, _md(lambda t: t.replace('modelIdentifier="node" ', ""))),
    "no FMI version": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(r'fmiVersion="[^"]*" ', "", t,
                                                                             count=1))),
    "default step not a number": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(
        r'stepSize="[^"]*"', 'stepSize="abc"', t, count=1))),
    "default step zero": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(
        r'stepSize="[^"]*"', 'stepSize="0"', t, count=1))),
    # our vendor annotation: phases no interval steps, a step that is not one, module names it would purge
    "annotation phases unknown": lambda src, dst: rebuild(src, dst, _md(lambda t: t.replace('phases="TM,TO"',
                                                                                           'phases="XX"'))),
    "annotation phases empty": lambda src, dst: rebuild(src, dst, _md(lambda t: t.replace('phases="TM,TO"',
                                                                                         'phases=""'))),
    "annotation step not a number": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(
        r'preferredStep="[^"]*"', 'preferredStep="abc"', t))),
    "annotation step zero": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(
        r'preferredStep="[^"]*"', 'preferredStep="0"', t))),
    "annotation package not ours": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(
        r'package="[^"]*"', 'package="numpy"', t))),
    "annotation slave module not ours": lambda src, dst: rebuild(src, dst, _md(lambda t: re.sub(
        r'slaveModule="[^"]*"', 'slaveModule="rotorcosim"', t))),
}


#: what the line must say, for the faults that could otherwise be refused for another reason
FMU_SAYS = {
    "model identifier climbing out": "modelIdentifier '../../../../lib/x86_64-linux-gnu/libc' is not a file name",
    "model identifier absolute": "modelIdentifier '/lib/x86_64-linux-gnu/libc.so.6' is not a file name",
    "no model identifier": "modelIdentifier None is not a file name",
    "no FMI version": "gives no fmiVersion",
    "FMI 4.0": "FMI 4.0 FMU: rotorcosim imports FMI 1.0, 2.0 and 3.0 co-simulation FMUs",
    "FMI 2.0 labelled 1.0": "which FMI 1.0 requires",
    "default step not a number": "DefaultExperiment stepSize='abc' is not a positive number",
    "default step zero": "DefaultExperiment stepSize='0' is not a positive number",
    "annotation phases unknown": "phases='XX' must name one or both of TM, TO",
    "annotation phases empty": "phases='' must name one or both of TM, TO",
    "annotation step not a number": "preferredStep='abc' is not a positive number",
    "annotation step zero": "preferredStep='0' is not a positive number",
    "annotation package not ours": "package='numpy' is not a name rotorcosim gives its bundles",
    "annotation slave module not ours": "slaveModule='rotorcosim' is not a name rotorcosim gives its bundles",
}


@pytest.mark.parametrize("case", sorted(FMU_FAULTS))
def test_fmu_archives(tmp, archives, case):
    bad = FMU_FAULTS[case](archives[0], tmp / "bad.fmu")
    out = tmp / "o"
    line = refused(tmp, [*RUN, "toy_thermomechanical", "--swap", f"node={bad}", "--out", str(out)], out=out)
    assert "bad.fmu" in line, line   # the file is named
    assert FMU_SAYS.get(case, "") in line, line
    assert not (tmp.parent / "escaped.txt").exists() and not Path("/tmp/absolute_corpus.txt").exists()


def test_fmu_of_another_component(tmp, archives):
    """The node's FMU in the oscillator's place: its ports are not the oscillator's."""
    out = tmp / "o"
    line = refused(tmp, [*RUN, "toy_thermomechanical", "--swap", f"osc={archives[0]}", "--out", str(out)], out=out)
    assert re.search(r"osc\.P is an input of component 'osc' \(FMUComponent\)", line), line


def test_fmu_path_that_is_a_folder(tmp):
    """--swap with a folder named like an FMU (an unpacked FMU, say): named as a folder, not as 'not found'."""
    (tmp / "node.fmu").mkdir()
    out = tmp / "o"
    line = refused(tmp, [*RUN, "toy_thermomechanical", "--swap", f"node={tmp / 'node.fmu'}", "--out", str(out)])
    assert re.search(r"swap node: FMU file .*node\.fmu is a folder, not an FMU file", line), line
    assert not out.exists()


def _ssd(fn):
    return lambda name, data: fn(data.decode()).encode() if name == "SystemStructure.ssd" else data


SSP_FAULTS = {
    "truncated": lambda src, dst: _write(dst, src.read_bytes()[: src.stat().st_size // 2]),
    "not a zip": lambda src, dst: _write(dst, b"SystemStructure.ssd"),
    "zip slip": lambda src, dst: rebuild(src, dst, extra=[("../../escaped.txt", b"x")]),
    "no structure": lambda src, dst: rebuild(src, dst, lambda n, d: None if n == "SystemStructure.ssd" else d),
    "garbage structure": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t[: len(t) // 3])),
    "entity bomb": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t.replace(
        "<?xml version='1.0' encoding='UTF-8'?>", '<?xml version="1.0"?><!DOCTYPE x [<!ENTITY a "a">]>'))),
    "fmu outside": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t.replace('source="resources/node.fmu"',
                                                                             'source="../../node.fmu"'))),
    "fmu missing": lambda src, dst: rebuild(src, dst, lambda n, d: None if n == "resources/node.fmu" else d),
    "fmu corrupt": lambda src, dst: rebuild(src, dst, lambda n, d: d[:100] if n == "resources/node.fmu" else d),
    "parameter in an unknown unit": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t.replace(
        '<ssv:Real value="10.0" />', '<ssv:Real value="10.0" unit="furlong" />'))),
    "parameter in a unit of another quantity": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t.replace(
        '<ssv:Real value="10.0" />', '<ssv:Real value="10.0" unit="m" />'))),
    "parameter not a number": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t.replace(
        '<ssv:Real value="10.0" />', '<ssv:Real value="ten" />'))),
    "parameter file outside": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t.replace(
        '<ssd:ParameterBinding type="application/x-ssp-parameter-set">',
        '<ssd:ParameterBinding type="application/x-ssp-parameter-set" source="../../etc/passwd">'))),
    # two things said at once, where the reader took one without a word
    "parameter given twice": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t.replace(
        '<ssv:Parameter name="C">', '<ssv:Parameter name="C"><ssv:Real value="99.0" /></ssv:Parameter>'
        '<ssv:Parameter name="C">'))),
    "parameter with two values": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t.replace(
        '<ssv:Real value="10.0" />', '<ssv:Real value="10.0" /><ssv:Real value="20.0" />'))),
    "two scenario annotations": lambda src, dst: rebuild(src, dst, _ssd(lambda t: re.sub(
        r'(<ssc:Annotation type="org.rotorcosim.scenario">.*?</ssc:Annotation>)', r"\1\1", t, flags=re.S))),
    "connection settings without a connection": lambda src, dst: rebuild(src, dst, _ssd(lambda t: t.replace(
        '"connections": [', '"connections": [{"from": "node.T", "to": "osc.x"}, ', 1))),
    "an FMU inside with a bad annotation": lambda src, dst: rebuild(src, dst, lambda n, d: rebuild_bytes(
        d, _md(lambda t: t.replace('phases="TM,TO"', 'phases="XX"'))) if n == "resources/node.fmu" else d),
}


def rebuild_bytes(data: bytes, edit) -> bytes:
    """``rebuild`` of a zip held in memory (an FMU inside an SSP archive)."""
    with tempfile.TemporaryDirectory() as d:
        (Path(d) / "in.zip").write_bytes(data)
        return rebuild(Path(d) / "in.zip", Path(d) / "out.zip", edit).read_bytes()


@pytest.mark.parametrize("case", sorted(SSP_FAULTS))
def test_ssp_archives(tmp, archives, case):
    bad = SSP_FAULTS[case](archives[1], tmp / "bad.ssp")
    out = tmp / "o"
    line = refused(tmp, [*RUN, str(bad), "--out", str(out)], out=out)
    assert "bad.ssp" in line and "systemtmp" not in line, line   # the archive is named, not where it was unpacked
    assert not (tmp.parent / "escaped.txt").exists()


@pytest.mark.parametrize("value, says", [
    ('<ssv:Boolean value="true" />', "expected a number"), ('<ssv:String value="ten" />', "expected a number"),
    ('<ssv:Real value="-10.0" />', "must be > 0"), ('<ssv:Real value="nan" />', "not finite")])
def test_an_ssp_component_is_named_by_its_entry(tmp, archives, value, says):
    """An error found when an SSP's FMU is set up named the temporary folder it was unpacked into (gone once the
    command ends): "FMU /tmp/rcs_ssp_x/resources/node.fmu"; now the archive and the entry."""
    bad = rebuild(archives[1], tmp / "bad.ssp", _ssd(lambda t: t.replace('<ssv:Real value="10.0" />', value)))
    rc, lines = cli([*RUN, str(bad), "--out", str(tmp / "o")])
    assert rc == 2 and len(lines) == 1, lines
    assert f"FMU 'resources/node.fmu' in {bad} (component 'node')" in lines[0] and says in lines[0], lines[0]
    assert "systemtmp" not in lines[0], lines[0]


# -- checkpoints -------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def interrupted(tmp_path_factory):
    """A toy run interrupted at t = 0.2 s (a real SIGINT), leaving its checkpoint."""
    import signal

    from rotorcosim.master.observer.progress import Progress

    folder = tmp_path_factory.mktemp("corpus_ck") / "run"
    original = Progress.step
    fired = []

    def step(self, sim, t):
        if not fired and t >= 0.2:
            fired.append(t)
            os.kill(os.getpid(), signal.SIGINT)
        original(self, sim, t)

    Progress.step = step
    try:
        rc, _ = cli(["run", "toy_thermomechanical", "--quiet", "--duration", "0.3", "--out", str(folder)])
    finally:
        Progress.step = original
    assert rc == 130 and (folder / "checkpoint.pkl").exists()
    return folder


CHECKPOINT_FAULTS = {
    "truncated": lambda b: b[: len(b) // 2],
    "empty": lambda b: b"",
    "garbage": lambda b: os.urandom(4096),
    "text": lambda b: b"checkpoint",
}


@pytest.mark.parametrize("case", sorted(CHECKPOINT_FAULTS))
def test_damaged_checkpoints(tmp, interrupted, case):
    folder = tmp / "run"
    shutil.copytree(interrupted, folder)
    ck = folder / "checkpoint.pkl"
    ck.write_bytes(CHECKPOINT_FAULTS[case](ck.read_bytes()))
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    line = refused(tmp, ["run", "toy_thermomechanical", "--quiet", "--duration", "0.3", "--resume", "--out",
                         str(folder)])
    why = {"truncated": "truncated", "empty": "empty", "garbage": "not a checkpoint|damaged|truncated",
           "text": "not a checkpoint"}[case]
    assert re.search(f"is not a readable checkpoint \\(({why})", line), line
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before   # the folder as it was


@pytest.mark.parametrize("argv", [
    ["--duration", "0.3", "--set", "node.C=20"],          # another scenario's checkpoint
    ["--duration", "0.25"],                               # another schedule
    ["--unbalance", "50", "--duration", "0.3"],
    # fewer signals: the resumed file's osc.x went on to 301 rows while node.T and osc.P stayed at 257 (rc 0)
    ["--duration", "0.3", "--record", "osc.x"],
    ["--duration", "0.3", "--record", "osc.x,osc.P,node.T,osc.v"],
])
def test_checkpoint_of_another_run(tmp, interrupted, argv):
    folder = tmp / "run"
    shutil.copytree(interrupted, folder)
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    refused(tmp, ["run", "toy_thermomechanical", "--quiet", "--resume", *argv, "--out", str(folder)])
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before


# -- output places -----------------------------------------------------------------------------------------
@pytest.mark.parametrize("where", ["file", "under a file", "proc", "empty", "holds results", "holds other files"])
def test_output_places(tmp, where):
    f = tmp / "afile"
    f.write_text("x")
    out = {"file": f, "under a file": f / "sub", "proc": Path("/proc/rotorcosim_corpus"), "empty": ""}.get(where)
    if where == "holds results":
        out = tmp / "prev"
        out.mkdir()
        (out / "summary.json").write_text('{"status": "complete"}')
    if where == "holds other files":
        out = tmp / "mine"
        out.mkdir()
        (out / "thesis.tex").write_text("x")
    refused(tmp, [*RUN, "toy_thermomechanical", "--out", str(out)])
    assert f.read_text() == "x"
    if where == "holds other files":
        assert sorted(p.name for p in out.iterdir()) == ["thesis.tex"]


# -- number options of every command -----------------------------------------------------------------------
BAD_NUMBERS = ["nan", "inf", "-inf", "abc", ""]
OPTIONS = [
    (["run", "toy_thermomechanical", "--quiet", "--out", "{out}"],
     ["--duration", "--unbalance", "--checkpoint-every", "--step-timeout"]),
    (["sweep", "--scenario", "toy_thermomechanical", "--serial", "--quiet", "--out", "{out}", "--duration", "0.05"],
     ["--unbalance", "--workers"]),
    (["compare", "--quiet", "--out", "{out}"], ["--duration", "--unbalance", "--revolutions"]),
    (["critical-speeds"], ["--count", "--max-rpm", "--oil-temperature"]),
    (["bearing-static", "--bearing", "0"], ["--radial-load", "--axial-load", "--speed-rpm"]),
    (["thermal-steady", "--bearing", "0", "--sfd-power", "1"], ["--drag-power"]),
    (["thermal-steady", "--bearing", "0", "--drag-power", "1"], ["--sfd-power", "--rub-power", "--ambient"]),
]
#: inf is a meaning of --checkpoint-every (no checkpoint inside an interval), not a mistake
CASES = [(base, opt, v) for base, opts in OPTIONS for opt in opts for v in BAD_NUMBERS
         if (opt, v) != ("--checkpoint-every", "inf")]


@pytest.mark.parametrize("base, option, value", CASES, ids=[f"{b[0]} {o} {v!r}" for b, o, v in CASES])
def test_number_options(tmp, base, option, value):
    out = tmp / "o"
    argv = [a.replace("{out}", str(out)) for a in base] + [option, value]
    if base[0] == "bearing-static" and option != "--radial-load":
        argv += ["--radial-load", "1000"]
    refused(tmp, argv)
    assert not out.exists()


@pytest.mark.parametrize("argv, message", [
    (["damper-force", "--damper", "0", "--position", "1e-5", "0", "--velocity", "1e9", "0", "--temperature", "70"],
     "turbulent film"),
    (["damper-force", "--damper", "0", "--position", "1", "1", "--velocity", "0", "0", "--temperature", "70"],
     "positions are in metres"),
    (["damper-force", "--damper", "0", "--position", "nan", "0", "--velocity", "0", "0", "--temperature", "70"],
     "finite"),
    (["damper-force", "--damper", "0", "--position", "0", "0", "--velocity", "0", "0", "--temperature", "5000"],
     "viscosity fit"),
    (["thermal-steady", "--bearing", "0", "--drag-power", "1e12", "--sfd-power", "0"], "viscosity fit"),
    (["thermal-steady", "--bearing", "0", "--drag-power", "1", "--sfd-power", "0", "--ambient", "5000"],
     "oil supply"),
    (["bearing-static", "--bearing", "0", "--radial-load", "1e12"], None),
    (["compare", "--quiet", "--out", "{out}", "--revolutions", "nan"], "--revolutions must be a positive"),
    # 10**11 timings of the staggered run were accepted and ran until stopped
    (["compare", "--quiet", "--out", "{out}", "--timing-runs", "100000000000"], "fewer --timing-runs"),
    (["export-fmus", "", "--scenario", "toy_thermomechanical"], "output folder is empty"),
    (["critical-speeds", "--count", "0"], None),
    (["critical-speeds", "--count", "2.5"], None),
    (["run", "toy_thermomechanical", "--quiet", "--out", "{out}", "--duration", "1e308"], "steps"),
    (["run", "toy_thermomechanical", "--quiet", "--out", "{out}", "--schedule", "auto", "--tolerance", "1e308"],
     "tolerance"),
    (["sweep", "--scenario", "toy_thermomechanical", "--serial", "--out", "{out}", "--unbalance", "1,1"], None),
    (["sweep", "--scenario", "toy_thermomechanical", "--serial", "--out", "{out}", "--unbalance", "10",
      "--workers", "0"], None),
])
def test_absurd_or_malformed_values(tmp, argv, message):
    out = tmp / "o"
    refused(tmp, [a.replace("{out}", str(out)) for a in argv], message)
    assert not out.exists()


# -- tables of the wrong kind, in a file, in the file it extends, in one that extends it -------------------
#: a value that is not the table (or list) the key holds
WRONG_KINDS = {"int": "3", "string": '"x"', "list of tables": "[{ a = 1 }]", "boolean": "true"}
TOP_TABLES = ["components", "connections", "inputs", "algorithm", "schedule", "outputs", "results"]
EXTENDS_TOY = '[scenario]\nextends = "b.toml"\nname = "child"\n'


def _without(table: str) -> str:
    """The toy's text with ``table`` renamed out of the way (``[x...]``), so that a bare key can take its name."""
    if table == "components":
        return ""
    return TOY_TEXT.replace(f"[[{table}]]", f"[[x{table}]]").replace(f"[{table}]", f"[x{table}]")


@pytest.mark.parametrize("kind", sorted(WRONG_KINDS))
@pytest.mark.parametrize("table", TOP_TABLES)
@pytest.mark.parametrize("where", ["own", "base", "child"])
def test_tables_of_the_wrong_kind(tmp, table, kind, where):
    """``components = 3``, ``connections = true``, ``inputs = [{...}]`` ...: the composition of ``extends``
    looked into them before the schema did (an unexpected TypeError / AttributeError)."""
    bad = f"{table} = {WRONG_KINDS[kind]}\n"
    if where == "own":
        (tmp / "s.toml").write_text(bad + _without(table))
    elif where == "base":
        (tmp / "b.toml").write_text(bad + _without(table))
        (tmp / "s.toml").write_text(EXTENDS_TOY)
    else:
        (tmp / "b.toml").write_text(TOY_TEXT)
        (tmp / "s.toml").write_text(bad + EXTENDS_TOY)
    line = refused(tmp, [*RUN, str(tmp / "s.toml"), "--out", str(tmp / "o")], r"\.toml")
    # a file of the chain and the table are named, and nothing was run. (Where _without renamed the toy's own
    # table out of the way, the schema reports that [x<table>] first: the bad value itself is then reached only
    # by composition, which is what this test was written for.)
    assert ("b.toml" in line or "s.toml" in line) and table in line, line
    assert not (tmp / "o").exists() or not any((tmp / "o").glob("timeseries*")), line


@pytest.mark.parametrize("kind", sorted(WRONG_KINDS))
@pytest.mark.parametrize("where", ["own", "child"])
def test_parameters_of_the_wrong_kind(tmp, kind, where):
    """A component's ``parameters`` that is not a table, in a file or in one extending another (where they
    merge key by key): the file that wrote it is named."""
    if where == "own":
        (tmp / "s.toml").write_text(TOY_TEXT.replace("parameters = { C = 10.0, R = 1.0 }",
                                                     f"parameters = {WRONG_KINDS[kind]}"))
    else:
        (tmp / "b.toml").write_text(TOY_TEXT)
        (tmp / "s.toml").write_text(EXTENDS_TOY + f"[components.node]\nparameters = {WRONG_KINDS[kind]}\n")
    line = refused(tmp, [*RUN, str(tmp / "s.toml"), "--out", str(tmp / "o")])
    assert re.search(r"s\.toml(:\d+)?: \[components\.node\] parameters: must be a table", line), line


# -- TOML text as users write it (components/toml_text.py) -------------------------------------------------
DEEP = "[" * 5000 + "]" * 5000


def test_a_byte_order_mark_is_not_content(tmp):
    """Windows editors start UTF-8 files with a byte-order mark: "Invalid statement (at line 1, column 1)"."""
    (tmp / "s.toml").write_bytes(b"\xef\xbb\xbf" + TOY_TEXT.encode())
    rc, lines = cli([*RUN, str(tmp / "s.toml"), "--out", str(tmp / "o")])
    assert rc == 0 and lines == [], lines
    from rotorcosim.components.rotor import model

    (tmp / "engine.toml").write_bytes(b"\xef\xbb\xbf" + model.DEFAULT_FILE.read_bytes())
    assert model.load_data(tmp / "engine.toml")[0] == model.load_data()[0]


@pytest.mark.parametrize("what", ["scenario", "extended scenario", "model file", "--set", "sweep --set"])
def test_nesting_too_deep_to_read(tmp, what):
    """Arrays nested thousands deep were an unexpected RecursionError of the TOML parser."""
    out = tmp / "o"
    if what == "scenario":
        (tmp / "s.toml").write_text(f"a = {DEEP}\n")
        argv = [*RUN, str(tmp / "s.toml"), "--out", str(out)]
    elif what == "extended scenario":
        (tmp / "b.toml").write_text(f"a = {DEEP}\n")
        (tmp / "s.toml").write_text(EXTENDS_TOY)
        argv = [*RUN, str(tmp / "s.toml"), "--out", str(out)]
    elif what == "model file":
        (tmp / "m.toml").write_text(f"a = {DEEP}\n")
        argv = ["critical-speeds", "--model-file", str(tmp / "m.toml")]
    elif what == "--set":
        argv = [*RUN, "toy_thermomechanical", "--set", f"node.C={DEEP}", "--out", str(out)]
    else:
        argv = ["sweep", "--scenario", "toy_thermomechanical", "--serial", "--quiet", "--duration", "0.05",
                "--out", str(out), "--set", f"node.C=1,{DEEP}"]
    line = refused(tmp, argv)
    assert re.search(r"nested too deeply|node\.C", line), line
    assert not out.exists()


@pytest.mark.parametrize("what", ["scenario", "extends", "--swap fmu", "scenario fmu", "model file"])
def test_symbolic_link_loops(tmp, what):
    """A path that is a loop of symbolic links (Path.resolve raised RuntimeError: "unexpected")."""
    (tmp / "a.toml").symlink_to(tmp / "b.toml")
    (tmp / "b.toml").symlink_to(tmp / "a.toml")
    (tmp / "a.fmu").symlink_to(tmp / "b.fmu")
    (tmp / "b.fmu").symlink_to(tmp / "a.fmu")
    out = tmp / "o"
    argv = {"scenario": [*RUN, str(tmp / "a.toml"), "--out", str(out)],
            "extends": [*RUN, str(tmp / "s.toml"), "--out", str(out)],
            "--swap fmu": [*RUN, "toy_thermomechanical", "--swap", f"node={tmp / 'a.fmu'}", "--out", str(out)],
            "scenario fmu": [*RUN, str(tmp / "s.toml"), "--out", str(out)],
            "model file": ["critical-speeds", "--model-file", str(tmp / "a.toml")]}[what]
    (tmp / "s.toml").write_text(
        '[scenario]\nextends = "a.toml"\nname = "x"\n' if what == "extends"
        else TOY_TEXT.replace('implementation = "testing.thermal_node"', 'fmu = "a.fmu"'))
    line = refused(tmp, argv)
    assert re.search(r"[ab]\.(toml|fmu) (is a symbolic link to nothing|not found)|not found: .*[ab]\.toml", line), line
    assert not out.exists()


@pytest.mark.parametrize("value", ["10\nR = 5", "10\n[x]\ny = 1", "1e-3\nnode.R = 2"])
@pytest.mark.parametrize("command", ["run", "sweep"])
def test_a_set_value_is_one_value(tmp, command, value):
    """``--set node.C=$'10\\nR = 5'`` was read as TOML: C = 10 and the second key dropped without a word."""
    out = tmp / "o"
    argv = ([*RUN, "toy_thermomechanical", "--set", f"node.C={value}"] if command == "run" else
            ["sweep", "--scenario", "toy_thermomechanical", "--serial", "--quiet", "--duration", "0.05",
             "--set", f"node.C=2,{value}"]) + ["--out", str(out)]
    line = refused(tmp, argv)
    assert "is not one value" in line, line
    assert not out.exists()


@pytest.mark.parametrize("command", ["run", "sweep"])
def test_the_unbalance_given_twice(tmp, command):
    """``--unbalance 10 --set osc.F0=5`` (the toy's unbalance parameter): run kept 10, sweep ran 5 while its
    table said 10."""
    out = tmp / "o"
    argv = ([*RUN, "toy_thermomechanical", "--unbalance", "10", "--set", "osc.F0=5"] if command == "run" else
            ["sweep", "--scenario", "toy_thermomechanical", "--serial", "--quiet", "--duration", "0.05",
             "--unbalance", "10", "--set", "osc.F0=5,6"]) + ["--out", str(out)]
    line = refused(tmp, argv)
    assert "--unbalance and --set osc.F0=... both give the level (osc.F0" in line, line
    assert not out.exists()


def test_a_plugin_that_exits_at_import(tmp):
    """sys.exit() in a plug-in's module ended the command with its status and not a word."""
    (tmp / "quitter.py").write_text("import sys\nsys.exit(3)\n")
    (tmp / "s.toml").write_text(TOY_TEXT.replace('implementation = "testing.thermal_node"',
                                                 'implementation = "quitter:Node"'))
    line = refused(tmp, [*RUN, str(tmp / "s.toml"), "--out", str(tmp / "o")])
    assert "module 'quitter' called sys.exit(3) while imported" in line, line


def test_sweep_starts_no_more_workers_than_cases(tmp, monkeypatch):
    """``--workers 100000`` started processes for minutes, then failed inside Dask (unexpected AssertionError);
    the local cluster now has at most one worker per case."""
    import dask.distributed

    from rotorcosim.master.cli import sweep

    started = []

    class Cluster:
        def __init__(self, n_workers, **kw):
            started.append(n_workers)
            raise OSError("no cluster in this test")

    monkeypatch.setattr(dask.distributed, "LocalCluster", Cluster)
    with pytest.raises(OSError, match="no cluster in this test"):
        sweep.sweep([1.0, 2.0], tmp / "o", "toy_thermomechanical", duration=0.05, workers=100000)
    assert started == [2]


# -- integers beyond 64 bits -------------------------------------------------------------------------------
BIG = "1" + "0" * 400


@pytest.mark.parametrize("where", ["parameter", "parameter list", "step", "hold_cycles", "interval", "input",
                                   "record_step", "--set", "sweep --set", "model file"])
def test_integers_beyond_64_bits(tmp, where):
    """tomllib returns a 400-digit integer as a Python int, which overflowed every check comparing it as a float
    (unexpected OverflowError); TOML's integers are 64-bit."""
    out = tmp / "o"
    edits = {"parameter": ("C = 10.0", f"C = {BIG}"), "parameter list": ("C = 10.0", f"C = [{BIG}]"),
             "step": ("step = 1e-3\n", f"step = {BIG}\n"), "hold_cycles": ("hold_cycles = 5", f"hold_cycles = -{BIG}"),
             "interval": ('{ phase = "TM", duration = 0.3 }', f'{{ phase = "TM", duration = {BIG} }}'),
             "input": ("[outputs]", f'[inputs]\n"osc.T" = {BIG}\n\n[outputs]'),
             "record_step": ("record_step = 1e-3", f"record_step = {BIG}")}
    if where in edits:
        (tmp / "s.toml").write_text(TOY_TEXT.replace(*edits[where], 1))
        argv = [*RUN, str(tmp / "s.toml"), "--out", str(out)]
    elif where == "--set":
        argv = [*RUN, "toy_thermomechanical", "--set", f"node.C={BIG}", "--out", str(out)]
    elif where == "sweep --set":
        argv = ["sweep", "--scenario", "toy_thermomechanical", "--serial", "--quiet", "--duration", "0.05",
                "--out", str(out), "--set", f"node.C=1,{BIG}"]
    else:
        (tmp / "m.toml").write_text(f"n = {BIG}\n")
        argv = ["critical-speeds", "--model-file", str(tmp / "m.toml")]
    line = refused(tmp, argv)
    assert "(401 digits) is beyond 64 bits" in line, line
    assert not out.exists()


def test_64_bit_integers_are_read():
    from rotorcosim.components import toml_text

    assert toml_text.loads(f"a = {2**64 - 1}\nb = {-2**63}\nc = [[{2**63}]]") == {
        "a": 2**64 - 1, "b": -2**63, "c": [[2**63]]}


# -- relative file parameters ------------------------------------------------------------------------------
def test_a_relative_model_file_is_read_from_the_scenario_folder(tmp_path, monkeypatch):
    """``parameters = { model_file = "engine2.toml" }`` was opened from the working folder: run from elsewhere, a
    file of that name there was used without a word (or "not found"). Now from the folder of the scenario file
    that wrote it, as ``fmu = ...``; a --set / Scenario.set value from the working folder."""
    from rotorcosim.master.api import load_scenario

    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    (tmp_path / "a" / "base.toml").write_text(
        '[scenario]\nextends = "blade_loss_2850"\nname = "a"\n'
        '[components.rotor]\nparameters = { model_file = "engine2.toml" }\n')
    (tmp_path / "a" / "sub").mkdir()
    (tmp_path / "a" / "sub" / "child.toml").write_text('[scenario]\nextends = "../base.toml"\nname = "c"\n')
    monkeypatch.chdir(tmp_path / "b")
    for f in (tmp_path / "a" / "base.toml", tmp_path / "a" / "sub" / "child.toml"):
        sc = load_scenario(str(f))
        assert sc.components["rotor"].parameters["model_file"] == str(tmp_path / "a" / "engine2.toml")
    assert sc.set({"rotor.model_file": "mine.toml"}).components["rotor"].parameters["model_file"] == \
        str(tmp_path / "b" / "mine.toml")


# -- a sweep's folder --------------------------------------------------------------------------------------
SWEEP = ["sweep", "--scenario", "toy_thermomechanical", "--serial", "--quiet", "--duration", "0.05"]


def test_a_sweep_is_never_mixed_with_a_previous_one(tmp):
    """A second sweep into a folder left the first one's case folders beside its own and a sweep.csv listing
    only the new cases; now a non-empty --out is refused, --overwrite replaces a previous sweep's results (only a
    sweep's files and case folders of run files: anything else is never cleared)."""
    out = tmp / "s"
    assert cli([*SWEEP, "--unbalance", "1,2", "--out", str(out)])[0] == 0
    before = sorted(p.name for p in out.iterdir())
    line = refused(tmp, [*SWEEP, "--unbalance", "3", "--out", str(out)])
    assert "is not empty (level_1, level_2, sweep.csv, sweep.json): results are never mixed" in line, line
    assert sorted(p.name for p in out.iterdir()) == before
    assert cli([*SWEEP, "--unbalance", "3", "--out", str(out), "--overwrite"])[0] == 0
    # the toy has no case: no case tables beside the sweep's own files
    assert sorted(p.name for p in out.iterdir()) == ["level_3", "sweep.csv", "sweep.json"]
    (out / "level_3" / "notes.txt").write_text("mine")
    line = refused(tmp, [*SWEEP, "--unbalance", "4", "--out", str(out), "--overwrite"])
    assert "holds files that are not a sweep's results (level_3): not clearing it" in line, line
    assert (out / "level_3" / "notes.txt").read_text() == "mine"


@pytest.mark.parametrize("case", ["annotation phases unknown", "model identifier climbing out", "default step zero",
                                  "input of another quantity"])
def test_fmu_faults_in_their_own_process(tmp, archives, case):
    """With --fmu-process the FMU loads in a child process: a load that failed left the child to the garbage
    collector ("ResourceWarning: subprocess N is still running" on stderr when warnings show), and a system
    refused after loading (units) kept the child running until the command ended; now both are stopped and reaped
    at once. The one line still names the problem."""
    faults = dict(FMU_FAULTS)
    faults["input of another quantity"] = lambda src, dst: rebuild(src, dst, _md(lambda t: t.replace(
        '<Real unit="W" start="0" />', '<Real unit="K" start="0" />')))
    bad = faults[case](archives[0], tmp / "bad.fmu")
    before = _children()
    line = refused(tmp, [*RUN, "toy_thermomechanical", "--swap", f"node={bad}", "--fmu-process", "--out",
                         str(tmp / "o")], out=tmp / "o")
    assert FMU_SAYS.get(case, "units differ") in line, line
    assert _children() - before == set(), "the FMU's child process is still there (running or unreaped)"


def _children() -> set[int]:
    """This process's child processes, zombies included (Linux /proc)."""
    out = set()
    for task in Path(f"/proc/{os.getpid()}/task").iterdir():
        try:
            out |= {int(p) for p in (task / "children").read_text().split()}
        except OSError:
            pass
    return out


def test_a_shipped_name_that_is_also_a_folder_here(tmp, monkeypatch):
    """`rotorcosim run toy_thermomechanical --out toy_thermomechanical` a second time (with --overwrite) read the
    results folder as the scenario: "is a folder, not a TOML file". A folder is no scenario: the shipped one."""
    monkeypatch.chdir(tmp)
    argv = [*RUN, "toy_thermomechanical", "--out", "toy_thermomechanical"]
    assert cli(argv) == (0, [])
    assert cli([*argv, "--overwrite"]) == (0, [])
    (tmp / "sub" / "toy_thermomechanical").mkdir(parents=True)   # a path, not a name: still a folder
    line = refused(tmp, [*RUN, "sub/toy_thermomechanical", "--out", "o2"])
    assert "is a folder, not a TOML file" in line, line
