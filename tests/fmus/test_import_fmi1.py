"""FMI 1.0 co-simulation FMUs as components: the test models of models/reference1 (after the Reference FMUs'
Dahlquist and Feedthrough, built by conftest.py) run by our master equal fmpy's ``simulate_fmu`` sample for
sample, with parameters and start values set as fmpy sets them; FMI 1.0's ports, its negated aliases, and its
refusals (model exchange only, no FMU state). test_reference_fmus.py runs the Reference FMUs' own FMI 1.0 builds
where their sources still have them.
"""
from __future__ import annotations

import zipfile

import numpy as np
import pytest
from numpy.lib import recfunctions

from rotorcosim.fmus.importer import FMUError, load_fmu_component
from rotorcosim.master.scenario.build import build_simulation, parse
from rotorcosim.master.schedule import Interval, Timeline

from tests.fmus.test_unconnected_inputs import assert_same_as_fmpy, fmpy_alone
from tests.helpers.fmus import CaptureAll

H = 1.0 / 64
DURATION = 2.0


def _ours(fmu, params=None, start=None):
    spec = {"fmu": str(fmu), "parameters": params or {}, "start": start or {}}
    cap = CaptureAll()
    sim = build_simulation(parse({"scenario": {}, "components": {"f": spec}}), [cap])
    try:
        report = sim.run(Timeline([Interval("TM", DURATION, H)]))
    finally:
        for c in sim.system.components.values():
            c.terminate()
    assert report.status == "complete", report.status
    return cap


@pytest.mark.parametrize("name, params, start", [
    ("dahlquist1", {}, {}),
    ("dahlquist1", {"k": 2.5}, {"x": 3.0}),
    ("feedthrough1", {}, {}),
    ("feedthrough1", {"gain": -4.0, "label": "set"}, {}),
], ids=["dahlquist1", "dahlquist1-k-x0", "feedthrough1", "feedthrough1-parameters"])
def test_fmi1_model_equals_fmpy_sample_for_sample(reference1_fmus, name, params, start):
    fmu = reference1_fmus[name]
    cap = _ours(fmu, params, start)
    ref = fmpy_alone(fmu, {**params, **start}, duration=DURATION, h=H)
    assert len(ref) == round(DURATION / H) + 1
    if name == "dahlquist1":
        # fmpy reads a negated alias as the value behind its reference (it ignores FMI 1.0's alias attribute)
        np.testing.assert_array_equal(cap.series("f.minus_x"), -np.asarray(ref["minus_x"]).reshape(-1, 1))
        ref = recfunctions.drop_fields(ref, "minus_x", usemask=False)
        # the outputs move: x decays from its start, the step count rises, x falls below 1/2 on the way
        assert ref["x"][0] == start.get("x", 1.0) and ref["x"][-1] < 0.5 * ref["x"][0]
        assert ref["steps"][-1] == len(ref) - 1 and ref["below"][0] != ref["below"][-1]
    else:
        gain = params.get("gain", 2.0)
        assert np.all(ref["real_out"] == gain * 0.5) and np.all(ref["int_out"] == 2) and np.all(ref["bool_out"])
        # fmpy records no String output: ours is checked here
        assert list(cap.series("f.string_out").ravel()) == ["Set me!"] * len(ref)
    assert_same_as_fmpy(cap, ref, 3)


def test_fmi1_ports(reference1_fmus):
    """FMI 1.0 causalities and variabilities as ports: variability parameter is a parameter (of any type),
    input / output keep theirs, internal variables are not ports; each type is kept."""
    c = load_fmu_component(reference1_fmus["feedthrough1"], "f")
    try:
        ports = {v.name: (v.causality, v.type, v.start) for v in c.variables}
    finally:
        c.terminate()
    assert ports == {
        "real_in": ("input", "Real", 0.5), "real_out": ("output", "Real", 0.0), "gain": ("parameter", "Real", 2.0),
        "int_in": ("input", "Integer", 2), "int_out": ("output", "Integer", 0),
        "bool_in": ("input", "Boolean", True), "bool_out": ("output", "Boolean", False),
        "string_in": ("input", "String", "Set me!"), "string_out": ("output", "String", ""),
        "label": ("parameter", "String", "label")}


def test_fmi1_inputs_reach_the_outputs(reference1_fmus):
    """Each type's input set (through the preallocated buffers) comes back on its output after a step."""
    c = load_fmu_component(reference1_fmus["feedthrough1"], "f", {"gain": 3.0})
    try:
        c.setup(0.0)
        c.u.update(real_in=np.array([1.25]), int_in=np.array([-7]), bool_in=np.array([False]),
                   string_in=np.array(["über"], dtype=object))
        c.do_step(0.0, 0.5)
        got = {k: v.tolist() for k, v in c.y.items()}
    finally:
        c.terminate()
    assert got == {"real_out": [3.75], "int_out": [-7], "bool_out": [False], "string_out": ["über"]}


