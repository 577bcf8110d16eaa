"""An FMI 2.0 co-simulation test FMU (pythonfmu) that resets its parameter ``k`` to its default in
fmi2SetupExperiment, as some tools' FMUs do (a 20-sim FMU of libcosim's demo system lost its mt0_init so): a
parameter written before setupExperiment only is lost; fmpy and libcosim write them after it. Output y = k."""
from pythonfmu import Fmi2Causality, Fmi2Initial, Fmi2Slave, Fmi2Variability, Real


class resets2(Fmi2Slave):

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.k, self.y = 1.0, 0.0
        self.register_variable(Real("k", causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed))
        self.register_variable(Real("y", causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                                    initial=Fmi2Initial.calculated))

    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        self.k = 1.0

    def exit_initialization_mode(self):
        self.y = self.k

    def do_step(self, current_time, step_size):
        self.y = self.k
        return True
