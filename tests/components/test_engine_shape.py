"""A wrong TOML shape anywhere in an engine file (a number where a table belongs, a list where a number belongs, a
table where a list belongs...) is one line naming the key and the shape expected, exit status 2, from
``check-engine``, and a ValueError naming the key from the model builder (``run``, ``critical-speeds``); never
"unexpected AttributeError ... may be a bug". The whole class: every key of the format that the test engine
holds (the paper's engine with a pedestal added: every table the format has) gets every wrong kind of value."""
from __future__ import annotations

import copy

import pytest

from rotorcosim.cases.blade_loss.check_engine import check_engine
from rotorcosim.components.rotor import engine_shape as es
from rotorcosim.components.rotor import model as fem
from rotorcosim.interop.engine_toml import dumps
from rotorcosim.master.cli import main

#: the values tried, by the TOML kind they are (a bool is not a number)
CANDIDATES = {"number": 7.5, "string": "x", "list": [1.0, 2.0], "table": {"a": 1.0}, "boolean": True}
#: what each kind of key accepts (written here, independently of the module under test)
ACCEPTS = {"number": {"number", "integer"}, "int": {"integer"}, "str": {"string"},
           "knob": {"number", "integer", "string"}, "node": set(), "end": {"string"}, "bool": {"boolean"}}


def _engine() -> dict:
    data, _ = fem.load_data(None)
    data = copy.deepcopy(data)
    data["pedestal"] = {"p1": {"mass": 2.0, "k": 1e8, "c": 100.0, "k_axial": 1e8}}
    data["spool"]["pt"]["layers"] = [{"element": 5, "d_out_mm": 70.0, "d_in_mm": 66.0, "material": "rotor"}]
    data["spool"]["gg"].update({"shear_effects": True, "rotary_inertia": False, "rayleigh": {"alpha": 1.0}})
    data["spool"]["pt"]["rayleigh"] = {"beta": [1e-6] * (len(data["spool"]["pt"]["z_mm"]) - 1)}
    data["support"].append({"name": "seal", "a": ["pt", 10], "b": "ground", "speed_rpm": [5000.0, 10000.0],
                            "kxx": [1e5, 2e5], "kyy": [1e5, 2e5], "kxy": [3e5, 4e5], "kyx": [-3e5, -4e5],
                            "cxx": 500.0, "cyy": 500.0, "cxy": 10.0, "cyx": -10.0})
    return data


def test_the_fuzzed_engine_itself_is_valid():
    from rotorcosim.components.rotor.engine_check import problems

    assert problems(_engine()) == []


def _accepts(kind) -> set:
    if isinstance(kind, str):
        return ACCEPTS.get(kind, set())
    tag = kind[0]
    if tag == "number|list":
        return {"number", "integer", "list"}
    if tag == "list":
        return {"list"}
    if tag in ("table", "tables", "attach"):
        return {"table"}
    if tag == "array":
        return set()
    return set()


def _paths(value, kind, path):
    """(path, kind) of every key of the format present in ``value`` (and its first element of every list)."""
    yield path, kind
    if isinstance(kind, str):
        return
    tag = kind[0]
    if tag == "table" and isinstance(value, dict):
        for k, sub in kind[1].items():
            if k in value:
                yield from _paths(value[k], sub, path + (k,))
    elif tag == "tables" and isinstance(value, dict) and kind[1] != "any":
        for name, x in value.items():
            yield from _paths(x, kind[1], path + (name,))
    elif tag == "list" and isinstance(value, list) and value:
        yield from _paths(value[0], kind[1], path + (0,))
    elif tag == "number|list" and isinstance(value, list) and value:
        yield from _paths(value[0], kind[1], path + (0,))
    elif tag == "array" and isinstance(value, list) and value:
        for i in sorted({0, len(value) - 1}):           # the first and the last entry (the seal's table)
            yield from _paths(value[i], kind[1], path + (i,))
    elif tag == "attach" and isinstance(value, dict):
        for k, x in value.items():
            sub = "number" if k == "oil_temperature_C" else es.ATTACH_ENTRY
            yield from _paths(x, sub, path + (k,))


def _name(path) -> str:
    out = ""
    for p in path:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else p)
    return out


