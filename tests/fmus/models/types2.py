"""An FMI 2.0 co-simulation test FMU (pythonfmu) with a port of every FMI 2.0 type, a state with a settable start
value, an output computed at initialisation and a stop request (fmi2Discard + fmi2Terminated) at ``t_stop``.

Units, ranges and the enumeration are added to its modelDescription.xml after the build (tests/fmus/conftest.py):
pythonfmu 0.7 does not declare them."""
from pythonfmu import Boolean, Fmi2Causality, Fmi2Initial, Fmi2Slave, Fmi2Variability, Integer, Real, String


class types2(Fmi2Slave):

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.gain, self.n, self.flag, self.label, self.mode, self.t_stop = 2.0, 3, False, "a", 1, 10.0
        self.u, self.ui, self.ub, self.us, self.ue = 0.0, 0, False, "", 1
        self.x, self.y, self.yi, self.yb, self.ys, self.ye, self.y0 = 1.0, 0.0, 0, False, "", 1, 0.0
        par, inp, out = Fmi2Causality.parameter, Fmi2Causality.input, Fmi2Causality.output
        fixed, disc, cont = Fmi2Variability.fixed, Fmi2Variability.discrete, Fmi2Variability.continuous
        calc = Fmi2Initial.calculated
        for var in (Real("gain", causality=par, variability=Fmi2Variability.tunable),
                    Integer("n", causality=par, variability=fixed), Boolean("flag", causality=par, variability=fixed),
                    String("label", causality=par, variability=fixed), Integer("mode", causality=par, variability=fixed),
                    Real("t_stop", causality=par, variability=fixed),
                    Real("u", causality=inp, variability=cont), Integer("ui", causality=inp, variability=disc),
                    Boolean("ub", causality=inp, variability=disc), String("us", causality=inp, variability=disc),
                    Integer("ue", causality=inp, variability=disc),
                    Real("x", causality=out, variability=cont, initial=Fmi2Initial.exact),
                    Real("y", causality=out, variability=cont, initial=calc),
                    Integer("yi", causality=out, variability=disc, initial=calc),
                    Boolean("yb", causality=out, variability=disc, initial=calc),
                    String("ys", causality=out, variability=disc, initial=calc),
                    Integer("ye", causality=out, variability=disc, initial=calc),
                    Real("y0", causality=out, variability=disc, initial=calc)):
            self.register_variable(var)

    def exit_initialization_mode(self):
        self.y0 = 2.0 * self.x          # an output computed at initialisation, from the start value of x
        self._outputs()

    def _outputs(self):
        self.y = self.gain * self.x + self.u
        self.yi = self.n * self.ui
        self.yb = self.flag != self.ub
        self.ys = self.label + self.us
        self.ye = self.mode if self.ue == 1 else self.ue

    def do_step(self, current_time, step_size):
        if current_time + step_size > self.t_stop + 1e-9:
            return False                # pythonfmu: fmi2Discard, then fmi2Terminated = true
        self.x += step_size * (0.01 * self.u - self.x)
        self._outputs()
        return True
