"""The strict scenario schema: each error names the file, the table, the key (and the line)."""
import textwrap

import pytest

from rotorcosim import scenarios
from rotorcosim.components.contract import ContractError
from rotorcosim.components.registry import create
from rotorcosim.master.scenario.build import load_scenario, parse
from rotorcosim.master.scenario.key_lines import locate
from rotorcosim.master.scenario.schema import SchemaError, check

TOY = scenarios.path("toy_thermomechanical").read_text()
BEARING = textwrap.dedent("""
    [components.b]
    implementation = "bearing.hertz"
    parameters = { bearing = 5 }
    [inputs]
    "b.X_inner" = 0.0
    [schedule]
    kind = "monolithic"
    duration = 0.1
    step = 1e-5
""")


def load(tmp_path, text):
    p = tmp_path / "s.toml"
    p.write_text(text)
    return load_scenario(p)


@pytest.mark.parametrize("edit, message", [
    # booleans and strings are not numbers
    (lambda s: s.replace('parameters = { C = 10.0, R = 1.0 }', 'parameters = { C = true, R = 1.0 }'),
     ":13: [components.node] parameters.C: must be a number [J/K], got a boolean (True)"),
    (lambda s: s.replace("step = 1e-3\nthermal_step", "step = true\nthermal_step"),
     "[schedule] step: must be a number, got a boolean (True)"),
    (lambda s: s.replace("record_step = 1e-3", 'record_step = "1e-3"'),
     "[outputs] record_step: must be a number, got a string ('1e-3')"),
    # the time series file says sampling_interval_s = record_step: a run samples every whole number of steps
    (lambda s: s.replace("record_step = 1e-3", "record_step = 1e-4"),
     "[outputs] record_step: 0.0001 s is shorter than the thermo-mechanical step 0.001 s"),
    (lambda s: s.replace("record_step = 1e-3", "record_step = 2.5e-3"),
     "[outputs] record_step: 0.0025 s is not a whole multiple of the thermo-mechanical step 0.001 s"),
    (lambda s: s.replace("hold_cycles = 5", "hold_cycles = -5"), "[schedule] hold_cycles: must be a positive number"),
    (lambda s: s.replace("speed_rpm = 2700.0", "speed_rpm = inf"), "[schedule] speed_rpm: must be a finite number"),
    # unknown keys everywhere, with "did you mean"
    (lambda s: s.replace('name = "toy_thermomechanical"', 'nmae = "x"'),
     "[scenario] nmae: unknown key (did you mean 'name'?)"),
    (lambda s: s.replace("record_step = 1e-3", "record_stpe = 1e-3"),
     "[outputs] record_stpe: unknown key (did you mean 'record_step'?)"),
    (lambda s: s.replace('level_parameter = "osc.F0"', 'level_paramter = "osc.F0"'),
     "[results] level_paramter: unknown key (did you mean 'level_parameter'?)"),
    (lambda s: s.replace('{ phase = "TM", duration = 0.3 }, { phase = "TO", duration = 4.7 },\n  { phase = "TM"',
                         '{ phase = "TM", duration = 0.3, stpe = 1e-3 }, { phase = "TO", duration = 4.7 },\n  { phase = "TM"', 1),
     "[schedule.intervals #1] stpe: unknown key (did you mean 'step'?)"),
    (lambda s: s.replace('implementation = "testing.thermal_node"', 'implementation = "testing.thermal_node"\nstpe = 1e-3'),
     "[components.node] stpe: unknown key (did you mean 'step'?)"),
    (lambda s: s.replace("[algorithm]", "[algoritm]"), "[algoritm]: unknown table (did you mean 'algorithm'?)"),
    (lambda s: s.replace('implementation = "testing.thermal_node"', 'implementation = "testing.thermal_nod"'),
     "(did you mean 'testing.thermal_node'?)"),
    (lambda s: s.replace('parameters = { C = 10.0, R = 1.0 }', 'parameters = { C = 10.0, RR = 1.0 }'),
     "[components.node] parameters.RR: testing.thermal_node has no parameter 'RR' (did you mean 'R'?)"),
    # cross-checks
    (lambda s: s.replace('order = ["osc", "node"]', 'order = ["osc", "node", "osc"]'),
     "[algorithm] order: component 'osc' is listed twice"),
    (lambda s: s.replace('order = ["osc", "node"]', 'order = ["osc", "nod"]'),
     "[algorithm] order: no component 'nod' (did you mean 'node'?)"),
    (lambda s: s.replace('implementation = "testing.thermal_node"', 'implementation = "testing.thermal_node"\nstep = 0.5'),
     "[components.node] step: 0.5 s is longer than the thermo-mechanical interval [schedule.intervals #1] of 0.3 s"),
    (lambda s: s.replace('implementation = "testing.thermal_node"', 'implementation = "testing.thermal_node"\nstep = 2.5e-3'),
     "[components.node] step: 0.0025 s is not a whole multiple of the thermo-mechanical step 0.001 s"),
    (lambda s: s.replace('record = ["osc.x", "osc.P", "node.T"]', 'record = ["osc.x", "nodes.T"]'),
     "[outputs] record: 'nodes.T': no component 'nodes' (did you mean 'node'?)"),
    (lambda s: s.replace('to = "node.P"', 'to = "nodeP"'), "[connections #1] to: 'nodeP' must be written 'component.port'"),
    (lambda s: s.replace('format = "h5"', 'format = "hdf"'), "[outputs] format: 'hdf' is not one of 'h5', 'csv'"),
    (lambda s: s.replace("[algorithm]", "[algorithm]\niterations = 2.0"), "[algorithm] iterations: must be a whole number"),
    # a hold window longer than every TM interval never fills (1e12 cycles ran the machine out of memory)
    (lambda s: s.replace("hold_cycles = 5", "hold_cycles = 1e12"),
     "[schedule] hold_cycles: 1e+12 cycles at 2700 rev/min last 2.222e+10 s, longer than the longest "
     "thermo-mechanical interval (0.3 s)"),
    (lambda s: s.replace("hold_cycles = 5", "hold_cycles = 14"), "hold_cycles: 14 cycles at 2700 rev/min last 0.3111 s"),
    # a restart ramp longer than the TM time after a TO interval never ends (1e12 was accepted); 0.3 s = 13.5
    # cycles at 2700 rev/min; under the automatic schedule tm_max bounds it
    (lambda s: s.replace("hold_cycles = 5", "hold_cycles = 5\nrestart_cycles = 1e12"),
     "[schedule] restart_cycles: 1e+12 cycles at 2700 rev/min last 2.222e+10 s, longer than the shortest run of "
     "thermo-mechanical intervals after a thermal-only one (0.3 s)"),
    (lambda s: s.replace("hold_cycles = 5", "hold_cycles = 5\nrestart_cycles = 14"), "restart_cycles: 14 cycles"),
    (lambda s: s.replace('kind = "timeline"', 'kind = "auto"\ntm_max = 0.12\nrestart_cycles = 6'),
     "restart_cycles: 6 cycles at 2700 rev/min last 0.1333 s, longer than tm_max"),
    # a rotor cycle shorter than two TM steps cannot be sampled (1e12 rev/min ran with one-sample windows)
    (lambda s: s.replace("speed_rpm = 2700.0", "speed_rpm = 1e12"),
     "[schedule] speed_rpm: 1e+12 rev/min turns once in 6e-11 s, less than two thermo-mechanical steps (0.001 s)"),
    (lambda s: s.replace("speed_rpm = 2700.0", "speed_rpm = 30001"), "speed_rpm: 30001 rev/min turns once in 0.002 s"),
    # under the automatic schedule the hold window is bounded by tm_max (1e308 overflowed in the hold)
    (lambda s: s.replace('kind = "timeline"', 'kind = "auto"').replace("hold_cycles = 5", "hold_cycles = 1e308"),
     "[schedule] hold_cycles: 1e+308 cycles at 2700 rev/min last inf s, longer than the longest thermo-mechanical "
     "interval (0.5 s)"),
    # a signal recorded twice (was h5py's "Unable to synchronously create dataset (name already exists)")
    (lambda s: s.replace('record = ["osc.x", "osc.P", "node.T"]', 'record = ["osc.x", "osc.P", "osc.x"]'),
     "[outputs] record: 'osc.x' is listed twice"),
])
def test_toy_scenario_mistakes(tmp_path, edit, message):
    text = edit(TOY)
    assert text != TOY
    with pytest.raises(SchemaError) as info:
        load(tmp_path, text)
    msg = str(info.value)
    assert message in msg
    assert msg.startswith(str(tmp_path / "s.toml"))