def _cases():
    data = _engine()
    out = []
    for path, kind in _paths(data, es.SHAPE, ()):
        if not path or kind == "any":
            continue
        for label, v in CANDIDATES.items():
            if label in _accepts(kind) or (label == "list" and kind in ("node", "end")):
                continue
            out.append(pytest.param(path, v, id=f"{_name(path)}={label}"))
    return out


CASES = _cases()


def test_the_fuzz_covers_every_table_of_the_format():
    names = {_name(c.values[0]) for c in CASES}
    for table in ("engine", "calibration", "material.rotor", "damping", "spool.pt", "spool.pt.disks[0]",
                  "spool.pt.layers[0]", "support[0]", "support[6].speed_rpm", "support[6].kxy", "pedestal.p1", "casing", "casing.hubs", "casing.mounts[0]", "attach",
                  "attach.bearing0", "attach.unbalance"):
        assert any(n == table or n.startswith(table + ".") or n.startswith(table + "[") for n in names), table
    assert len(CASES) > 250


def _write(tmp_path, path, value):
    data = _engine()
    node = data
    for p in path[:-1]:
        node = node[p]
    node[path[-1]] = value
    f = tmp_path / "engine.toml"
    f.write_text(dumps(data))
    return f


@pytest.mark.parametrize("path, value", CASES)
def test_wrong_shape_is_one_line_naming_the_key(tmp_path, path, value):
    f = _write(tmp_path, path, value)
    key = _name(path)
    problems = check_engine(str(f))["problems"]
    assert any(line.startswith(key) and "must be" in line and "\n" not in line for line in problems), (key, problems)
    # the model builder (run, critical-speeds) says the same in one line
    with pytest.raises(ValueError) as exc:
        fem.load(f)
    assert key in str(exc.value) and "\n" not in str(exc.value)


@pytest.mark.parametrize("path, value, expected", [
    (("pedestal", "p1"), 3.0, "pedestal.p1: must be a table (mass, k or kxx/kyy"),
    (("spool", "pt", "disks"), 5, "spool.pt.disks: must be a list of tables"),
    (("spool", "pt", "speed_rpm"), [16000.0, 17000.0], "spool.pt.speed_rpm: must be a number, got a list of 2"),
    (("casing",), 5, "casing: must be a table"),
])
def test_check_engine_command_on_a_wrong_shape(tmp_path, capsys, path, value, expected):
    f = _write(tmp_path, path, value)
    rc = main(["check-engine", str(f), "--campbell", str(tmp_path / "c.png")])
    out, err = capsys.readouterr()
    assert rc == 2, (out, err)
    assert "may be a bug" not in out + err and "Traceback" not in out + err
    problems = [line.strip() for line in out.splitlines()[1:]]
    assert len(problems) == 1 and problems[0].startswith(expected), out
    assert not (tmp_path / "c.png").exists()


def _part_cases():
    data, _ = fem.load_data(None)
    out = []
    for table in ("bearing", "damper", "rubring", "thermal", "unbalance"):
        entries = data.get(table, {})
        rows = [((table,), entries)] if table == "unbalance" else [((table, i), e) for i, e in entries.items()]
        for path, entry in rows:
            for key, v in entry.items():
                for label, bad in CANDIDATES.items():
                    if type(bad) is type(v) or (label == "number" and isinstance(v, (int, float))
                                                and not isinstance(v, bool)):
                        continue
                    out.append(pytest.param(path + (key,), bad, id=f"{_name(path + (key,))}={label}"))
    return out


@pytest.mark.parametrize("path, value", _part_cases())
def test_wrong_shape_in_a_part_table_is_one_line_naming_the_key(tmp_path, path, value):
    """The part tables ([bearing.ID], [damper.ID], [rubring.ID], [thermal.ID], [unbalance]) of the paper's
    engine, every key of them given every wrong kind of value: a problem line naming the table, the id and the
    key, never a crash."""
    data, _ = fem.load_data(None)
    node = data
    for p in path[:-1]:
        node = node[p]
    node[path[-1]] = value
    f = tmp_path / "engine.toml"
    f.write_text(dumps(data))
    problems = check_engine(str(f))["problems"]
    assert any(all(str(p) in line for p in path) and "\n" not in line for line in problems), (path, problems)


