"""Imported FMUs of every FMI 2.0 / 3.0 type, against fmpy.simulate_fmu as the reference.

The test FMUs (models/types2.py with pythonfmu, models/types3.py with pythonfmu3, built once per session in
conftest.py) have ports of every type those tools can declare, a state whose start value the scenario sets, an
output computed at initialisation, and a stop request at ``t_stop``. Each run through our master is compared with
fmpy's run of the same FMU, value for value (exact equality), at every recorded time, t = 0 included.
"""
from __future__ import annotations

import json

import numpy as np
import pytest

from rotorcosim.fmus.importer import FMUError, load_fmu_component
from rotorcosim.master.scenario.build import build_simulation, build_system, parse
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.core.system import SystemError_

from tests.helpers.fmus import CaptureAll, model_description, with_model_description

#: a binary fraction: fmpy passes t_{k+1} - t_k as the step size, rotorcosim the nominal step; they are the same
#: number only when the step is exact in binary (with 0.1 they differ by an ulp, and so do the results, ~1e-16)
H = 0.125
PARAMS = {"gain": 3.0, "n": 2, "flag": True, "label": "a", "mode": 2}
START = {"x": 0.5}
INPUTS = {"u": 25.0, "ui": 4, "ub": False, "us": "b", "ue": 1}
INPUTS3 = {**INPUTS, "ul": -7, "uu": 5, "ua": [1.0, 2.0, 3.0]}


@pytest.fixture(params=["fmi2", "fmi3"])
def typed(request, types2_fmu, types3_fmu):
    if request.param == "fmi2":
        return types2_fmu, INPUTS
    return types3_fmu, INPUTS3


def _scenario(fmu, inputs, params=PARAMS, start=START):
    return parse({"components": {"f": {"fmu": str(fmu), "parameters": dict(params), "start": dict(start)}},
                  "inputs": {f"f.{k}": v for k, v in inputs.items()}})


def _run(sc, duration):
    cap = CaptureAll()
    sim = build_simulation(sc, [cap])
    try:
        report = sim.run(Timeline([Interval("TM", duration, H)]))
    finally:
        for c in sim.system.components.values():
            c.terminate()
    return cap, report, sim


def _fmpy(fmu, inputs, duration, params=PARAMS, start=START):
    """fmpy's run of the FMU. pythonfmu(3) FMUs carry a copy of pythonfmu(3) in their resources, which they import
    in this process from fmpy's temporary folder: the modules and sys.path entries they add are dropped after the
    run, or a later in-process export (fmus/export.py) would build with that copy (which has no binaries)."""
    import sys

    from fmpy import simulate_fmu

    path, modules = list(sys.path), set(sys.modules)
    try:
        return simulate_fmu(str(fmu), stop_time=duration, output_interval=H,
                            start_values={**params, **start, **inputs})
    finally:
        sys.path[:] = path
        for name in set(sys.modules) - modules:
            del sys.modules[name]


def _same_as_fmpy(cap, ref):
    """Every output fmpy records (it does not record strings) equal to ours at every time, t = 0 included."""
    np.testing.assert_array_equal(np.array(cap.t), ref["time"])
    names = [n for n in ref.dtype.names if n != "time"]
    assert len(names) >= 6
    for name in names:
        ours = cap.series(f"f.{name}")
        theirs = np.asarray(ref[name]).reshape(ours.shape)
        assert ours.dtype.kind == theirs.dtype.kind or {ours.dtype.kind, theirs.dtype.kind} <= {"i", "u"}, name
        np.testing.assert_array_equal(ours, theirs, err_msg=name)


def test_every_type_is_a_port(types2_fmu, types3_fmu):
    for fmu, extra in ((types2_fmu, {}), (types3_fmu, {"ul": ("Integer", "Int64", 1), "uu": ("Integer", "UInt64", 1),
                                                         "yu": ("Integer", "UInt64", 1),
                                                         "ua": ("Real", "Float64", 3), "ya": ("Real", "Float64", 3)})):
        c = load_fmu_component(fmu, "f")
        try:
            got = {v.name: (v.type, v.fmi_type, v.size) for v in c.variables}
            real, integer = ("Real", "Integer") if fmu is types2_fmu else ("Float64", "Int32")
            want = {"u": ("Real", real, 1), "ui": ("Integer", integer, 1), "ub": ("Boolean", "Boolean", 1),
                    "us": ("String", "String", 1), "ue": ("Integer", "Enumeration", 1),
                    "label": ("String", "String", 1), **extra}
            for name, w in want.items():
                assert got[name] == w, name
            assert c.variable("ue").choices == (1, 2, 3)
            assert c.variable("u").unit == "degC" and c.variable("u").unit_definition == ({"K": 1}, 1.0, 273.15)
            assert c.variable("y").unit_definition == ({"m": 1}, 0.001, 0.0)
            assert (c.variable("gain").min, c.variable("gain").max) == (0.0, 10.0)
        finally:
            c.terminate()


