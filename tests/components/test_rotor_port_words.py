"""The rotor's port descriptions speak of the engine it runs: the spool each part is on by the engine file's
own name, the housing as what it is; the paper's engine keeps its words (PT, GG, casing hub). Names and numbers
are never touched: only the descriptions."""
from __future__ import annotations

import re

import h5py
import pytest

from rotorcosim.components.rotor.component import Rotor
from rotorcosim.components.rotor.spinning import SpinningRotor
from rotorcosim.master.cli import main

PAPER_WORDS = re.compile(r"\bPT\b|\bGG\b|power[ -]turbine|gas[ -]generator|casing hub")


@pytest.fixture(scope="module")
def own_engine(tmp_path_factory):
    folder = tmp_path_factory.mktemp("own") / "X"
    assert main(["new-engine", str(folder)]) == 0
    return folder


@pytest.mark.parametrize("cls", [Rotor, SpinningRotor])
def test_a_users_engine_is_described_in_its_own_words(own_engine, cls):
    r = cls("rotor", {"model_file": str(own_engine / "engine.toml")})
    # the same ports and parameters, in the same order, as the paper's engine's: a contract of users' scripts
    assert [v.name for v in r.variables] == [v.name for v in cls.variables]
    said = {v.name: v.description for v in r.variables}
    assert not [f"{n}: {d}" for n, d in said.items() if PAPER_WORDS.search(d)]
    assert said["X_brg0"] == "rotor spool displacement at bearing #0 (x y z)"
    assert said["X_housing0"] == "pedestal displacement under bearing #0"
    assert said["F_rub5"] == "rub force on the rotor spool node at rub ring #5"
    assert said["omega_pt"] == "speed of the rotor spool (the first spool)"
    assert said["omega_gg"] == "speed of the second spool (this engine has none)"


@pytest.mark.parametrize("cls", [Rotor, SpinningRotor])
def test_the_papers_engine_keeps_its_words(cls):
    assert cls("rotor", {}).variables == cls.variables
    said = {v.name: v.description for v in cls.variables}
    assert said["X_brg0"] == "PT displacement at bearing #0 (x y z)"
    assert said["X_housing5"] == "casing hub displacement under bearing #5"


def test_the_time_series_of_a_users_engine_says_its_words(own_engine, tmp_path):
    out = tmp_path / "r"
    assert main(["run", str(own_engine / "blade_loss.toml"), "--duration", "0.02", "--out", str(out), "--quiet",
                 "--no-figures"]) == 0
    with h5py.File(out / "timeseries.h5") as f:
        said = {k: str(f[k].attrs.get("description", "")) for k in f}
    assert said["rotor.X_brg0"] == "rotor spool displacement at bearing #0 (x y z)"
    assert not [f"{k}: {d}" for k, d in said.items() if PAPER_WORDS.search(d)]