def test_error_gives_the_line(tmp_path):
    text = TOY.replace("record_step = 1e-3", "record_stpe = 1e-3")
    line = next(i for i, l in enumerate(text.splitlines(), 1) if "record_stpe" in l)
    with pytest.raises(SchemaError, match=rf"s\.toml:{line}: \[outputs\] record_stpe"):
        load(tmp_path, text)


def test_toml_syntax_error_gives_the_line(tmp_path):
    with pytest.raises(ValueError, match=r"s\.toml:3: not valid TOML"):
        load(tmp_path, "[scenario]\nname = 'x'\nbad = = 1\n")


def test_a_part_without_its_record_or_its_values_is_an_error(tmp_path):
    """A bearing, damper, rub ring or thermal network given neither a record of the paper's Table 3 nor its own
    values (a scenario takes them from its engine) names what is missing when it is set up."""
    from rotorcosim.master.scenario.build import create_component

    for impl, missing in (("bearing.hertz", "balls, ball_diameter, bore"), ("damper.fast", "radius, length"),
                          ("rubring.contact", "clearance, radius"), ("thermal.network", "bore, outside_diameter")):
        text = BEARING.replace('"bearing.hertz"', f'"{impl}"').replace("parameters = { bearing = 5 }", "")
        with pytest.raises(ContractError, match=rf"\(\w+ = -1\) and no {missing}"):
            create_component(load(tmp_path, text).components["b"]).setup(0.0)