def _table_paths():
    """Every table of the format the test engine holds (each a place where a typo'd key could hide)."""
    return [path for path, kind in _paths(_engine(), es.SHAPE, ()) if not isinstance(kind, str) and kind[0] == "table"]


@pytest.mark.parametrize("path", [pytest.param(p, id=_name(p) or "top") for p in _table_paths()])
def test_an_unknown_key_in_any_table_is_named(tmp_path, path):
    """A key the format does not know is a problem naming it, not a value silently left at its default."""
    data = _engine()
    node = data
    for p in path:
        node = node[p]
    node["zz_unknown"] = 1.0
    f = tmp_path / "engine.toml"
    f.write_text(dumps(data))
    key = _name(path + ("zz_unknown",))
    problems = check_engine(str(f))["problems"]
    assert any(line.startswith(f"{key}: unknown") for line in problems), (key, problems)
    with pytest.raises(ValueError) as exc:
        fem.load(f)
    assert key in str(exc.value) and "\n" not in str(exc.value)


def test_every_table_of_the_format_is_tried_for_unknown_keys():
    names = {_name(p) for p in _table_paths()}
    assert {"", "engine", "material.rotor", "damping", "spool.pt", "spool.pt.disks[0]", "spool.pt.layers[0]",
            "support[0]", "pedestal.p1", "casing", "casing.hubs.h0", "casing.mounts[0]", "casing.struts"} <= names


@pytest.mark.parametrize("old, new, says", [
    ("speed_rpm = 16000.0", "speed_rmp = 16000.0", "spool.pt.speed_rmp: unknown key (did you mean 'speed_rpm'?)"),
    ("c = 1751.0\nk_axial", "cc = 1751.0\nk_axial", "support[0].cc: unknown key (did you mean 'c'?)"),
    ("zeta = 0.01", "zeta = 0.01\nzetta = 0.02", "damping.zetta: unknown key (did you mean 'zeta'?)"),
    ("[spool.pt]", "[spoool.x]\nspeed_rpm = 1.0\n\n[spool.pt]", "spoool: unknown table (did you mean 'spool'?)"),
])
def test_a_typo_is_refused_by_every_command_that_reads_the_engine(tmp_path, capsys, old, new, says):
    """check-engine lists it, critical-speeds and a run refuse it in one line (exit 2), and the run leaves no
    folder."""
    text = fem.DEFAULT_FILE.read_text()
    assert old in text
    f = tmp_path / "engine.toml"
    f.write_text(text.replace(old, new, 1))
    rc = main(["check-engine", str(f), "--campbell", str(tmp_path / "c.png")])
    out, err = capsys.readouterr()
    assert rc == 2 and says in out, (out, err)
    rc = main(["critical-speeds", "--model", str(f)])
    out, err = capsys.readouterr()
    lines = [line for line in err.splitlines() if line.strip()]
    assert rc == 2 and len(lines) == 1 and says in lines[0] and "Traceback" not in err, err
    sc = tmp_path / "s.toml"
    sc.write_text(f'[scenario]\nextends = "blade_loss_2850"\nname = "typo"\nengine = "{f.name}"\n')
    rc = main(["run", str(sc), "--duration", "0.001", "--no-figures", "--quiet", "--out", str(tmp_path / "o")])
    out, err = capsys.readouterr()
    lines = [line for line in err.splitlines() if line.strip()]
    assert rc == 2 and len(lines) == 1 and says in lines[0], err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("old, new, says", [
    ("preload_N = 800.0", "preload_N = 800.0\npreload = 800.0", "[bearing.0] preload: unknown key"),
    ("k_spring = 5.254e6", "k_spring = 5.254e6\nk_sprng = 1.0", "[damper.0] k_sprng: unknown key"),
    ("phase_deg = 90.0", "phase_deg = 90.0\nphase = 0.0", "[unbalance] phase: unknown key"),
    ("clearance_mm = 0.508", "clearance_mm = -0.508", "[rubring.0] clearance_mm: must be > 0"),
    ("[unbalance]", "[thermal.7]\nshaft_length_mm = 100.0\n\n[unbalance]", "[thermal.7]: [attach] has no bearing7"),
])
def test_a_part_table_problem_is_refused_by_critical_speeds_and_run(tmp_path, capsys, old, new, says):
    """What check-engine lists of the part tables refuses critical-speeds and a run too, naming the engine file
    (not the paper's engine, whose parts the linearisation would otherwise be said to come from), exit 2, no
    folder."""
    text = fem.DEFAULT_FILE.read_text()
    assert old in text
    f = tmp_path / "engine.toml"
    f.write_text(text.replace(old, new, 1))
    rc = main(["critical-speeds", "--model", str(f)])
    out, err = capsys.readouterr()
    lines = [line for line in err.splitlines() if line.strip()]
    assert rc == 2 and len(lines) == 1 and says in lines[0] and str(f) in lines[0], err
    sc = tmp_path / "s.toml"
    sc.write_text(f'[scenario]\nextends = "blade_loss_2850"\nname = "part"\nengine = "{f.name}"\n')
    rc = main(["run", str(sc), "--duration", "0.001", "--no-figures", "--quiet", "--out", str(tmp_path / "o")])
    out, err = capsys.readouterr()
    lines = [line for line in err.splitlines() if line.strip()]
    assert rc == 2 and len(lines) == 1 and says in lines[0] and str(f) in lines[0], err
    assert not (tmp_path / "o").exists()


