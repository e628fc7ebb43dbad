"""BallCarriage5DOF FMU: a ball-guide carriage with five degrees of freedom on Hertz balls
(Wu et al. 2012; physics/ball_guides/carriage_5dof.py)."""
from __future__ import annotations

import math

import numpy as np
from ..runtime import DefaultExperiment

from ...physics.ball_guides import carriage_5dof as bc
from ...physics.dynamics import rk4_step, substeps
from ...physics.papers import wu2012
from ..base import GuidewaySlave

#: RK4 substeps keep omega_max h below this (RK4 is stable to 2.8; 0.5 keeps the period error
#: of the stiffest mode near 1e-4)
OMEGA_STEP = 0.5
UNITS = {"u": "m", "v": "m", "phi": "rad", "theta": "rad", "psi": "rad"}
LOAD_UNITS = {"F_y": "N", "F_z": "N", "M_x": "N.m", "M_y": "N.m", "M_z": "N.m"}
WHAT = {"u": "lateral displacement along y", "v": "vertical displacement along z",
        "phi": "roll angle about x", "theta": "pitch angle about y", "psi": "yaw angle about z"}


class BallCarriage5DOF(GuidewaySlave):
    """Ball-guide carriage, 5 DOF (u, v, roll, pitch, yaw) on two rows of preloaded Hertz balls.

    M q'' = F + R(q) - C q': R the balls' restoring force (nonlinear Hertz, a ball may lose
    contact), C the balls' damping, F the load inputs plus the static_* parameters. It starts in
    static equilibrium under the loads at the start, at rest. The balls roll along the load zone
    at half the feed velocity, which modulates the stiffness at the ball-passage frequency
    u_feed / (2 pitch). The preload is an input, so that raceway wear (the Wear FMU) can take it
    away during a run. Integrated by RK4 substeps (omega_max h <= 0.5 at the state the step
    starts from) with the inputs held over a step. It stands in for VerticalDynamics plus a
    contact FMU when the guide is a ball guide."""

    #: what a host runs without an experiment: the moment-load run of Wu et al. (2012)
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.14, step_size=1e-5)

    description = __doc__.splitlines()[0]
    internal_state = ("state", "time", "started")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("mass", wu2012.MASS, "kg", "carriage mass m")
        for axis, value in zip("xyz", wu2012.INERTIA):
            self.parameter(f"inertia_{axis}", value, "kg.m2", f"moment of inertia J_{axis}")
        self.parameter("contact_angle", math.radians(wu2012.CONTACT_ANGLE_DEG), "rad",
                       "ball contact angle beta")
        self.parameter("d", wu2012.OFFSET_D, "m",
                       "distance of the contact points from the x-y plane")
        self.parameter("e", wu2012.OFFSET_E, "m",
                       "distance of the contact points from the x-z plane")
        self.parameter("balls_per_row", wu2012.BALLS_PER_ROW, None,
                       "balls in the load zone of each row")
        self.parameter("pitch", wu2012.LOAD_ZONE_LENGTH / wu2012.BALLS_PER_ROW, "m",
                       "ball spacing along x")
        self.parameter("ball_diameter", wu2012.BALL_DIAMETER, "m", "ball diameter (Hertz balls)")
        self.parameter("conformity", wu2012.CONFORMITY, "1",
                       "groove radius / ball diameter (> 0.5)")
        self.parameter("ball_stiffness", "", None, "per-row ball stiffnesses [N/m], space "
                       "separated, both rows alike: linear springs instead of Hertz balls "
                       "(empty: Hertz)")
        self.parameter("ball_damping", 30.0, "N.s/m", "normal damping of each ball in contact")
        for name, unit in LOAD_UNITS.items():
            self.parameter(f"static_{name}", 0.0, unit, f"constant part of {name}, added to the input")
        for name, unit in LOAD_UNITS.items():
            self.input(name, 0.0, unit, f"external {'force' if unit == 'N' else 'moment'} {name} "
                       f"on the carriage, held over a step")
        self.input("u_feed", 0.0, "m/s", "feed velocity of the carriage along x")
        self.input("preload", wu2012.PRELOAD, "N", "normal load of each Hertz ball at rest "
                   "(falls as the raceways wear: connect Wear.preload); > 0 at the start", True)
        for name in bc.DOF:
            self.output(name, UNITS[name], WHAT[name])
        for name in bc.DOF:
            self.output(f"{name}_dot", UNITS[name] + "/s", f"rate of the {WHAT[name]}")
        for row in (1, 2):
            self.output(f"row_load_{row}", "N", f"total normal ball load of row {row} (linear "
                        f"springs: its change from rest)", ("preload",))
        self.state, self.time, self.started = np.zeros(11), 0.0, False

    @classmethod
    def continuous_model(cls, parameters):
        return bc.from_parameters(**parameters)

    def setup_experiment(self, start_time, stop_time, tolerance):
        self.time = start_time

    def initialise(self):
        self.started = False  # stays False if there is no equilibrium
        self.state = np.array(self.model().initial_state(self.time, self.model_inputs()))
        self.started = True

    def _started(self) -> np.ndarray:
        if not self.started:  # FMI runs initialise first; its error said why it failed
            raise RuntimeError("the carriage has no start: its initialisation found no static "
                               "equilibrium")
        return self.state

    def advance(self, t, h):
        self._started()
        model, inputs = self.model(), self.model_inputs()
        omega = 2 * math.pi * model.highest_frequency(self.state, inputs["preload"])
        n = substeps(h * omega / OMEGA_STEP, "the carriage's motion (omega h <= OMEGA_STEP)")
        for k in range(n):
            self.state = rk4_step(model, t + k * h / n, self.state, inputs, h / n)
        self.time = t + h

    def evaluate(self):
        return self.model().outputs(self.time, self._started(), self.model_inputs())