def test_matches_fmpy_exactly_at_every_time_from_t0(typed):
    fmu, inputs = typed
    cap, report, _ = _run(_scenario(fmu, inputs), 0.5)
    assert report.status == "complete"
    _same_as_fmpy(cap, _fmpy(fmu, inputs, 0.5))
    # the first row holds the outputs after initialisation: y0 = 2 x(0) with the scenario's start value of x
    assert cap.rows[0]["f.y0"][0] == 1.0 and cap.rows[0]["f.x"][0] == 0.5
    assert cap.rows[0]["f.y"][0] == 3.0 * 0.5 + 25.0
    # the types fmpy does not record, checked against the model's own formulas
    assert all(r["f.ys"][0] == "ab" for r in cap.rows)
    assert all(r["f.yi"][0] == 8 and r["f.yb"][0] for r in cap.rows)
    assert all(r["f.ye"][0] == 2 for r in cap.rows)
    if "uu" in inputs:   # UInt64 beyond 2^63, Int64 beyond 2^53: exact
        assert all(r["f.yu"][0] == 2**63 + 5 and r["f.yl"][0] == 2**40 - 7 for r in cap.rows)


def test_stop_request_ends_the_run_where_fmpy_ends_it(typed):
    fmu, inputs = typed
    params = {**PARAMS, "t_stop": 0.35}
    cap, report, sim = _run(_scenario(fmu, inputs, params), 1.0)
    ref = _fmpy(fmu, inputs, 1.0, params)
    _same_as_fmpy(cap, ref)
    # FMI 2 (pythonfmu): the step 0.25 -> 0.375 is discarded, the FMU stops at its last successful time 0.25;
    # FMI 3 (pythonfmu3): the step to 0.375 completes, then the FMU asks to terminate
    t_stop = 0.25 if fmu.name == "types2.fmu" else 0.375
    assert report.status == "stopped" and report.stopped["component"] == "f"
    assert report.stopped["t_s"] == pytest.approx(t_stop, abs=1e-12) and sim.t == report.t_end
    assert cap.t[-1] == pytest.approx(t_stop, abs=1e-12)


def test_stop_request_from_an_fmu_in_its_own_process(types3_fmu):
    """The same stop when the FMU runs in a process of its own (``process = true``, fmus/process.py)."""
    params = {**PARAMS, "t_stop": 0.35}
    sc = _scenario(types3_fmu, INPUTS3, params)
    sc.components["f"].options["process"] = True
    cap, report, sim = _run(sc, 1.0)
    assert type(sim.system.components["f"]).__name__ == "ProcessFMU"
    _same_as_fmpy(cap, _fmpy(types3_fmu, INPUTS3, 1.0, params))
    assert report.status == "stopped" and report.stopped["t_s"] == pytest.approx(0.375)


def test_stop_request_through_the_command_line(types3_fmu, tmp_path, capsys):
    from rotorcosim.master.cli import main

    toml = tmp_path / "stop.toml"
    inputs = "\n".join(f'"f.{k}" = {json.dumps(v)}' for k, v in INPUTS3.items())
    toml.write_text(f'''
[components.f]
fmu = "{types3_fmu}"
parameters = {{ t_stop = 0.25 }}
[inputs]
{inputs}
[schedule]
kind = "monolithic"
duration = 1.0
step = 0.1
[outputs]
record = ["f.x", "f.yu", "f.yb", "f.ys", "f.ya"]
record_step = 0.1
''')
    out = tmp_path / "out"
    assert main(["run", str(toml), "--out", str(out), "--quiet", "--no-figures"]) == 0
    printed = capsys.readouterr().out
    notice = [line for line in printed.splitlines() if "asked to stop" in line]
    assert len(notice) == 1 and "f asked to stop the simulation at t = 0.3 s" in notice[0]
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "stopped" and summary["error"] is None
    assert summary["stopped"]["component"] == "f" and summary["stopped"]["t_s"] == pytest.approx(0.3)
    import h5py

    with h5py.File(out / "timeseries.h5") as f:
        # 0, 0.1, 0.2 and 0.3, where the step that reached t_stop = 0.25 ended and the FMU asked to terminate
        assert f["time"][-1] == pytest.approx(0.3) and len(f["time"]) == 4
        assert f["f.yu"].dtype == np.uint64 and f["f.yu"][0, 0] == 2**63 + 5
        assert f["f.ys"][0, 0].decode() == "ab" and f["f.ya"].shape == (4, 3)


