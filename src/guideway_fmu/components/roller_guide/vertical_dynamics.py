"""VerticalDynamics FMU: the carriage's vertical degree of freedom (Soleimanian et al. 2020, eq. 1b)."""
from __future__ import annotations

from ...physics.roller_guide import carriage
from ...physics.roller_guide.roller_law import EXPONENT, OpposedRows
from ..base import GuidewaySlave


class VerticalDynamics(GuidewaySlave):
    """M y'' = M g + F_e(t) + F_ext - F_contact, y positive along gravity and the external load.

    F_e(t) = load_static + load_amplitude sin(2 pi load_frequency t + load_phase) is the external
    load of eq. 1b, evaluated at every instant; the F_ext input is held over a step.
    Over each communication step the contact force is extrapolated with the K_contact and
    C_contact inputs (leave them unconnected, 0, to hold F_contact constant), or, when
    law_force_1um > 0, it is the contact's force law given by the law_* inputs (the two opposed
    roller rows of physics/roller_guide/roller_law.OpposedRows, films moving at the given rates) plus
    C_contact y_dot, evaluated at every instant; the ODE is integrated with RK4 substeps
    (physics/roller_guide/carriage.py): stable for K, C >= 0 at any step.
    """

    description = __doc__.splitlines()[0]
    internal_state = ("y", "y_dot", "time")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("mass", carriage.Carriage.mass, "kg", "mass M of the moving body (rail)")
        self.parameter("gravity", carriage.Carriage.gravity, "m/s2", "gravitational acceleration along +y")
        self.parameter("load_static", 0.0, "N", "static part of the external load F_e")
        self.parameter("load_amplitude", 0.0, "N", "amplitude of the harmonic external load F_e")
        self.parameter("load_frequency", 0.0, "Hz", "frequency of the harmonic external load F_e")
        self.parameter("load_phase", 0.0, "rad", "phase of the harmonic external load F_e at t = 0")
        self.parameter("y_start", 0.0, "m", "displacement at the start time")
        self.parameter("y_dot_start", 0.0, "m/s", "velocity at the start time")
        self.input("F_contact", 0.0, "N", "net contact force on the body, opposing positive y")
        self.input("F_ext", 0.0, "N", "further external vertical force, positive along +y, held over a step")
        self.input("K_contact", 0.0, "N/m", "tangent stiffness dF_contact/dy (optional, >= 0)",
                   non_negative=True)
        self.input("C_contact", 0.0, "N.s/m", "tangent damping dF_contact/dy_dot (optional, >= 0)",
                   non_negative=True)
        self.input("law_force_1um", 0.0, "N", "contact force law: net force of the rows at 1 um "
                   "approach (0: no law, use the tangents)", non_negative=True)
        self.input("law_exponent", EXPONENT, "1", "contact force law: exponent of the row approaches",
                   non_negative=True)
        self.input("law_sine", 1.0, "1", "contact force law: row approach per unit y")
        self.input("law_approach_upper", 0.0, "m", "contact force law: upper row approach at y = 0")
        self.input("law_approach_lower", 0.0, "m", "contact force law: lower row approach at y = 0")
        self.input("law_rate_upper", 0.0, "m/s", "contact force law: rate of the upper approach")
        self.input("law_rate_lower", 0.0, "m/s", "contact force law: rate of the lower approach")
        self.output("y", "m", "vertical displacement")
        self.output("y_dot", "m/s", "vertical velocity")
        self.output("y_ddot", "m/s2", "vertical acceleration", depends=("F_contact", "F_ext"))
        self.y, self.y_dot, self.time = 0.0, 0.0, 0.0

    @classmethod
    def continuous_model(cls, parameters):
        return carriage.from_parameters(**parameters)

    def setup_experiment(self, start_time, stop_time, tolerance):
        self.time = start_time

    def initialise(self):
        self.y, self.y_dot = self.model().initial_state(self.time, {})

    def advance(self, t, h):
        rows = OpposedRows(self.law_force_1um, self.law_exponent, self.law_sine,
                           self.law_approach_upper, self.law_approach_lower, self.law_rate_upper,
                           self.law_rate_lower) if self.law_force_1um > 0.0 else None
        self.y, self.y_dot, _ = self.model().step(self.y, self.y_dot, t, h, self.F_ext,
                                                  self.F_contact, self.K_contact, self.C_contact,
                                                  rows)
        self.time = t + h

    def evaluate(self):
        return self.model().outputs(self.time, (self.y, self.y_dot), self.model_inputs())
