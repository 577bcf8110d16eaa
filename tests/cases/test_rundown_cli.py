"""The rundown from the command line: bad speed inputs end in one line naming the parameter (never a traceback),
a profile that stops the rotor is a legal end state, and ``--set`` / ``sweep --set`` act on the speed profile."""
from __future__ import annotations

import json
import subprocess
import sys

import pytest


def _run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", *args], capture_output=True, text=True,
                          cwd=cwd)


@pytest.mark.parametrize("sets, message", [
    (["spool.inertia=-1"], "spool.inertia must be a finite number >= 0"),
    (["spool.profile=table", 'spool.table="0 9000, 1 3000, 0.5 100"'], "the times must increase strictly"),
    (["spool.profile=torque", "spool.windmill_rpm=9500", "spool.aero_torque=1"], "is not below the start speed"),
    (["spool.profile=stop"], "spool.profile must be one of"),
])
def test_bad_speed_inputs_are_one_line(tmp_path, sets, message):
    args = ["run", "jeffcott_rundown", "--out", str(tmp_path / "o"), "--no-figures"]
    for s in sets:
        args += ["--set", s]
    r = _run(*args)
    assert r.returncode == 2
    assert message in r.stderr and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_nan_torque_is_named(tmp_path):
    f = tmp_path / "nan.toml"
    f.write_text('[scenario]\nextends = "jeffcott_rundown"\nname = "nan"\n[inputs]\n"spool.T_rub1" = nan\n'
                 '[components.spool]\nparameters = { profile = "torque", t_fuel_cut = 0.0, inertia = 0.01 }\n')
    r = _run("run", str(f), "--out", str(tmp_path / "o"), "--no-figures")
    assert r.returncode != 0 and "T_rub1" in r.stderr and "Traceback" not in r.stderr


@pytest.mark.slow   # ~9-10 s (measured; a rundown sweep)
def test_sweep_over_the_speed_profile(tmp_path):
    """A sweep over the ramp's end speed: a rundown to 0 rev/min stops the rotor (a legal end state, reported)
    and crosses the critical speed as the one to 3000 rev/min does, later in speed terms slower."""
    out = tmp_path / "sw"
    r = _run("sweep", "jeffcott_rundown", "--set", "spool.end_speed_rpm=3000,0", "--serial", "--out", str(out))
    assert r.returncode == 0, r.stderr
    summaries = sorted(out.glob("*/summary.json"))
    assert len(summaries) == 2
    by_end = {}
    for p in summaries:
        s = json.loads(p.read_text())
        by_end[round(s["speeds"]["spool"]["end_rpm"])] = s
    assert by_end[0]["speeds"]["spool"]["stopped"] and not by_end[3000]["speeds"]["spool"]["stopped"]
    for s in by_end.values():
        (c,) = s["crossings"]
        assert 5000 < c["peak_speed_rpm"] < 6100