def test_boolean_parameter_refused_by_the_contract_too():
    """The API path (no scenario file) refuses a boolean for a number as well."""
    with pytest.raises(ContractError, match="expected a number"):
        create("testing.mass", "m", {"k": True})
    with pytest.raises(ContractError, match="expected a number"):
        create("testing.mass", "m", {"k": "4"})


def test_schema_applies_to_a_composed_dict():
    """check() takes the dict after composition, whatever put it together (extends, API)."""
    import tomllib

    data = tomllib.loads(TOY)
    check(data)  # the shipped scenario is valid
    data["schedule"]["stpe"] = 1.0
    with pytest.raises(SchemaError, match=r"^scenario: \[schedule\] stpe: unknown key"):
        parse(data)


def test_every_shipped_scenario_passes():
    """Every shipped scenario loads through the strict schema (a shipped file the schema refuses raises here)."""
    import glob

    files = sorted(glob.glob(str(scenarios.path("toy_thermomechanical").parent / "*.toml")))
    assert len(files) >= 9  # blade_loss, its seven levels, the toy
    for f in files:
        sc = load_scenario(f)
        assert sc.components and sc.connections, f


def test_locate_finds_inline_table_keys(tmp_path):
    p = tmp_path / "x.toml"
    p.write_text('[scenario]\nname = "a"\n\n[components.m]\nimplementation = "x"\nparameters = { k = true }\n')
    assert locate(p, "components.m", "k") == 6
    assert locate(p, "scenario", "name") == 2


def test_error_in_an_extended_base_names_its_file_and_line(tmp_path):
    base = tmp_path / "base.toml"
    base.write_text(TOY.replace("record_step = 1e-3", "record_stpe = 1e-3"))
    top = tmp_path / "top.toml"
    top.write_text('[scenario]\nextends = "base.toml"\nname = "top"\n')
    line = next(i for i, l in enumerate(base.read_text().splitlines(), 1) if "record_stpe" in l)
    with pytest.raises(SchemaError, match=rf"top\.toml \(from .*base\.toml:{line}\): \[outputs\] record_stpe"):
        load_scenario(top)
