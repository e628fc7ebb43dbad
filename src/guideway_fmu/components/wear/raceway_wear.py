"""Wear FMU: raceway wear of a linear ball guide over its running distance and the preload it
costs (Zhang, Wang and Jiang, fractal-creep wear; physics/wear/raceway_wear.py)."""
from __future__ import annotations

import numpy as np
from ..runtime import DefaultExperiment

from ...physics.wear import raceway_wear
from ..base import GuidewaySlave

GUIDE = raceway_wear.Guide()  # the LG20 defaults


class Wear(GuidewaySlave):
    """Raceway wear of a ball guide's slider along its running distance, and its preload.

    Meant for a slow time base: each step advances the wear along the increase of the
    ``distance`` input (the running distance, which never decreases) under the ``F_load``
    input held; time itself plays no part. Feed ``preload`` to a contact FMU's preload (for
    example BallCarriage5DOF.preload) and the fast model stiffens or softens as the raceways
    wear. The guide starts new at the first distance it is given."""

    #: what a host runs without an experiment: the shipped wear scenario
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.1, step_size=1e-4)

    description = __doc__.splitlines()[0]
    internal_state = ("wear", "distance_last")
    without_time_model = ("it advances along its running-distance input, not in time "
                          "(guideway-fmu wear computes the same wear directly)")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("ball_diameter", GUIDE.ball_diameter, "m", "ball diameter D_b")
        self.parameter("conformity", GUIDE.conformity, "1", "groove radius / ball diameter (> 0.5)")
        self.parameter("balls_per_row", GUIDE.balls_per_row, None, "loaded balls in each row n_s")
        self.parameter("contact_angle", GUIDE.contact_angle, "rad", "contact angle alpha")
        self.parameter("initial_deformation", GUIDE.preload_deformation, "m",
                       "each ball's approach at rest in the new guide delta_0 (Table 1)")
        self.parameter("youngs_modulus", GUIDE.youngs_modulus, "Pa", "Young's modulus of balls and raceways")
        self.parameter("poisson_ratio", GUIDE.poisson_ratio, "1", "Poisson's ratio of balls and raceways")
        self.parameter("yield_strength", GUIDE.yield_strength, "Pa", "yield strength sigma_s")
        self.parameter("hardness", 0.0, "Pa", "hardness H of the raceway (0: 2.8 yield_strength)")
        self.parameter("fractal_dimension", GUIDE.fractal_dimension, "1",
                       "fractal dimension D of the raceway surface (2 < D < 3)")
        self.parameter("fractal_scale", GUIDE.fractal_scale, "m", "fractal scale G of the raceway")
        self.parameter("wear_coefficient", GUIDE.wear_coefficient, "1", "fractal wear coefficient K_f")
        self.parameter("friction", GUIDE.friction, "1", "sliding friction coefficient mu of the creep")
        self.parameter("hysteresis", GUIDE.hysteresis, "1", "elastic hysteresis coefficient tau")
        self.parameter("spacing_ratio", GUIDE.spacing_ratio, "1", "ball centre distance / diameter D_w")
        self.parameter("rolling_resistance", True, None, "true: the tangential force is the "
                       "balls' rolling resistance; false: tangential_ratio")
        self.parameter("tangential_ratio", 0.1, "1", "tangential force / (mu normal load) when "
                       "rolling_resistance is false, in [0, 1)")
        self.parameter("lateral_ratio", 0.0, "1", "lateral tangential force / (mu normal load)")
        self.input("F_load", 0.0, "N", "vertical load on the slider toward the rail")
        self.input("distance", 0.0, "m", "running distance of the slider (never decreases)", True)
        self.output("preload_deformation", "m", "every ball's approach at rest, delta_0 minus the "
                    "wear depth (negative: clearance)")
        self.output("preload", "N", "every ball's load at rest (0 once the preload is lost)")
        self.output("wear_depth", "m", "slider raceway wear averaged over the opposed rows")
        self.output("wear_upper", "m", "slider raceway wear of the upper (loaded) rows")
        self.output("wear_lower", "m", "slider raceway wear of the lower rows")
        loaded = ("F_load",)
        self.output("vertical_displacement", "m", "slider's sinking toward the rail under the "
                    "load, elastic plus what wear adds", loaded)
        self.output("ball_load_upper", "N", "load of a ball in an upper row", loaded)
        self.output("ball_load_lower", "N", "load of a ball in a lower row", loaded)
        self.wear, self.distance_last = np.zeros(2), 0.0

    def build_model(self):
        return raceway_wear.from_parameters(**self.parameter_values())

    def initialise(self):
        self.wear, self.distance_last = np.zeros(2), float(self.distance)

    def advance(self, t, h):
        run = self.distance - self.distance_last
        if run < 0.0:
            raise ValueError(f"input distance must not decrease (it is the running distance): "
                             f"{self.distance!r} m after {self.distance_last!r} m")
        self.wear = self.model().advance(self.wear, self.model_inputs(), run)
        self.distance_last = float(self.distance)

    def evaluate(self):
        out = self.model().outputs(self.wear, self.model_inputs())
        return {name: out[name] for name in self._depends}
