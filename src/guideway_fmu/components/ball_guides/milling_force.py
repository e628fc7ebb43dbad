"""MillingForce FMU: the cutting force of an end mill on the workpiece, a force source for the
feed unit (physics/ball_guides/milling_force.py)."""
from __future__ import annotations

import math

from ..runtime import DefaultExperiment

from ...physics.ball_guides import milling_force as mf
from ..base import GuidewaySlave


class MillingForce(GuidewaySlave):
    """End-milling force on the table: straight-fluted mill, mechanistic cutting and edge forces.

    The feed per tooth follows the feed velocity input; the tooth angles follow the time, so the
    force is periodic at the tooth-passing frequency teeth x spindle_speed. Evaluated exactly at
    the communication points."""

    #: what a host runs without an experiment: a milling pass of Zhang et al. (2019)
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.2, step_size=1e-4)

    description = __doc__.splitlines()[0]
    internal_state = ("time",)

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("spindle_speed", 200.0, "Hz", "spindle speed n [rev/s]")
        self.parameter("teeth", 3, None, "number of teeth N")
        self.parameter("axial_depth", 2e-3, "m", "axial depth of cut a")
        self.parameter("entry_angle", 0.0, "rad", "immersion angle where a tooth enters the cut")
        self.parameter("exit_angle", math.pi, "rad", "immersion angle where it leaves (pi: slotting)")
        # cutting and edge coefficients of the order reported for aluminium alloys
        for name, value, unit, what in (
                ("K_tc", 800e6, "Pa", "tangential cutting coefficient"),
                ("K_rc", 170e6, "Pa", "radial cutting coefficient"),
                ("K_ac", 220e6, "Pa", "axial cutting coefficient"),
                ("K_te", 28e3, "N/m", "tangential edge coefficient"),
                ("K_re", 31e3, "N/m", "radial edge coefficient"),
                ("K_ae", 2e3, "N/m", "axial edge coefficient")):
            self.parameter(name, value, unit, what)
        self.parameter("start_angle", 0.0, "rad", "immersion angle of tooth 0 at t = 0")
        self.input("u_feed", 0.0, "m/s", "feed velocity (sets the feed per tooth)")
        for name in mf.FORCES:
            self.output(name, "N", f"cutting force {name} on the workpiece (table frame)",
                        depends=("u_feed",))
        self.time = 0.0

    @classmethod
    def continuous_model(cls, parameters):
        return mf.from_parameters(**parameters)

    def setup_experiment(self, start_time, stop_time, tolerance):
        self.time = start_time

    def advance(self, t, h):
        self.time = t + h

    def evaluate(self):
        return self.model().outputs(self.time, (), self.model_inputs())
