"""VerticalDynamics FMU: the moving body's vertical degree of freedom (paper 000, eq. 1b)."""
from __future__ import annotations

from ..physics import carriage
from .base import GuidewaySlave


class VerticalDynamics(GuidewaySlave):
    """M y'' = M g + F_e(t) + F_ext - F_contact, y positive along gravity and the external load.

    F_e(t) = load_static + load_amplitude sin(2 pi load_frequency t + load_phase) is the external
    load of paper 000 eq. 1b, evaluated at every instant; the F_ext input is held over a step.
    Over each communication step the contact force is extrapolated with the K_contact and
    C_contact inputs (leave them unconnected, 0, to hold F_contact constant) and the linear ODE is
    integrated with RK4 substeps (physics/carriage.py): stable for K, C >= 0 at any step.
    """

    description = __doc__.splitlines()[0]
    internal_state = ("y", "y_dot", "time")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("mass", carriage.Body.mass, "kg", "mass M of the moving body (rail)")
        self.parameter("gravity", carriage.Body.gravity, "m/s2", "gravitational acceleration along +y")
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
        self.output("y", "m", "vertical displacement")
        self.output("y_dot", "m/s", "vertical velocity")
        self.output("y_ddot", "m/s2", "vertical acceleration", depends=("F_contact", "F_ext"))
        self.y, self.y_dot, self.time = 0.0, 0.0, 0.0

    def build_model(self):
        return carriage.from_parameters(**self.parameter_values())

    def setup_experiment(self, start_time, stop_time, tolerance):
        self.time = start_time

    def initialise(self):
        self.y, self.y_dot = float(self.y_start), float(self.y_dot_start)

    def advance(self, t, h):
        body, load = self.model()
        self.y, self.y_dot, _ = carriage.step(body, self.y, self.y_dot, h, self.F_ext, self.F_contact,
                                              self.K_contact, self.C_contact, t=t, load=load)
        self.time = t + h

    def evaluate(self):
        body, load = self.model()
        return {"y": self.y, "y_dot": self.y_dot,
                "y_ddot": body.gravity + (load(self.time) + self.F_ext - self.F_contact) / body.mass}
