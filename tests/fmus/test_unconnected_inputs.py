"""FMU inputs left unconnected keep the FMU's declared start values, as fmpy, Ecos and OMSimulator run them.

The reference is fmpy's ``simulate_fmu`` given no input at all (the FMU then runs from the values its model
description declares): every output fmpy records must equal ours at every recorded time, t = 0 included, for
FMI 3.0 models after the Modelica Reference FMUs Feedthrough (an input of every FMI 3.0 type), StateSpace
(structural parameters, array ports) and Roberts (a stiff system, its archive holding an entry twice with the
same bytes), built here from models/reference3 with the C compiler, and for the FMI 2.0 / 3.0 type FMUs of
conftest.py. The Reference FMUs themselves are run by test_reference_fmus.py where their sources are at hand.
"""
from __future__ import annotations

import dataclasses
import re
import sys
import zipfile

import numpy as np
import pytest

from rotorcosim.components.contract import ContractError
from rotorcosim.fmus.importer import load_fmu_component
from rotorcosim.master.scenario.build import build_simulation, build_system, load_scenario, parse
from rotorcosim.master.scenario.schema import SchemaError
from rotorcosim.master.schedule import Interval, Timeline

from tests.helpers.fmus import CaptureAll, model_description, with_model_description

#: a binary fraction: fmpy passes t_{k+1} - t_k as the step size, rotorcosim the nominal step (test_import_types.py)
H = 0.125
DURATION = 0.5


def run_alone(fmu, params=None, scenario=None, duration=DURATION, h=H):
    """Our run of the FMU as the only component, none of its inputs connected or given: (capture, report)."""
    sc = parse({"scenario": dict(scenario or {}), "components": {"f": {"fmu": str(fmu), "parameters": params or {}}}})
    cap = CaptureAll()
    sim = build_simulation(sc, [cap])
    try:
        report = sim.run(Timeline([Interval("TM", duration, h)]))
    finally:
        for c in sim.system.components.values():
            c.terminate()
    return cap, report


def fmpy_alone(fmu, params=None, duration=DURATION, h=H):
    """fmpy's run with no input given (pythonfmu FMUs' modules, imported from fmpy's folder, dropped after)."""
    from fmpy import simulate_fmu

    path, modules = list(sys.path), set(sys.modules)
    try:
        return simulate_fmu(str(fmu), start_time=0.0, stop_time=duration, output_interval=h,
                            start_values=dict(params or {}))
    finally:
        sys.path[:] = path
        for name in set(sys.modules) - modules:
            del sys.modules[name]


def assert_same_as_fmpy(cap, ref, at_least: int):
    np.testing.assert_array_equal(np.array(cap.t), ref["time"])
    names = [n for n in ref.dtype.names if n != "time"]
    assert len(names) >= at_least
    for name in names:
        ours = cap.series(f"f.{name}")
        theirs = np.asarray(ref[name]).reshape(ours.shape)
        np.testing.assert_array_equal(ours, theirs, err_msg=name)


def defaulted_lines(capsys) -> list[str]:
    return [line for line in capsys.readouterr().err.splitlines() if "keep their start values" in line]


FEEDTHROUGH_STARTS = {"Float32_continuous_input": 0.5, "Float32_discrete_input": -1.25,
                      "Float64_continuous_input": 1.5, "Float64_discrete_input": 2.5, "Int8_input": -3,
                      "UInt8_input": 200, "Int16_input": -300, "UInt16_input": 60000, "Int32_input": -70000,
                      "UInt32_input": 4000000000, "Int64_input": -5000000000, "UInt64_input": 10**19,
                      "Boolean_input": True, "String_input": "Set me!", "Enumeration_input": 2,
                      "Float64_vector_input": [1.0, 2.0, 3.0]}