@pytest.mark.parametrize("key, value, why", [
    ("n", 7.9, r"expected an integer \(Int32|expected an integer \(Integer"),
    ("n", 6, r"6 is outside the range \[1, 5\]"),
    ("flag", 2, r"expected a Boolean \(true/false, or 0/1\), got 2"),
    ("gain", 11.0, r"11.0 is outside the declared range \[0, 10\]"),
    ("mode", 4, r"4 is outside the range \[1, 3\]"),
    ("label", 3, "expected a string"),
])
def test_parameters_checked_against_type_and_range(typed, key, value, why):
    fmu, _ = typed
    with pytest.raises(FMUError, match=why):
        load_fmu_component(fmu, "f", {key: value})


@pytest.mark.parametrize("ref, value, why", [
    ("f.ui", 1.5, "expected an integer"),
    ("f.ub", 2, "expected a Boolean"),
    ("f.ue", 7, r"outside the range \[1, 3\]"),
    ("f.u", True, "expected a number"),
])
def test_constant_inputs_checked_against_type_and_range(types3_fmu, ref, value, why):
    with pytest.raises(SystemError_, match=rf"constant input {ref}: .*{why}"):
        build_system(_scenario(types3_fmu, {**INPUTS3, ref[2:]: value}))


def test_start_values_checked(types2_fmu):
    with pytest.raises(FMUError, match=r"'y' .*initial calculated.*no start value to set"):
        load_fmu_component(types2_fmu, "f", start_values={"y": 1.0})
    with pytest.raises(FMUError, match=r"'gain' is a parameter"):
        load_fmu_component(types2_fmu, "f", start_values={"gain": 1.0})
    with pytest.raises(FMUError, match=r"'nothing': no such variable.*'x'.*expected a number"):
        load_fmu_component(types2_fmu, "f", start_values={"nothing": 1.0, "x": "one"})
    with pytest.raises(Exception, match="'start' sets start values of an FMU"):
        parse({"components": {"m": {"implementation": "testing.mass", "start": {"x": 1.0}}}})


def _pair(fmu, src, dst, **con):
    """Component a (testing.mass, or the FMU) -> the FMU b, one connection plus constants for b's other inputs."""
    inputs = {f"b.{k}": v for k, v in INPUTS3.items() if f"b.{k}" != dst}
    return parse({
        "components": {"a": {"fmu": str(fmu)}, "b": {"fmu": str(fmu), "parameters": {"n": 1}}},
        "connections": [{"from": src, "to": dst, **con}],
        "inputs": {**inputs, **{f"a.{k}": v for k, v in INPUTS3.items()}},
    })


@pytest.mark.parametrize("src, dst, con, why", [
    ("a.x", "b.ui", {}, r'a Float64 output into an Int32 input needs an explicit conversion: add convert = "round"'),
    ("a.x", "b.ub", {}, r'needs an explicit conversion: add convert = "nonzero"'),
    ("a.yb", "b.u", {"unit": "degC"}, r'add convert = "float"'),
    ("a.yl", "b.ul", {"convert": "round"}, r'convert \'round\' does not apply to Integer -> Integer'),
    ("a.yu", "b.ul", {}, r"do not all fit the input"),
    ("a.yl", "b.u", {"unit": "degC"}, r"values beyond 2\^53 would be rounded"),
    ("a.ys", "b.ui", {}, "strings convert to nothing"),
    ("a.yi", "b.ue", {}, "and its enumeration items"),
    ("a.x", "b.u", {}, r'a.x has no unit and the other side is in \[degC\]: .*unit = "degC"'),
    ("a.y", "b.u", {}, r"units differ, \[mm\] \(m\) -> \[degC\] \(K\), in dimension"),
    ("a.ya", "b.u", {}, r"sizes differ"),
])
def test_typed_connections_refused_without_conversion(types3_fmu, src, dst, con, why):
    with pytest.raises(SystemError_, match=why):
        build_system(_pair(types3_fmu, src, dst, **con))


