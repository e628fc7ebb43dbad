"""FeedUnitErrors FMU: the five errors of a four-slider ball-guide feed unit under a cutting
force (Zhang, Wang and Le 2019; physics/ball_guides/feed_unit.py)."""
from __future__ import annotations

import math

from ..runtime import DefaultExperiment

from ...physics.ball_guides import feed_unit as fu
from ...physics.ball_guides import hertz_point
from ...physics.papers import zhang2019
from ..base import GuidewaySlave

FORCE_INPUTS = ("F_x", "F_y", "F_z")
POINT_INPUTS = ("point_x", "point_y", "point_z", "x_feed")
ERROR_UNITS = {"delta_y": "m", "delta_z": "m", "epsilon_x": "rad", "epsilon_y": "rad",
               "epsilon_z": "rad"}
WHAT = {"delta_y": "lateral error of the table centre (straightness along y)",
        "delta_z": "vertical error of the table centre (straightness along z)",
        "epsilon_x": "roll error of the table about x", "epsilon_y": "pitch error about y",
        "epsilon_z": "yaw error about z"}


class FeedUnitErrors(GuidewaySlave):
    """Four-slider ball-guide feed unit: five errors of the table under a force at a load point.

    Quasi-static: every evaluation finds the table's equilibrium on the preloaded Hertz balls of
    its four sliders (four rows each, with or without the load-dependent contact angle) under the
    force inputs acting at the load point (point_x - x_feed, point_y, point_z) from the table's
    centre; connect the table's feed position to x_feed when the tool stands and the table moves.
    Outputs the five errors of the table centre, the load point's displacement and the largest
    ball load."""

    #: what a host runs without an experiment: a milling pass of Zhang et al. (2019)
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.2, step_size=1e-4)

    description = __doc__.splitlines()[0]

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("half_span_x", 0.1, "m", "W_x: sliders at x = +-W_x")
        self.parameter("half_span_y", 0.15, "m", "W_y: rails at y = +-W_y")
        self.parameter("row_spacing_y", 0.023, "m", "L_y: between a slider's left and right rows")
        self.parameter("row_spacing_z", 0.010, "m", "L_z: between a slider's upper and lower rows")
        self.parameter("contact_angle", math.radians(zhang2019.CONTACT_ANGLE_DEG), "rad",
                       "ball contact angle alpha at rest")
        self.parameter("balls_per_row", 12, None, "balls in the load zone of each row")
        self.parameter("pitch", 4.8e-3, "m", "ball spacing along x")
        self.parameter("ball_diameter", 4.7625e-3, "m", "ball diameter D")
        self.parameter("conformity", 0.52, "1", "groove radius / ball diameter f (> 0.5)")
        self.parameter("preload", 20.0, "N", "normal load of every ball at rest")
        self.parameter("youngs_modulus", hertz_point.STEEL[0], "Pa", "Young's modulus of balls and grooves")
        self.parameter("poisson_ratio", hertz_point.STEEL[1], "1", "Poisson's ratio of balls and grooves")
        self.parameter("angle_change", True, None, "contact angle follows the load (eqs. 9-10); "
                       "false: constant")
        for name in FORCE_INPUTS:
            self.input(name, 0.0, "N", f"force {name} on the table (cutting force on the workpiece)")
        for name, what in zip(POINT_INPUTS, ("x of the load point from the table centre",
                                             "y of the load point from the table centre",
                                             "height of the load point above the ball rows",
                                             "the table's travel, subtracted from point_x")):
            self.input(name, 0.0, "m", what)
        inputs = FORCE_INPUTS + POINT_INPUTS
        for name, unit in ERROR_UNITS.items():
            self.output(name, unit, WHAT[name], depends=inputs)
        for axis in "xyz":
            self.output(f"tool_d_{axis}", "m", f"displacement of the load point along {axis}",
                        depends=inputs)
        self.output("max_ball_load", "N", "largest normal load of any ball", depends=inputs)

    @classmethod
    def continuous_model(cls, parameters):
        return fu.from_parameters(**parameters)
