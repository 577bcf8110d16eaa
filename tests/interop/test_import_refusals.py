"""``import-ross`` never writes an engine file that ``check-engine`` rejects: a bad value of a ROSS element is one
line naming the element and the key, exit status 2, and nothing is written (no engine file, no temporary file);
the writer itself refuses an engine with the same checks check-engine uses."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from rotorcosim.interop import write_engine
from rotorcosim.interop.ross_import import from_ross
from rotorcosim.master.cli import main

DATA = Path(__file__).with_name("data")


def _mutated(tmp_path, old: str, new: str) -> Path:
    text = (DATA / "rotor_example.toml").read_text()
    assert old in text
    p = tmp_path / "rotor.toml"
    p.write_text(text.replace(old, new, 1))
    return p


def _refused(tmp_path, capsys, rotor, *extra):
    out = tmp_path / "engine.toml"
    rc = main(["import-ross", str(rotor), "--out", str(out), *extra])
    o, err = capsys.readouterr()
    lines = [line for line in err.splitlines() if line.strip()]
    assert rc == 2, (o, err)
    assert len(lines) == 1 and "Traceback" not in err, err
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rotor.toml"]
    return lines[0]


FIRST = '["ShaftElement_Shaft Element 0"]\nL = 0.25\nidl = 0.0\nodl = 0.05'


@pytest.mark.parametrize("new, words", [
    ('["ShaftElement_Shaft Element 0"]\nL = 0.25\nidl = 0.0\nodl = -0.05', ("'Shaft Element 0'", "odl", "> 0")),
    ('["ShaftElement_Shaft Element 0"]\nL = 0.25\nidl = 0.06\nodl = 0.05', ("'Shaft Element 0'", "idl", "outer")),
    ('["ShaftElement_Shaft Element 0"]\nL = nan\nidl = 0.0\nodl = 0.05', ("'Shaft Element 0'", "L", "nan")),
    ('["ShaftElement_Shaft Element 0"]\nidl = 0.0\nodl = 0.05', ("'Shaft Element 0'", "L missing")),
    ('["ShaftElement_Shaft Element 0"]\nL = -0.25\nidl = 0.0\nodl = 0.05', ("'Shaft Element 0'", "L", "> 0")),
    ('["ShaftElement_Shaft Element 0"]\nL = 0.25\nidl = 0.0\nodl = inf', ("'Shaft Element 0'", "odl", "finite")),
])
def test_bad_shaft_values_are_refused_by_element_and_key(tmp_path, capsys, new, words):
    line = _refused(tmp_path, capsys, _mutated(tmp_path, FIRST, new))
    for w in words:
        assert w in line, line


def test_bad_disk_mass_is_refused_by_element(tmp_path, capsys):
    text = (DATA / "rotor_example.toml").read_text()
    m = re.search(r'\["DiskElement_([^"]+)"\][^\[]*?\nm = ([0-9.e+-]+)', text)
    p = _mutated(tmp_path, f"\nm = {m.group(2)}", "\nm = -1.0")
    line = _refused(tmp_path, capsys, p)
    assert "DiskElement" in line and "m must be" in line


@pytest.mark.parametrize("hub", ["-3", "nan", "inf"])
def test_negative_or_non_finite_hub_mass_is_refused(tmp_path, capsys, hub):
    p = tmp_path / "rotor.toml"
    p.write_text((DATA / "rotor_example.toml").read_text())
    line = _refused(tmp_path, capsys, p, "--attach", "0=0,5=6", f"--hub-mass={hub}")
    assert "--hub-mass" in line


def test_the_writer_refuses_what_check_engine_rejects(tmp_path):
    """Every writer of engine files goes through write_engine: an engine that check-engine would reject (here a
    negative pedestal mass and an inner diameter above the outer) is refused, naming the key, nothing written."""
    engine = from_ross(DATA / "rotor_example.toml", attach={"bearing0": 0, "bearing5": 6})
    bad = dict(engine)
    bad["pedestal"] = {k: dict(v) for k, v in engine["pedestal"].items()}
    bad["pedestal"]["h0"]["mass"] = -3.0
    with pytest.raises(ValueError, match=r"pedestal\.h0\.mass") as exc:
        write_engine(bad, tmp_path / "e.toml")
    assert "\n" not in str(exc.value)
    bad = dict(engine)
    bad["spool"] = {k: dict(v) for k, v in engine["spool"].items()}
    bad["spool"]["shaft"]["d_in_mm"] = [60.0] + bad["spool"]["shaft"]["d_in_mm"][1:]
    with pytest.raises(ValueError, match=r"element 0.*inner diameter 60"):
        write_engine(bad, tmp_path / "e.toml")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("example, value, message", [
    # nan and inf gave NaN coefficients (a check-engine line naming a support, not the option), a negative speed
    # was taken silently
    ("rotor_example", "nan", "--coefficients-at must be a finite speed >= 0 rev/min, got nan"),
    ("rotor_example", "-3", "--coefficients-at must be a finite speed >= 0 rev/min, got -3.0"),
    # beyond a table's speeds the end value was held silently, where ROSS extrapolates (3000 rev/min: kxx 1.14e8
    # written, ROSS's 9.28e7)
    ("compressor_example", "3000", "ROSS BearingElement 'Bearing 0': --coefficients-at 3000 rev/min is outside the "
                                   "speeds its kxx is given at (4000 to 11000 rev/min)"),
])
def test_coefficients_at_a_speed_the_file_cannot_give(tmp_path, capsys, example, value, message):
    p = tmp_path / "rotor.toml"
    p.write_text((DATA / f"{example}.toml").read_text())
    line = _refused(tmp_path, capsys, p, f"--coefficients-at={value}")
    assert line == f"rotorcosim import-ross: error: {message}", line


def test_an_unbalance_node_without_attach_is_refused(tmp_path, capsys):
    """--unbalance-node without --attach was dropped without a word (the engine written had no unbalance)."""
    p = tmp_path / "rotor.toml"
    p.write_text((DATA / "rotor_example.toml").read_text())
    line = _refused(tmp_path, capsys, p, "--unbalance-node", "3")
    assert line == ("rotorcosim import-ross: error: --unbalance-node places the blade loss of the co-simulated "
                    "bearings: it applies with --attach only (without it the engine has no [attach] table)"), line


def test_a_folder_is_not_a_rotor_file(tmp_path, capsys):
    """A folder given as the ROSS file was called 'not found'."""
    (tmp_path / "rotor.toml").mkdir()
    assert main(["import-ross", str(tmp_path / "rotor.toml"), "--out", str(tmp_path / "engine.toml")]) == 2
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert err == [f"rotorcosim import-ross: error: ROSS rotor file {tmp_path / 'rotor.toml'} is a folder, not a "
                   "file written by ROSS's Rotor.save"], err


def test_a_folder_given_as_the_parts_file_is_named_a_folder(tmp_path, capsys):
    """--parts FOLDER said "no such file" of a folder that exists."""
    rotor = _mutated(tmp_path, "L = 0.25", "L = 0.25")
    line = _refused(tmp_path, capsys, rotor, "--attach", "0=0", "--parts", str(tmp_path))
    assert line == (f"rotorcosim import-ross: error: --parts {tmp_path}: is a folder; give the TOML file of the "
                    "parts ([bearing.ID], [damper.ID], ...)"), line
