"""ForceTable FMU: a recorded force replayed in time (physics/rigs/force_table.py)."""
from __future__ import annotations

from ...physics.rigs import force_table
from ..base import GuidewaySlave


class ForceTable(GuidewaySlave):
    """A recorded force replayed in time, linear between samples, held outside them.

    It drives a model with a measured load, for example the normal force of a measured run
    into VerticalDynamics.F_ext, as FeedKinematics' replay profile drives it with the motion."""

    description = __doc__.splitlines()[0]
    internal_state = ("time",)

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("table_file", "", None, "CSV file with a header: time [s] and the column")
        self.parameter("column", "normal_force", None, "the force column of the file [N]")
        self.output("F", "N", "the recorded force at the time")
        self.time = 0.0

    @classmethod
    def continuous_model(cls, parameters):
        return force_table.from_parameters(**parameters)

    def setup_experiment(self, start_time, stop_time, tolerance):
        self.time = start_time

    def advance(self, t, h):
        self.time = t + h

    def evaluate(self):
        return self.model().outputs(self.time, (), {})