@pytest.mark.parametrize("name, outputs", [("feedthrough3", 16), ("statespace3", 1), ("roberts3", 3)])
def test_reference_like_fmus_equal_fmpy_sample_for_sample(reference3_fmus, name, outputs, capsys):
    fmu = reference3_fmus[name]
    cap, report = run_alone(fmu)
    assert report.status == "complete"
    assert_same_as_fmpy(cap, fmpy_alone(fmu), outputs)
    lines = defaulted_lines(capsys)
    if name == "roberts3":   # no inputs: nothing to say
        assert lines == []
        return
    assert len(lines) == 1 and 'unconnected_inputs = "error"' in lines[0]
    if name == "statespace3":
        assert "f.u = [1.0, 2.0, 3.0]" in lines[0]
        return
    for port, value in FEEDTHROUGH_STARTS.items():   # every carried input, with its start value
        assert f"f.{port} = {value!r}" in lines[0], port
    assert "Binary_input" not in lines[0]            # not carried: it stays the FMU's own
    # the outputs repeat the inputs: the declared start values reached the FMU (not zeros)
    last = cap.rows[-1]
    assert last["f.UInt64_output"][0] == 10**19 and last["f.Int64_output"][0] == -5000000000
    assert last["f.String_output"][0] == "Set me!" and last["f.Float32_discrete_output"][0] == np.float32(-1.25)
    # x' = 2 u - x with u = 1.5 by Euler steps of H from 0
    x = 0.0
    for _ in range(4):
        x += H * (2.0 * 1.5 - x)
    assert last["f.x"][0] == x


def test_fmi2_and_fmi3_inputs_of_every_type_left_unconnected(types2_fmu, types3_fmu, widths3_fmu, capsys):
    """FMI 2.0 Real, Integer, Boolean, String, Enumeration (pythonfmu); FMI 3.0 Float64 (scalar and array),
    Int32, Int64, UInt64, Boolean, String, Enumeration (pythonfmu3); Float32, Int8, UInt8, Int16, UInt16, UInt32
    (C): all unconnected, equal to fmpy's run without inputs."""
    for fmu, inputs in ((types2_fmu, ("u", "ui", "ub", "us", "ue")),
                        (types3_fmu, ("u", "ui", "ul", "uu", "ub", "us", "ue", "ua")),
                        (widths3_fmu, ("f32_in", "i8_in", "u8_in", "i16_in", "u16_in", "u32_in"))):
        cap, report = run_alone(fmu)
        assert report.status == "complete", fmu
        assert_same_as_fmpy(cap, fmpy_alone(fmu), 6)
        lines = defaulted_lines(capsys)
        assert len(lines) == 1
        assert set(re.findall(r"f\.(\w+) =", lines[0])) == set(inputs), fmu


def test_the_scenario_option_refuses_them(reference3_fmus, tmp_path):
    fmu = reference3_fmus["statespace3"]
    with pytest.raises(ContractError, match=r'inputs left unconnected \(unconnected_inputs = "error": connect them '
                                            r'or give a constant under \[inputs\]\): f\.u'):
        run_alone(fmu, scenario={"unconnected_inputs": "error"})
    # given a constant, the input is no longer unconnected
    sc = parse({"scenario": {"unconnected_inputs": "error"}, "components": {"f": {"fmu": str(fmu)}},
                "inputs": {"f.u": [0.0, 0.0, 0.0]}})
    system = build_system(sc)
    try:
        assert system.defaulted == {}
    finally:
        for c in system.components.values():
            c.terminate()
    # a base scenario's choice holds in the scenarios that extend it
    (tmp_path / "base.toml").write_text(f'[scenario]\nunconnected_inputs = "error"\n[components.f]\nfmu = "{fmu}"\n')
    (tmp_path / "child.toml").write_text('[scenario]\nextends = "base.toml"\nname = "child"\n')
    with pytest.raises(ContractError, match=r"inputs left unconnected .*f\.u"):
        build_system(load_scenario(tmp_path / "child.toml"))
    with pytest.raises(SchemaError, match=r"unconnected_inputs.*'never' is not one of 'start', 'error'"):
        parse({"scenario": {"unconnected_inputs": "never"}, "components": {"f": {"fmu": str(fmu)}}})


