"""Many FMUs in one process: loaded, stepped, freed, and the process exits cleanly.

pythonfmu 0.7's binary (copied into every FMU we export) stays loaded until the process ends, whatever the host's
dlclose (its C++ template statics are STB_GNU_UNIQUE symbols), and then released its global interpreter state
twice: its static destructor freed the shared pointer's control block, its ``__attribute__((destructor))`` then
released the freed block again. Reading 1 there (whatever the freed memory then held) freed it twice: the
intermittent "corrupted double-linked list" at exit of tests/fmus/test_export.py::test_exported_fmu_needs_no_rotorcosim,
likelier with every copy of the binary loaded. Our slave releases that state from a Python ``atexit`` first
(fmus/slave_template.py, ``_release_at_exit``). valgrind sees the use after free at every exit, crash or not:
the regression check (with a control that undoes the fix). Each test runs its host in a process of its own (the exit is what is checked).
"""
from __future__ import annotations

import re
import shutil
import subprocess
import sys

import pytest

#: the FMUs loaded at once in one process (each concurrent instance is its own extraction: its own copy of the
#: binary, as a sweep or a UQ loading many FMUs has)
N = 100

_ROTORCOSIM_HOST = r"""
import sys
import numpy as np
from rotorcosim.fmus.importer import load_fmu_component

comps = [load_fmu_component(sys.argv[1], f"m{i}", {"k": 40.0 + i}) for i in range(int(sys.argv[2]))]
for c in comps:
    c.setup(0.0)
    for k in range(10):
        c.set_inputs({"F": np.array([1.0])})
        c.do_step(k * 1e-3, 1e-3)
moved = sum(float(c.y["x"][0]) != 0.1 for c in comps)
copies = {l.split()[5] for l in open("/proc/self/maps") if "/binaries/linux64/" in l and ".so" in l}  # "(deleted)" too
for c in comps:
    c.terminate()
del comps, c
import gc; gc.collect()
print(moved, len(copies))
"""

_FMPY_HOST = r"""
import sys, fmpy
n = int(sys.argv[2])
for i in range(n):
    fmpy.simulate_fmu(sys.argv[1], stop_time=0.01, output_interval=1e-3, start_values={"F": 1.0})
copies = {l.split()[5] for l in open("/proc/self/maps") if "/binaries/linux64/" in l and ".so" in l}  # "(deleted)" too
print(n, len(copies))
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the binaries' copies are counted in /proc/self/maps")
def test_a_hundred_fmus_in_one_rotorcosim_process(mass_fmu):
    """100 instances of one exported FMU alive at once in rotorcosim's importer (100 copies of the binary, all
    still mapped after they are freed), each stepped 10 times, then freed: exit status 0, nothing on stderr."""
    out = subprocess.run([sys.executable, "-c", _ROTORCOSIM_HOST, str(mass_fmu), str(N)], capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stderr == ""
    assert out.stdout.split() == [str(N), str(N)]   # every instance moved; N copies of the binary were loaded


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the binaries' copies are counted in /proc/self/maps")
def test_a_hundred_fmus_in_one_fmpy_process(mass_fmu):
    """The same in a third-party host without rotorcosim: fmpy simulating the FMU 100 times (each time a fresh
    extraction, so 100 copies of the binary that fmpy's dlclose cannot unload)."""
    out = subprocess.run([sys.executable, "-I", "-c", _FMPY_HOST, str(mass_fmu), str(N)], capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stderr == ""
    assert out.stdout.split() == [str(N), str(N)]


#: the host of the valgrind tests: fmpy simulating the FMU once; ``without-release`` undoes the fix (the slave's
#: atexit release of pythonfmu's interpreter state is not registered), the control that shows the check finds the
#: defect it is there for
_FMPY_HOST_UNDONE = ("import sys, atexit\n"
                     "if sys.argv[3] == 'without-release':\n"
                     "    register = atexit.register\n"
                     "    atexit.register = lambda f, *a, **k: (f if getattr(f, '__name__', '') == "
                     "'finalizePythonInterpreter' else register(f, *a, **k))\n" + _FMPY_HOST)


def _memcheck(fmu, tmp_path, mode: str) -> tuple[list[str], str]:
    """(every error memcheck reports about freed memory: a read or write into a freed block, a free of a freed or
    foreign pointer; the whole report) of an fmpy process that runs ``fmu`` once and exits.

    ``PYTHONMALLOC=malloc``: every Python object is a block of its own, so that memcheck sees a use of a freed
    one too. ``--undef-value-errors=no``: with the system allocator CPython 3.11 itself reports 622 uses of
    uninitialised values in ``python -c pass`` alone (26 contexts, every one from an integer built with an
    uninitialised digit that it then multiplies by its size 0: _PyLong_FromByteArray, PyLong_FromString,
    long_bitwise -> maybe_small_long), none with pymalloc, none from this project; they say nothing about a
    use after free."""
    python = getattr(sys, "_base_executable", sys.executable)
    script = tmp_path / "host.py"
    script.write_text(_FMPY_HOST_UNDONE)
    out = subprocess.run(["valgrind", "--error-limit=no", "--undef-value-errors=no", python, str(script),
                          str(fmu), "1", mode], capture_output=True, text=True, timeout=900,
                         env={"PYTHONMALLOC": "malloc", "PATH": "/usr/bin:/bin"})
    assert out.returncode == 0, out.stderr[-3000:]
    assert out.stdout.split() == ["1", "1"]
    report = re.sub(r"^==\d+== ?", "", out.stderr, flags=re.M)
    assert "ERROR SUMMARY" in report, report[-3000:]
    errors = [b.strip() for b in report.split("\n\n") if re.match(r"\s*(Invalid|Mismatched)", b)]
    freed = [e for e in errors if " free'd" in e or e.startswith(("Invalid free", "Mismatched"))]
    return freed, report


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("valgrind") is None, reason="valgrind is not installed: the use after free at "
                                                             "exit cannot be seen without a crash")
def test_no_use_after_free_at_exit(mass_fmu, tmp_path):
    """Under valgrind, an fmpy process that ran one of our FMUs touches no freed memory and frees nothing twice,
    to its last exit handler (without the fix, at every exit: "Invalid read of size 4 at
    finalizePythonInterpreter", a block freed by __run_exit_handlers: the next test)."""
    freed, report = _memcheck(mass_fmu, tmp_path, "as-shipped")
    assert not freed, freed[0]
    assert "finalizePythonInterpreter" not in report


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("valgrind") is None, reason="valgrind is not installed: the use after free at "
                                                             "exit cannot be seen without a crash")
def test_the_check_finds_the_use_after_free_without_the_fix(mass_fmu, tmp_path):
    """The control: with the slave's atexit release undone, the same check finds pythonfmu's release of its freed
    interpreter state in the binary's destructor (so the test above can fail)."""
    freed, _ = _memcheck(mass_fmu, tmp_path, "without-release")
    assert any("finalizePythonInterpreter" in e and "__run_exit_handlers" in e for e in freed), freed