def test_fmi1_has_no_fmu_state(reference1_fmus):
    c = load_fmu_component(reference1_fmus["dahlquist1"], "d")
    try:
        c.setup(0.0)
        c.do_step(0.0, 0.1)        # stepping works
        with pytest.raises(FMUError, match=r"cannot get/set its state \(FMI 1.0 has no FMU state functions\): "
                                           "rollback"):
            c.get_state()
    finally:
        c.terminate()


def test_fmi1_model_exchange_only(reference1_fmus, tmp_path):
    """An FMI 1.0 description without <Implementation> is model exchange: refused as FMI 2.0's is."""
    with zipfile.ZipFile(reference1_fmus["dahlquist1"]) as zf:
        xml = zf.read("modelDescription.xml").decode()
    start, end = xml.index("<Implementation>"), xml.index("</Implementation>") + len("</Implementation>")
    me = tmp_path / "me1.fmu"
    with zipfile.ZipFile(me, "w") as zf:
        zf.writestr("modelDescription.xml", xml[:start] + xml[end:])
    with pytest.raises(FMUError, match=r"me1.fmu: the FMU offers model exchange only, no co-simulation interface"):
        load_fmu_component(me, "c")


def test_fmi1_start_value_without_a_declared_start(reference1_fmus):
    with pytest.raises(FMUError, match=r"'real_out' \(causality output, variability continuous\) has no start value "
                                       "to set: only FMI 1.0 variables that declare a start value do"):
        load_fmu_component(reference1_fmus["feedthrough1"], "f", start_values={"real_out": 1.0})


def test_fmi1_discard_is_a_failed_step(reference1_fmus):
    """fmiDiscard from fmiDoStep: FMI 1.0 has no way to ask to stop, so the step failed; the error says where
    the slave got to (fmiLastSuccessfulTime)."""
    c = load_fmu_component(reference1_fmus["dahlquist1"], "d", {"t_discard": 0.3})
    try:
        c.setup(0.0)
        c.do_step(0.0, 0.25)
        with pytest.raises(FMUError, match=r"fmiDoStep\(t = 0.25 s, h = 0.25 s\) returned fmiDiscard \(it reached "
                                           r"t = 0.3 s\): the step was not completed"):
            c.do_step(0.25, 0.25)
    finally:
        c.terminate()


def test_fmi1_step_error_names_the_fmus_message(reference1_fmus):
    """A failing fmiDoStep is one line with what the FMU logged (FMI 1.0's variadic logger, formatted by fmpy's
    native proxy)."""
    c = load_fmu_component(reference1_fmus["dahlquist1"], "d")
    try:
        c.setup(0.0)
        with pytest.raises(FMUError, match=r"DoStep\(t = 0.5 s, h = 0.1 s\) failed \(status error\): fmiDoStep: "
                                           "not at the slave's time$"):
            c.do_step(0.5, 0.1)
    finally:
        c.terminate()


def test_fmi1_guid_that_does_not_match_the_binary(reference1_fmus, tmp_path):
    src = reference1_fmus["feedthrough1"]
    bad = tmp_path / "guid1.fmu"
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(bad, "w") as zout:
        for item in zin.infolist():
            data = zin.read(item)
            if item.filename == "modelDescription.xml":
                data = data.replace(b"{8c4e810f-3df3-4a00-8276-176fa3c9f002}", b"{00000000-0000-0000-0000-000000000000}")
            zout.writestr(item, data)
    with pytest.raises(FMUError, match=r"guid1.fmu \(component 'c'\): instantiation failed \(fmiInstantiateSlave "
                                       r"returned no instance\)"):
        load_fmu_component(bad, "c")


def test_fmi1_binary_of_another_model_identifier(reference1_fmus, tmp_path):
    """The functions of an FMI 1.0 binary carry the model identifier: a binary under the right file name that
    exports another identifier's functions does not load, and the error names the binary."""
    src = reference1_fmus["feedthrough1"]
    bad = tmp_path / "ident1.fmu"
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(bad, "w") as zout:
        zout.writestr("modelDescription.xml", zin.read("modelDescription.xml").replace(
            b'modelIdentifier="feedthrough1"', b'modelIdentifier="other1"'))
        zout.writestr("binaries/linux64/other1.so", zin.read("binaries/linux64/feedthrough1.so"))
    with pytest.raises(FMUError, match=r"its binary \(model identifier 'other1'\) does not load on this platform: "
                                       r".*other1_fmi.*\(binaries in the FMU: binaries/linux64/other1.so\)"):
        load_fmu_component(bad, "c")
