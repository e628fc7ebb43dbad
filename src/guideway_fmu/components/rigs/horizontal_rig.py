"""HorizontalRig FMU: the drive force of a horizontal rig from the feed motion and the friction."""
from __future__ import annotations

from ...physics.rigs import horizontal
from ..base import GuidewaySlave


class HorizontalRig(GuidewaySlave):
    """Drive force m a - F_friction (+ sensor offset) of a drive moving a mass against friction.

    Algebraic, no state (physics/rigs/horizontal.py).
    """

    description = __doc__.splitlines()[0]
    role = "diagnosis"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("mass", 1.0, "kg", "moving mass m the drive accelerates (>= 0)")
        self.parameter("drive_offset", 0.0, "N", "constant offset (sensor zero) of drive_force")
        self.parameter("friction_offset", 0.0, "N", "constant offset (sensor zero) of friction_force")
        self.input("a", 0.0, "m/s2", "feed acceleration of the moving part")
        self.input("F_friction", 0.0, "N", "friction force on the moving part (opposing its motion)")
        self.output("drive_force", "N", "force the drive applies to the moving part",
                    ("a", "F_friction"))
        self.output("friction_force", "N", "friction resistance along the motion, -F_friction",
                    ("F_friction",))

    @classmethod
    def continuous_model(cls, parameters):
        return horizontal.from_parameters(**parameters)
