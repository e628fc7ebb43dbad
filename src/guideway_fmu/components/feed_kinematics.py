"""FeedKinematics FMU: the prescribed horizontal motion of the moving body."""
from __future__ import annotations

from ..physics import feed_profiles as fp
from .base import GuidewaySlave

PROFILES = ("biharmonic", "oscillating", "constant", "trapezoid", "table", "input")


class FeedKinematics(GuidewaySlave):
    """Feed position, velocity and acceleration from a chosen profile or from the u_cmd input.

    Analytic profiles and the table are evaluated exactly at the communication points. With
    profile "input", u follows u_cmd, x integrates u_cmd held over each step exactly, and a is
    the backward difference of u_cmd over the last step.
    """

    description = __doc__.splitlines()[0]
    internal_state = ("time", "x_input", "u_previous", "a_input")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        bi, osc, tr = fp.BiHarmonic(), fp.Oscillating(), fp.Trapezoid()
        self.parameter("profile", "biharmonic", None, f"feed profile, one of {PROFILES}")
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
                       "table: CSV with columns time and feed_velocity (or u)")
        self.input("u_cmd", 0.0, "m/s", "commanded velocity, used when profile is 'input'")
        self.output("x", "m", "feed position")
        self.output("u", "m/s", "feed velocity", depends=("u_cmd",))
        self.output("a", "m/s2", "feed acceleration", depends=("u_cmd",))
        self.time, self.x_input, self.u_previous, self.a_input = 0.0, 0.0, 0.0, 0.0

    def build_model(self):
        name = self.profile.strip().lower()
        if name == "input":
            return None
        if name == "table":
            return self._table()
        params = {
            "biharmonic": dict(amplitude1=self.amplitude1, amplitude2=self.amplitude2,
                               phase1=self.phase1, phase2=self.phase2, frequency=self.frequency),
            "oscillating": dict(mean=self.mean_velocity, amplitude=self.oscillation_amplitude,
                                frequency=self.frequency),
            "constant": dict(velocity=self.velocity),
            "trapezoid": dict(distance=self.distance, v_max=self.v_max, a_max=self.a_max,
                              t_start=self.t_start),
        }.get(name)
        if params is None:
            raise ValueError(f"parameter profile must be one of {PROFILES}, got {self.profile!r}")
        return fp.make_profile(name, **params)

    def _table(self):
        if not self.table_file:
            raise ValueError("parameter table_file must name a CSV file when profile is 'table'")
        try:
            return fp.Table.from_csv(self.table_file)
        except OSError as exc:
            raise ValueError(f"parameter table_file: cannot read {self.table_file!r}: "
                             f"{exc.strerror or exc}") from exc

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
        profile = self.model()
        if profile is None:
            return {"x": self.x_input, "u": self.u_cmd, "a": self.a_input}
        x, u, a = profile.evaluate(self.time)
        return {"x": float(x), "u": float(u), "a": float(a)}