def test_conversions_and_units_on_connections(types3_fmu):
    """What arrives through converting connections: Real [mm] -> Integer with convert = "round" (the unit-less
    Integer side declared in mm), Int32 -> Int64, Boolean, String, arrays as they are, and a.x (no unit)
    declared in K by the connection's unit -> b.u in degC."""
    cons = [{"from": "a.y", "to": "b.ui", "convert": "round", "unit": "mm"}, {"from": "a.yi", "to": "b.ul"},
            {"from": "a.yb", "to": "b.ub"}, {"from": "a.ys", "to": "b.us"}, {"from": "a.ya", "to": "b.ua"},
            {"from": "a.x", "to": "b.u", "unit": "K"}]
    sc = parse({"components": {"a": {"fmu": str(types3_fmu), "parameters": {"gain": 4.5}},
                               "b": {"fmu": str(types3_fmu)}},
                "connections": cons,
                "inputs": {**{f"a.{k}": v for k, v in INPUTS3.items()}, "b.uu": 0, "b.ue": 1}})
    cap, report, sim = _run(sc, 0.2)
    b = sim.system.components["b"]
    assert report.status == "complete"
    # b's inputs are a's outputs of the last step, converted (Gauss-Seidel: a steps first)
    last = cap.rows[-1]
    y = last["a.y"][0]
    assert y != np.floor(y) and b.u["ui"].tolist() == [int(np.floor(abs(y) + 0.5))] and b.u["ui"].dtype == np.int64
    assert b.u["ul"].tolist() == last["a.yi"].tolist()
    assert b.u["ub"].tolist() == last["a.yb"].tolist() and b.u["us"].tolist() == ["ab"]
    assert b.u["ua"].tolist() == last["a.ya"].tolist()
    assert b.u["u"][0] == pytest.approx(last["a.x"][0] - 273.15, abs=1e-12)
    # and what b computed from them: yi = n * ui with the rounded value
    assert last["b.yi"][0] == 3 * int(np.floor(abs(y) + 0.5))


def test_unconnected_binary_ports_do_not_block_and_connected_ones_are_refused(types3_fmu, tmp_path):
    xml = model_description(types3_fmu).replace(
        "</ModelVariables>",
        '<Binary name="blob_in" valueReference="90" causality="input" variability="discrete"><Start value="0a"/>'
        '</Binary><Binary name="blob" valueReference="91" causality="output" variability="discrete" '
        'initial="exact"><Start value="0b"/></Binary><Clock name="tick" valueReference="92" causality="input" '
        'variability="discrete" intervalVariability="triggered"/></ModelVariables>')
    fmu = with_model_description(types3_fmu, tmp_path / "binary.fmu", xml)
    sc = _scenario(fmu, INPUTS3)
    cap, report, _ = _run(sc, 0.2)            # blob_in unconnected, blob unread: the FMU runs
    assert report.status == "complete" and "f.blob" not in cap.rows[0]
    assert _run(_scenario(fmu, INPUTS3), 0.2)[0].rows[-1]["f.x"] == cap.rows[-1]["f.x"]
    with pytest.raises(SystemError_, match="a.blob is a Binary port; rotorcosim does not carry Binary values"):
        build_system(_pair(fmu, "a.blob", "b.blob_in"))
    with pytest.raises(SystemError_, match="b.tick is a Clock port; rotorcosim does not carry Clock values"):
        build_system(_pair(fmu, "a.x", "b.tick"))
    with pytest.raises(SystemError_, match="constant input f.tick: a Clock variable cannot be given a value"):
        build_system(_scenario(fmu, {**INPUTS3, "tick": 1}))


def test_every_problem_named_at_once(types2_fmu, tmp_path):
    xml = model_description(types2_fmu).replace(
        "</ModelVariables>",
        '<ScalarVariable name="v[1]" valueReference="90" causality="output"><Real/></ScalarVariable>'
        '<ScalarVariable name="v[2]" valueReference="91" causality="output"><Integer/></ScalarVariable>'
        '<ScalarVariable name="w[1]" valueReference="92" causality="output"><Real unit="mm"/></ScalarVariable>'
        '<ScalarVariable name="w[2]" valueReference="93" causality="output"><Real unit="degC"/></ScalarVariable>'
        '</ModelVariables>')
    fmu = with_model_description(types2_fmu, tmp_path / "bad.fmu", xml)
    with pytest.raises(FMUError, match=r"elements of 'v' differ in type.*; the elements of 'w' have different units"):
        load_fmu_component(fmu, "f")


