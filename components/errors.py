"""The errors of the component contract (:mod:`.contract`), apart so that the value checks can raise them."""


class ContractError(ValueError):
    """A component or its use breaks the contract (unknown variable, wrong size, bad value)."""


class Diverged(RuntimeError):
    """Raised by ``do_step`` when the component's own state left the domain of its equations (a journal into the
    damper wall): the master reports a divergence, as for a non-finite output."""


class StepTimeout(Exception):
    """Raised by ``do_step`` when the step did not return within the component's time limit (an FMU run in a
    process of its own, stopped by the master's side): the master reports a timed-out step, not a divergence."""


class ProcessDied(Exception):
    """Raised by ``do_step`` when the process computing the component's step died (an FMU run in a process of its
    own that crashed or was killed): the master reports a crash, not a divergence."""


class StopRequested(Exception):
    """Raised by ``do_step`` when the component asks to end the simulation (FMI 2: ``fmi2Discard`` with the
    ``fmi2Terminated`` status; FMI 3: ``terminateSimulation`` / early return from ``fmi3DoStep``).

    The component has advanced to ``t_stop`` (at most the step's end) and its outputs are valid there: the
    master ends the run at that time and keeps what was computed (a stop is an answer, not a failure)."""

    def __init__(self, component: str, t_stop: float, reason: str = ""):
        self.component = component
        self.t_stop = float(t_stop)
        self.reason = reason
        super().__init__(f"{component} asked to stop the simulation at t = {self.t_stop:.9g} s"
                         + (f" ({reason})" if reason else ""))
