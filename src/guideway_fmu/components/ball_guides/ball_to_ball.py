"""BallToBallFriction FMU: the friction that contacts between neighbouring balls of one row add
to a ball guide (Lin, Duan and Okwudire 2019; physics/ball_guides/ball_row.py)."""
from __future__ import annotations

import math

import numpy as np
from ..runtime import DefaultExperiment

from ...physics.ball_guides import ball_row
from ...physics.papers import lin2019, wu2012
from ..base import GuidewaySlave


class BallToBallFriction(GuidewaySlave):
    """Ball-to-ball contact friction of one ball row; add it to the guide's other friction.

    The row's balls roll at slightly different speeds where their contact angles deviate and
    their side loads differ; gaps close, groups of touching balls push each other and part
    again, and every contact slides at u / cos(beta_0) with the metal friction coefficient. The
    balls' positions are the state, integrated by RK4 substeps with the inputs held over a step
    and a substep ending at each change of the groups (BallRow.advance); they start evenly
    spaced."""

    #: what a host runs without an experiment: a feed stroke of Lin et al. (2019)
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.14, step_size=1e-5)

    description = __doc__.splitlines()[0]
    internal_state = ("state", "time")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        # a row of Wu et al.'s carriage (the BallCarriage5DOF FMU's) of Lin et al.'s material
        self.parameter("radius", wu2012.BALL_DIAMETER / 2, "m", "ball radius R_B")
        self.parameter("conformity", wu2012.CONFORMITY, "1",
                       "groove radius / ball diameter (> 0.5)")
        self.parameter("youngs_modulus", lin2019.YOUNGS_MODULUS, "Pa",
                       "Young's modulus of balls and grooves")
        self.parameter("poisson_ratio", lin2019.POISSON_RATIO, "1",
                       "Poisson's ratio of balls and grooves")
        self.parameter("friction", lin2019.FRICTION, "1", "metal-to-metal friction coefficient mu")
        self.parameter("nominal_angle", math.radians(wu2012.CONTACT_ANGLE_DEG), "rad",
                       "nominal contact angle beta_0")
        self.parameter("balls", wu2012.BALLS_PER_ROW, None, "balls in the row's load zone (>= 2)")
        self.parameter("zone_length", wu2012.LOAD_ZONE_LENGTH, "m",
                       "length of the load zone (> balls x diameter)")
        for contact in ("BL", "BR", "TR", "TL"):
            self.parameter(f"deviation_{contact}", 0.0, "rad",
                           f"constant contact-angle deviation of the {contact} contact")
        self.parameter("wave_amplitude", 0.0, "rad", "amplitude of the rail groove's wave of "
                       "contact angle (BL: sine, BR: cosine of the rail position)")
        self.parameter("wavelength", 0.01, "m", "wavelength of the rail groove's wave (> 0)")
        self.parameter("velocity_tolerance", 1e-4, "m/s",
                       "velocity of the regularised sign of the friction force")
        self.input("u", 0.0, "m/s", "feed velocity of the carriage")
        self.input("x", 0.0, "m", "feed position of the carriage on the rail")
        self.input("F_normal", 0.0, "N", "normal load of the row (all its balls, >= 0)", True)
        self.input("F_side", 0.0, "N", "side load of the row across the rail")
        self.input("M_yaw", 0.0, "N.m", "yaw moment the row carries (side loads varying along it)")
        loads = ("u", "x", "F_normal", "F_side", "M_yaw")
        self.output("F_friction", "N", "ball-to-ball friction force on the carriage", loads)
        self.output("contact_force", "N", "sum of the ball-to-ball contact forces", loads)
        self.output("max_contact_force", "N", "largest ball-to-ball contact force", loads)
        self.output("friction_loss", "W", "power lost in the ball-to-ball contacts", loads)
        self.output("groups", "1", "number of groups of balls moving together", loads)
        self.output("epsilon_mean", "1", "mean velocity deviation epsilon of the balls "
                    "(v_B = (1 + epsilon) u / 2)", loads)
        self.state, self.time = None, 0.0

    @classmethod
    def continuous_model(cls, parameters):
        return ball_row.from_parameters(**parameters)

    def setup_experiment(self, start_time, stop_time, tolerance):
        self.time = start_time

    def initialise(self):
        self.state = np.array(self.model().initial_state(self.time, self.model_inputs()))

    def _started(self) -> np.ndarray:
        if self.state is None or len(self.state) != self.model().balls:
            self.initialise()
        return self.state

    def advance(self, t, h):
        self.state = self.model().advance(t, self._started(), self.model_inputs(), h)
        self.time = t + h

    def evaluate(self):
        return self.model().outputs(self.time, self._started(), self.model_inputs())