def test_scheduled_execution_only_has_its_own_message(types3_fmu, tmp_path):
    import re

    xml = re.sub(r"<CoSimulation [^>]*/>", '<ScheduledExecution modelIdentifier="types3"/>',
                 model_description(types3_fmu))
    fmu = with_model_description(types3_fmu, tmp_path / "se.fmu", xml)
    with pytest.raises(FMUError, match="scheduled execution only .neither co-simulation nor model exchange"):
        load_fmu_component(fmu, "f")


W_INPUTS = {"f32_in": 0.1, "i8_in": -100, "u8_in": 254, "i16_in": -32767, "u16_in": 30000, "u32_in": 294967295}


@pytest.mark.parametrize("t_stop, t_end", [(10.0, 0.5), (0.2, 0.25)])
def test_every_integer_width_and_float32_match_fmpy(widths3_fmu, t_stop, t_end):
    """Float32 (scalar and array), Int8, UInt8, Int16, UInt16, UInt32 at their range limits, a Binary output
    left unread, a parameter at its declared minimum, a state's start value; and the stop at the end of the
    step that reaches t_stop."""
    params, start = {"k": -5, "t_stop": t_stop}, {"x": 0.5}
    cap, report, _ = _run(_scenario(widths3_fmu, W_INPUTS, params, start), 0.5)
    _same_as_fmpy(cap, _fmpy(widths3_fmu, W_INPUTS, 0.5, params, start))
    assert report.status == ("complete" if t_stop > 1 else "stopped") and cap.t[-1] == pytest.approx(t_end)
    row = cap.rows[0]
    assert (row["f.i8"][0], row["f.u8"][0], row["f.i16"][0], row["f.u16"][0], row["f.u32"][0]) == \
        (-95, 255, 32767, 60000, 2**32 - 1)
    assert row["f.f32"][0] == np.float32(np.float32(1.5) * np.float32(0.1) + np.float32(0.5))
    assert "f.blob" not in row


@pytest.mark.parametrize("where, value, why", [
    ("parameters", {"k": 6}, r"6 is outside the range \[-5, 5\]"),
    ("inputs", {"f.i8_in": 200}, r"200 is outside the range \[-128, 127\] of Int8"),
    ("inputs", {"f.u32_in": -1}, r"-1 is outside the range \[0, 4294967295\] of UInt32"),
    ("inputs", {"f.f32_in": 1e39}, "outside the range of Float32"),
])
def test_width_ranges_checked(widths3_fmu, where, value, why):
    inputs = {f"f.{k}": v for k, v in W_INPUTS.items()}
    spec = {"fmu": str(widths3_fmu)}
    if where == "parameters":
        spec["parameters"] = value
    else:
        inputs.update(value)
    with pytest.raises((FMUError, SystemError_), match=why):
        build_system(parse({"components": {"f": spec}, "inputs": inputs}))


def test_integer_widths_connect_only_where_the_values_fit(widths3_fmu):
    def pair(src, dst, **con):
        inputs = {f"{c}.{k}": v for c in "ab" for k, v in W_INPUTS.items() if f"{c}.{k}" != dst}
        return parse({"components": {"a": {"fmu": str(widths3_fmu)}, "b": {"fmu": str(widths3_fmu)}},
                      "connections": [{"from": src, "to": dst, **con}], "inputs": inputs})

    build_system(pair("a.u8", "b.i16_in"))                     # UInt8 fits Int16
    build_system(pair("a.x", "b.f32_in"))                      # Float64 -> Float32: Real to Real
    with pytest.raises(SystemError_, match=r"a\.i16 -> b\.i8_in: .*\[-32768, 32767\] do not all fit the input "
                                           r"\[-128, 127\]"):
        build_system(pair("a.i16", "b.i8_in"))
    sc = pair("a.i16", "b.i8_in", convert="clip")
    cap, report, sim = _run(sc, 0.2)
    assert sim.system.components["b"].u["i8_in"].tolist() == [127]       # 32767 saturated
    with pytest.raises(SystemError_, match="a.blob is a Binary port"):
        build_system(pair("a.blob", "b.u8_in"))
