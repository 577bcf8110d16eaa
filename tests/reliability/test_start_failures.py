"""A run that fails before it computes anything ends with that failure alone and leaves no folder; an event set
after the end of a run is warned; a static load past a bearing's validity is warned, and "did not converge" is
said only when the residual says so."""
from __future__ import annotations


import pytest

import rotorcosim
from rotorcosim.master.cli import main


def call(capsys, *argv):
    rc = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return rc, out, err


def last_line(err: str) -> str:
    assert "Traceback" not in err and "may be a bug" not in err, err
    return [x for x in err.splitlines() if x.strip()][-1]


def test_a_run_refused_at_a_standing_start_leaves_no_folder(tmp_path, capsys):
    """The cycle of the held outputs has no period at 0 rev/min: refused at t = 0, before any step (was: exit 2
    with summary.json and timeseries.h5 left behind)."""
    rc, _, err = call(capsys, "run", "jeffcott_rundown", "--set", "spool.speed_rpm=0", "--duration", "0.01",
                      "--no-figures", "--out", tmp_path / "o")
    assert rc == 2
    assert "cycle signal spool.Omega is 0 (SI) at t = 0 s: no cycle period" in last_line(err)
    assert "summary" not in err
    assert not (tmp_path / "o").exists()


def test_a_file_that_cannot_be_opened_at_set_up_is_the_one_error(tmp_path, monkeypatch):
    """HDF5 refusing the run's own new time series ("unable to lock file", seen under load) ends the run with
    that error alone: no second error of an observer that never started (was: 'RundownTrack' object has no
    attribute 'cols' in the summary), and nothing left in the folder."""
    import h5py

    real = h5py.File

    def locked(name, mode="r", *args, **kwargs):
        if str(name).endswith(".part") and mode == "r+":
            raise OSError("Unable to open file (unable to lock file, errno = 11, error message = 'Resource "
                          "temporarily unavailable')")
        return real(name, mode, *args, **kwargs)

    monkeypatch.setattr(h5py, "File", locked)
    sc = rotorcosim.load_scenario("jeffcott_rundown")
    with pytest.raises(OSError, match="unable to lock file") as info:
        rotorcosim.simulate(sc, duration=0.01, out=tmp_path / "o", figures=False, progress=False)
    assert "cols" not in str(info.value) and getattr(info.value, "result", None) is None
    assert not (tmp_path / "o").exists()


def test_a_lock_on_another_descriptor_of_the_runs_own_file_refuses_nothing(tmp_path):
    """A child process that another thread starts while the recorder creates its file (the figure workers) holds a
    copy of the file's descriptor, and with it HDF5's lock, until its exec closes it: the reopening for appending
    was refused now and then ("unable to lock file, errno = 11", a sweep's case failing). The recorder opens its
    own ``.part`` file, which no other process opens, without HDF5's lock (recorder_hdf5.LOCKING): an exclusive
    lock held on another descriptor of it refuses neither the first file of a layout (made by h5py) nor the next
    (copied from the template), and the file holds its layout."""
    import fcntl
    import os

    import h5py

    from rotorcosim.components.contract import Variable
    from rotorcosim.master.core.phases import Phases
    from rotorcosim.master.observer import recorder_hdf5

    recorder_hdf5.TEMPLATES.clear()
    variables = {"c.x": Variable("x", "output", 2, "m", "a signal")}
    for name in ("first", "second"):
        tmp = tmp_path / f"{name}.h5.part"
        tmp.write_bytes(b"")
        held = os.open(tmp, os.O_RDWR)
        try:
            fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
            f = recorder_hdf5.create(tmp, ["c.x"], variables, 1e-3, 16, Phases())
            f.close()
        finally:
            os.close(held)
        with h5py.File(tmp, "r") as f:
            assert f["c.x"].shape == (0, 2) and "time" in f
    assert len(recorder_hdf5.TEMPLATES) == 1


@pytest.mark.parametrize("args, warned", [
    (["jeffcott_rundown", "--duration", "0.05"], None),
    (["blade_loss_rundown", "--duration", "0.02"], "spool_gg.t_fuel_cut = 15.01 s is at or after the end of the run "
                                                   "(t = 0.02 s): the fuel cut never happens in it"),
    (["blade_loss_2850", "--set", "rotor.t_blade_loss=0.5", "--duration", "0.02"],
     "rotor.t_blade_loss = 0.5 s is at or after the end of the run (t = 0.02 s): the blade loss never happens in it"),
])
def test_an_event_after_the_end_of_the_run_is_warned(tmp_path, capsys, args, warned):
    rc, _, err = call(capsys, "run", *args, "--no-figures", "--quiet", "--out", tmp_path / "o")
    assert rc == 0, err
    if warned is None:
        assert "never happens" not in err
    else:
        assert f"warning: {warned}" in err


def test_bearing_static_warns_past_validity_and_converges_at_rounding(capsys):
    """1e6 N: 14.9 GPa, past ISO 76's 4200 MPa of permanent deformation: warned. 1e8 N: the balls' force residual
    at the contact loads' rounding (~1e-8 N against ~1e7 N) was "did not converge (residual 1.1e-08 N)"; now the
    refusal, when there is one, names a residual comparable to the loads."""
    rc, out, err = call(capsys, "bearing-static", "--bearing", "0", "--radial-load", "1e6")
    assert rc == 0 and "warning: contact stress of bearing0 14910 MPa is above 4200 MPa" in err
    for load in ("1e8", "1e9"):
        rc, out, err = call(capsys, "bearing-static", "--bearing", "0", "--radial-load", load)
        line = last_line(err)
        if rc == 2:
            assert "did not converge (residual" in line and "against contact loads up to" in line, line
            residual = float(line.split("(residual ")[1].split(" N")[0])
            loads = float(line.split("contact loads up to ")[1].split(" N")[0])
            assert residual > 1e-12 * loads, line   # a failure the residual shows
        else:
            assert rc == 0 and "warning: contact stress" in err

