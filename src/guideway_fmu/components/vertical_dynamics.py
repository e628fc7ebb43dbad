"""VerticalDynamics FMU: the moving body's vertical degree of freedom (paper 000, eq. 1b)."""
from __future__ import annotations

from ..physics import carriage, checks
from .base import GuidewaySlave


class VerticalDynamics(GuidewaySlave):
    """M y'' = M g + F_ext - F_contact, y positive along gravity and the external load.

    Integration: over each communication step the contact force is extrapolated with the
    K_contact and C_contact inputs (leave them unconnected, 0, to hold F_contact constant) and
    the linear ODE is solved exactly (matrix exponential): exact for any step, stable for K, C >= 0.
    """

    description = __doc__.splitlines()[0]
    internal_state = ("y", "y_dot")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("mass", carriage.Body.mass, "kg", "mass M of the moving body (rail)")
        self.parameter("gravity", carriage.Body.gravity, "m/s2", "gravitational acceleration along +y")
        self.parameter("y_start", 0.0, "m", "displacement at the start time")
        self.parameter("y_dot_start", 0.0, "m/s", "velocity at the start time")
        self.input("F_contact", 0.0, "N", "net contact force on the body, opposing positive y")
        self.input("F_ext", 0.0, "N", "external vertical force, positive along +y")
        self.input("K_contact", 0.0, "N/m", "tangent stiffness dF_contact/dy (optional, >= 0)",
                   non_negative=True)
        self.input("C_contact", 0.0, "N.s/m", "tangent damping dF_contact/dy_dot (optional, >= 0)",
                   non_negative=True)
        self.output("y", "m", "vertical displacement")
        self.output("y_dot", "m/s", "vertical velocity")
        self.output("y_ddot", "m/s2", "vertical acceleration", depends=("F_contact", "F_ext"))
        self.y, self.y_dot = 0.0, 0.0

    def build_model(self):
        body = carriage.Body(mass=self.mass, gravity=self.gravity)
        body.validate()
        checks.finite("y_start", self.y_start)
        checks.finite("y_dot_start", self.y_dot_start)
        return body

    def initialise(self):
        self.y, self.y_dot = float(self.y_start), float(self.y_dot_start)

    def advance(self, t, h):
        self.y, self.y_dot, _ = carriage.step(self.model(), self.y, self.y_dot, h, self.F_ext,
                                              self.F_contact, self.K_contact, self.C_contact)

    def evaluate(self):
        body = self.model()
        return {"y": self.y, "y_dot": self.y_dot,
                "y_ddot": body.gravity + (self.F_ext - self.F_contact) / body.mass}
