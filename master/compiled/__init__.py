"""The compiled fast path: a thermo-mechanical interval whose components all offer a compiled kernel runs in
one compiled loop instead of the generic Python one, with the same order, rates, extrapolation, windows and
recorded samples (a test holds them equal). The master takes it when it can and says why not when it cannot.

- :mod:`.choice`: the engine choice, :func:`~.choice.why_not` (imports no numba: a system without kernels never
  does);
- :mod:`.runner`: the runner of an interval through the compiled loop;
- :mod:`.loop_ops`: the loop (run_chunk) and its arguments as named records; the links' operations compiled from
  master/core/links.py;
- :mod:`.kernel_args`: the components' kernel arguments packed for the loop;
- :mod:`.ahead`: a helper process that builds missing kernels and tables on a fresh machine while the run starts.
"""
