"""A component step that never returns ends the run with a clear error (in process) instead of hanging."""
import json
import subprocess
import sys
import textwrap
import time


def test_hung_step_ends_the_process_with_a_clear_error(tmp_path):
    script = textwrap.dedent(f"""
        import time
        import numpy as np
        from rotorcosim.components.contract import Component, Variable
        from rotorcosim.components.registry import register
        from rotorcosim.master.cli.run import execute
        from rotorcosim.master.scenario.build import parse

        @register("testing.stuck")
        class Stuck(Component):
            variables = (Variable("y", "output", unit="m"),)
            def do_step(self, t, h):
                if t >= 0.005:
                    time.sleep(3600)   # like a binary stuck in a loop
                self.y["y"] = np.array([t])

        sc = parse({{"components": {{"c": {{"implementation": "testing.stuck"}}}},
                    "schedule": {{"kind": "monolithic", "duration": 1.0, "step": 1e-3}},
                    "outputs": {{"record": ["c.y"], "record_step": 1e-3}}}})
        execute(sc, {str(tmp_path / "o")!r}, figures=False, step_timeout=1.0)
    """)
    t0 = time.perf_counter()
    res = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert time.perf_counter() - t0 < 100
    assert res.returncode == 1
    lines = [l for l in res.stderr.splitlines() if l.strip()]
    assert len(lines) == 1 and "Traceback" not in res.stderr
    assert lines[0].startswith("rotorcosim run: error: a component's step timed out: c did not return from its step at "
                               "t = 0.005 s within 1 s (the step time limit)"), lines[0]
    s = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert s["status"] == "failed" and s["error"].startswith("StepTimedOut: c did not return")
    # what was recorded is kept: the buffered rows written, the file closed under its name, marked incomplete
    # (before: timeseries.h5.part holding the rows of earlier flushes only, none in a run this short)
    import h5py

    assert s["timeseries"] == "timeseries.h5" and not (tmp_path / "o" / "timeseries.h5.part").exists()
    with h5py.File(tmp_path / "o" / "timeseries.h5") as f:
        assert f.attrs["complete"] == False and "did not return" in f.attrs["error"]  # noqa: E712 (numpy bool)
        assert list(f["time"][()]) == [0.0, 0.001, 0.002, 0.003, 0.004, 0.005]
        assert list(f["c.y"][()].ravel()) == [0.0, 0.0, 0.001, 0.002, 0.003, 0.004]


def test_watchdog_costs_nothing_when_steps_return(tmp_path):
    from rotorcosim import scenarios
    from rotorcosim.master.core import algorithm
    from rotorcosim.master.cli.run import execute
    from rotorcosim.master.scenario.build import load_scenario

    s = execute(load_scenario(scenarios.path("toy_thermomechanical")), tmp_path / "o", duration=1.0, figures=False,
                step_timeout=0.5)
    assert s["status"] == "complete"
    assert algorithm.CALL is None  # removed after the run