def test_a_support_between_a_node_and_itself_is_refused(tmp_path, capsys):
    """It would add k - k = 0 to the stiffness: a support that carries nothing, surely not what was meant."""
    text = fem.DEFAULT_FILE.read_text()
    f = tmp_path / "engine.toml"
    f.write_text(text.replace('b = ["hub", "b1"]', 'b = ["gg", 14]', 1))
    for argv in (["critical-speeds", "--model", str(f)], ["check-engine", str(f), "--campbell", str(tmp_path / "c.png")]):
        rc = main(argv)
        out, err = capsys.readouterr()
        lines = [line for line in err.splitlines() if line.strip()]
        assert rc == 2 and len(lines) == 1 and "a and b are the same node ['gg', 14]" in lines[0], (argv, err)
    assert not (tmp_path / "c.png").exists()


def test_a_test_rotor_s_model_file_is_named_as_such(tmp_path, capsys):
    """A ``[shaft]`` model file (the Jeffcott rotor's) given where an engine file belongs: one line saying which
    format it is (was: three problems of a missing engine, or "shaft: unknown table")."""
    f = fem.DEFAULT_FILE.with_name("jeffcott.toml")
    says = "shaft: a test rotor's model file ([shaft], components/rotor/shaft_model.py), not an engine file"
    rc = main(["critical-speeds", "--model", str(f)])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert rc == 2 and len(err) == 1 and says in err[0], err
    rc = main(["check-engine", str(f), "--campbell", str(tmp_path / "c.png")])
    out = capsys.readouterr().out
    assert rc == 2 and [line.strip() for line in out.splitlines()[1:]] == [says + " (docs/reference/engine-format.md)"]


def test_windmill_range_without_a_diagram_is_refused(capsys):
    """``--windmill-rpm`` only marks the Campbell diagram: without ``--campbell`` it did nothing, silently."""
    rc = main(["critical-speeds", "--windmill-rpm", "3000,4000"])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert rc == 2 and err == ["rotorcosim critical-speeds: error: --windmill-rpm marks the Campbell diagram: give "
                               "--campbell FILE.png too"], err


@pytest.mark.parametrize("rayleigh, message", [
    ({"alpha": -1.0}, "spool.gg.rayleigh.alpha: must be a finite number >= 0, got -1.0"),
    ({"beta": [1e-6, 1e-6]}, "spool.gg.rayleigh.beta: needs 15 values (one per element) or one number, got 2"),
    ({"alpha": [1.0] * 14 + [float("nan")]}, "spool.gg.rayleigh.alpha[14]: must be a finite number >= 0, got nan"),
])
def test_a_bad_rayleigh_value_is_named(rayleigh, message):
    from rotorcosim.components.rotor.engine_check import problems

    data = _engine()
    assert len(data["spool"]["gg"]["z_mm"]) == 16
    data["spool"]["gg"]["rayleigh"] = rayleigh
    assert problems(data)[0] == message
    with pytest.raises(ValueError, match="rayleigh"):
        fem.build(data)
