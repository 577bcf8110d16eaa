"""An FMI 3.0 co-simulation test FMU (pythonfmu3) with ports of the FMI 3.0 types pythonfmu3 can declare (Float64,
Int32, Int64, UInt64, Boolean, String, Enumeration), Float64 arrays as input and output, units with offsets and
factors, a state with a settable start value, an output computed at initialisation and a terminate request
(terminateSimulation) at ``t_stop``."""
import numpy as np
from enum import Enum

from pythonfmu3 import (Boolean, Dimension, Enumeration, Fmi3Causality, Fmi3Initial, Fmi3Slave, Fmi3StepResult,
                        Fmi3Variability, Float64, Int32, Int64, String, UInt64)
from pythonfmu3.unit import Unit
from pythonfmu3.variable_types import EnumerationType


class Enum64(Enumeration):
    """pythonfmu3 0.3 reads and writes enumerations as Int64 values and expects them to say they are scalars."""
    dimensions = []

    def size(self, variables):
        return 1


class Mode(Enum):
    low = 1
    mid = 2
    high = 3


class types3(Fmi3Slave):

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.gain, self.n, self.big, self.flag, self.label, self.mode, self.t_stop = 2.0, 3, 2**40, False, "a", 1, 10.0
        self.u, self.ui, self.ul, self.uu, self.ub, self.us, self.ue = 0.0, 0, 0, 0, False, "", 1
        self.ua = np.zeros(3)
        self.x, self.y, self.yi, self.yl, self.yu, self.yb, self.ys, self.ye, self.y0 = 1.0, 0.0, 0, 0, 0, False, "", 1, 0.0
        self.ya = np.zeros(3)
        self.time = 0.0
        self.register_units([Unit("degC", K=1, offset=273.15), Unit("mm", m=1, factor=0.001)])
        par, inp, out = Fmi3Causality.parameter, Fmi3Causality.input, Fmi3Causality.output
        fixed, disc, cont = Fmi3Variability.fixed, Fmi3Variability.discrete, Fmi3Variability.continuous
        calc = Fmi3Initial.calculated
        three = [Dimension(start="3")]
        mode_type = EnumerationType("Mode", values=Mode)
        self.register_variable(Float64("time", causality=Fmi3Causality.independent, variability=cont))
        for var in (Float64("gain", causality=par, variability=Fmi3Variability.tunable, start=2.0),
                    Int32("n", causality=par, variability=fixed, start=3),
                    Int64("big", causality=par, variability=fixed, start=2**40),
                    Boolean("flag", causality=par, variability=fixed, start=False),
                    String("label", causality=par, variability=fixed, start="a"),
                    Float64("t_stop", causality=par, variability=fixed, start=10.0),
                    Float64("u", causality=inp, variability=cont, start=0.0, unit="degC"),
                    Int32("ui", causality=inp, variability=disc, start=0),
                    Int64("ul", causality=inp, variability=disc, start=0),
                    UInt64("uu", causality=inp, variability=disc, start=0),
                    Boolean("ub", causality=inp, variability=disc, start=False),
                    String("us", causality=inp, variability=disc, start=""),
                    Float64("ua", causality=inp, variability=cont, start=np.zeros(3), dimensions=three,
                            # (pythonfmu3 0.3's default array setter calls numpy's removed reshape(newshape=))
                            setter=lambda v: setattr(self, "ua", np.asarray(v, dtype=float))),
                    Float64("x", causality=out, variability=cont, start=1.0, initial=Fmi3Initial.exact),
                    Float64("y", causality=out, variability=cont, initial=calc, unit="mm"),
                    Int32("yi", causality=out, variability=disc, initial=calc),
                    Int64("yl", causality=out, variability=disc, initial=calc),
                    UInt64("yu", causality=out, variability=disc, initial=calc),
                    Boolean("yb", causality=out, variability=disc, initial=calc),
                    String("ys", causality=out, variability=disc, initial=calc),
                    Float64("ya", causality=out, variability=cont, initial=calc, dimensions=three),
                    Float64("y0", causality=out, variability=disc, initial=calc)):
            self.register_variable(var)
        self.register_variable(Enum64("mode", causality=par, variability=fixed, start=1), var_type=mode_type)
        self.register_variable(Enum64("ue", causality=inp, variability=disc, start=1), var_type=mode_type)
        self.register_variable(Enum64("ye", causality=out, variability=disc, initial=calc), var_type=mode_type)

    def exit_initialization_mode(self):
        self.y0 = 2.0 * self.x          # an output computed at initialisation, from the start value of x
        self._outputs()

    def _outputs(self):
        self.y = self.gain * self.x + self.u
        self.yi = self.n * self.ui
        self.yl = self.big + self.ul
        self.yu = self.uu + 2**63      # beyond int64 and beyond 2**53: exact only as an unsigned 64-bit integer
        self.yb = self.flag != self.ub
        self.ys = self.label + self.us
        self.ye = self.mode if self.ue == 1 else self.ue
        self.ya = 2.0 * np.asarray(self.ua, dtype=float) + self.x

    def do_step(self, current_time, step_size):
        self.x += step_size * (0.01 * self.u - self.x)
        self._outputs()
        return Fmi3StepResult(terminateSimulation=current_time + step_size >= self.t_stop - 1e-9)
