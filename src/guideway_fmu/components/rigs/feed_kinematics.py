"""FeedKinematics FMU: the prescribed horizontal motion of the moving body."""
from __future__ import annotations

from ...physics.rigs import feed_motion as fp
from ..base import GuidewaySlave


class FeedKinematics(GuidewaySlave):
    """Feed position, velocity and acceleration from a chosen profile or from the u_cmd input.

    Analytic profiles, the table and the replay are evaluated exactly at the communication
    points. With profile "input", u follows u_cmd, x integrates u_cmd held over each step
    exactly, and a is the backward difference of u_cmd over the last step.
    """

    description = __doc__.splitlines()[0]
    internal_state = ("time", "x_input", "u_previous", "a_input")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        bi, osc, tr = fp.BiHarmonic(), fp.Oscillating(), fp.Trapezoid()
        self.parameter("profile", "biharmonic", None, f"feed profile, one of {fp.PROFILES}",
                       choices=fp.PROFILES)
        self.parameter("frequency", bi.frequency, "Hz", "feed frequency f (biharmonic, oscillating)")
        self.parameter("amplitude1", bi.amplitude1, "m/s", "biharmonic: amplitude A1 at f (eq. 1a)")
        self.parameter("amplitude2", bi.amplitude2, "m/s", "biharmonic: amplitude A2 at 3f (eq. 1a)")
        self.parameter("phase1", bi.phase1, "rad", "biharmonic: phase phi1")
        self.parameter("phase2", bi.phase2, "rad", "biharmonic: phase phi2")
        self.parameter("mean_velocity", osc.mean, "m/s", "oscillating: nominal speed u_bar (eq. 33)")
        self.parameter("oscillation_amplitude", osc.amplitude, "m/s", "oscillating: amplitude a (eq. 33)")
        self.parameter("velocity", fp.Constant().velocity, "m/s", "constant: velocity")
        self.parameter("distance", tr.distance, "m", "trapezoid: move distance (sign = direction)")
        self.parameter("v_max", tr.v_max, "m/s", "trapezoid: velocity limit")
        self.parameter("a_max", tr.a_max, "m/s2", "trapezoid: acceleration limit")
        self.parameter("t_start", tr.t_start, "s", "trapezoid: start time of the move")
        self.parameter("table_file", "", None,
                       "table: CSV with columns time and feed_velocity (or u); replay: CSV with "
                       "time, feed_position, feed_velocity, feed_acceleration")
        self.input("u_cmd", 0.0, "m/s", "commanded velocity, used when profile is 'input'")
        self.output("x", "m", "feed position")
        self.output("u", "m/s", "feed velocity", depends=("u_cmd",))
        self.output("a", "m/s2", "feed acceleration", depends=("u_cmd",))
        self.time, self.x_input, self.u_previous, self.a_input = 0.0, 0.0, 0.0, 0.0

    @classmethod
    def continuous_model(cls, parameters):
        profile = fp.from_parameters(**parameters)
        if profile is None:
            raise ValueError("profile 'input' (the velocity from the u_cmd input) has no "
                             "continuous-time model; choose an analytic or a table profile")
        return fp.FeedModel(profile)

    def build_model(self):
        profile = fp.from_parameters(**self.parameter_values())
        return None if profile is None else fp.FeedModel(profile)

    def setup_experiment(self, start_time, stop_time, tolerance):
        self.time = start_time

    def initialise(self):
        self.x_input, self.u_previous, self.a_input = 0.0, self.u_cmd, 0.0

    def advance(self, t, h):
        self.x_input += self.u_cmd * h
        self.a_input = (self.u_cmd - self.u_previous) / h
        self.u_previous = self.u_cmd
        self.time = t + h

    def evaluate(self):
        if self.model() is None:
            return {"x": self.x_input, "u": self.u_cmd, "a": self.a_input}
        return self.model().outputs(self.time, (), {})