def test_an_input_without_start_value_is_named(reference3_fmus, tmp_path):
    src = reference3_fmus["feedthrough3"]
    xml = model_description(src).replace('<Int8 name="Int8_input" valueReference="11" causality="input" start="-3"/>',
                                         '<Int8 name="Int8_input" valueReference="11" causality="input"/>')
    assert 'name="Int8_input" valueReference="11" causality="input"/>' in xml
    fmu = with_model_description(src, tmp_path / "nostart.fmu", xml)
    c = load_fmu_component(fmu, "f")
    try:
        assert not c.variable("Int8_input").has_default and c.variable("Int16_input").has_default
    finally:
        c.terminate()
    with pytest.raises(ContractError, match=r"inputs left unconnected \(.*they declare no default to keep \(an FMU "
                                            r"input's is its start value\)\): f\.Int8_input$"):
        run_alone(fmu)
    sc = parse({"components": {"f": {"fmu": str(fmu)}}, "inputs": {"f.Int8_input": 7}})
    system = build_system(sc)
    try:
        assert "f.Int8_input" not in system.defaulted and "f.Int16_input" in system.defaulted
    finally:
        for comp in system.components.values():
            comp.terminate()


def test_native_inputs_stay_required_unless_they_declare_a_default(tmp_path, capsys):
    """components/testing/gauge.py, as a plug-in: ``bias`` declares a default, ``F`` does not."""
    impl = "rotorcosim.components.testing.gauge:Gauge"
    (tmp_path / "s.toml").write_text(f'[components.g]\nimplementation = "{impl}"\n')
    with pytest.raises(ContractError, match=r"inputs left unconnected .*: g\.F \("):
        build_system(load_scenario(tmp_path / "s.toml"))
    (tmp_path / "s.toml").write_text(f'[components.g]\nimplementation = "{impl}"\n[inputs]\n"g.F" = 1.0\n')
    cap = CaptureAll()
    sim = build_simulation(load_scenario(tmp_path / "s.toml"), [cap])
    sim.run(Timeline([Interval("TM", 0.01, 0.01)]))
    assert cap.rows[-1]["g.y"][0] == 3.0                     # F = 1 given, bias = 2 kept
    lines = defaulted_lines(capsys)
    assert len(lines) == 1 and "g.bias = 2.0" in lines[0] and "g.F" not in lines[0]


def test_our_exported_fmus_keep_the_native_rule(mass_fmu, tmp_path):
    """An FMU exported by rotorcosim declares a start for every input (FMI asks for one), yet its inputs stay as
    required as the native component's; those its component declares with a default are named in the vendor
    annotation (``defaultInputs``) and may stay unconnected."""
    c = load_fmu_component(mass_fmu, "m")
    try:
        assert not c.variable("F").has_default
    finally:
        c.terminate()
    with pytest.raises(ContractError, match=r"inputs left unconnected .*: m\.F"):
        build_system(parse({"components": {"m": {"fmu": str(mass_fmu)}}}))
    xml = model_description(mass_fmu)
    assert "defaultInputs" not in xml
    marked = with_model_description(mass_fmu, tmp_path / "marked.fmu",
                                    xml.replace('errorVariable=', 'defaultInputs="F" errorVariable=', 1))
    c = load_fmu_component(marked, "m")
    try:
        assert c.variable("F").has_default
    finally:
        c.terminate()


def test_in_a_process_of_its_own_and_through_an_ssp_archive(reference3_fmus, tmp_path):
    """The FMU behind ``process = true`` keeps its start values the same way; an SSP archive carries the strict
    option (and leaves it out when it is the default)."""
    from rotorcosim.master.scenario.ssp import read_ssp, write_ssp

    fmu = reference3_fmus["statespace3"]
    sc = parse({"components": {"f": {"fmu": str(fmu), "process": True}}})
    cap = CaptureAll()
    sim = build_simulation(sc, [cap])
    try:
        assert sim.system.defaulted.keys() == {"f.u"}
        sim.run(Timeline([Interval("TM", DURATION, H)]))
    finally:
        for c in sim.system.components.values():
            c.terminate()
    assert_same_as_fmpy(cap, fmpy_alone(fmu), 1)
    strict = parse({"scenario": {"name": "strict", "unconnected_inputs": "error"},
                    "components": {"f": {"fmu": str(fmu)}}})
    back = read_ssp(write_ssp(strict, tmp_path / "strict.ssp"))
    assert back.unconnected_inputs == "error"
    with pytest.raises(ContractError, match=r'unconnected_inputs = "error".*f\.u'):
        build_system(back)
    lenient = write_ssp(dataclasses.replace(strict, unconnected_inputs="start"), tmp_path / "lenient.ssp")
    assert read_ssp(lenient).unconnected_inputs == "start"
    with zipfile.ZipFile(lenient) as zf:
        assert b"unconnected_inputs" not in zf.read("SystemStructure.ssd")


def test_a_regrouped_fmi2_input_keeps_its_start_only_when_every_element_declares_one():
    """``X[1]``, ``X[2]`` form one port: it may stay unconnected only when both declare a start value."""
    import io

    from fmpy import read_model_description

    from rotorcosim.fmus.description import _zip_of, ports_of

    def port(second: str):
        xml = f'''<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="m" guid="{{0}}">
  <CoSimulation modelIdentifier="m"/>
  <ModelVariables>
    <ScalarVariable name="X[1]" valueReference="1" causality="input" variability="continuous"><Real start="1"/></ScalarVariable>
    <ScalarVariable name="X[2]" valueReference="2" causality="input" variability="continuous"><Real {second}/></ScalarVariable>
  </ModelVariables>
  <ModelStructure/>
</fmiModelDescription>'''
        md = read_model_description(io.BytesIO(_zip_of({"modelDescription.xml": xml.encode()})), validate=False)
        (x,), _ = ports_of(md, "m.fmu")
        return x

    both = port('start="2"')
    assert both.name == "X" and both.size == 2 and both.has_default and list(both.start_array()) == [1.0, 2.0]
    assert not port("").has_default


def test_an_exported_native_component_keeps_its_defaults(tmp_path):
    """Exported (components/testing/gauge.py), ``bias`` (declared with a default) is named in the vendor annotation and may stay
    unconnected; ``F`` stays required although FMI gives it a start value too."""
    from rotorcosim.fmus.export import export_component

    fmu = export_component("rotorcosim.components.testing.gauge:Gauge", tmp_path / "gauge.fmu", instance_name="g")
    assert 'defaultInputs="bias"' in model_description(fmu)
    with pytest.raises(ContractError, match=r"inputs left unconnected .*: g\.F( |$)"):
        build_system(parse({"components": {"g": {"fmu": str(fmu)}}}))
    sc = parse({"components": {"g": {"fmu": str(fmu)}}, "inputs": {"g.F": 1.0}})
    cap = CaptureAll()
    sim = build_simulation(sc, [cap])
    try:
        assert sim.system.defaulted.keys() == {"g.bias"}
        sim.run(Timeline([Interval("TM", H, H)]))
    finally:
        for c in sim.system.components.values():
            c.terminate()
    assert cap.rows[-1]["g.y"][0] == 3.0


def test_parameters_survive_an_fmu_that_resets_them_in_setup_experiment(tmp_path):
    """tests/fmus/models/resets2.py resets k in fmi2SetupExperiment: our run, like fmpy's (which writes start
    values after setupExperiment), keeps the k it was given."""
    from tests.helpers.fmus import build_python_fmu

    fmu = build_python_fmu("resets2", tmp_path, fmi3=False)
    cap, report = run_alone(fmu, params={"k": 3.0})
    ref = fmpy_alone(fmu, params={"k": 3.0})
    assert report.status == "complete" and np.all(ref["y"] == 3.0)
    assert_same_as_fmpy(cap, ref, 1)
