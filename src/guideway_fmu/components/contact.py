"""Contact FMUs of the four-row roller guideway: ContactDryHertz and ContactEHL (paper 000)."""
from __future__ import annotations

import math

from ..physics import film, guideway
from .base import GuidewaySlave

_FEEDTHROUGH = ("y", "y_dot", "u")
FILM_SUBSTEP = 13.2  # largest Heun substep of the film integration, in units of h / |u|
FILM_FLOOR = 1e-9  # m, films below this size the substeps as if they were this thick


class _RollerContact(GuidewaySlave):
    """Shared interface: inputs y, y_dot, u; loads, films, net force and its tangents as outputs."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        g = guideway.Guideway()
        self.parameter("rollers_per_groove", g.rollers_per_groove, None, "rollers N in each of the 4 grooves")
        self.parameter("contact_angle", g.contact_angle, "rad", "contact angle from the horizontal")
        self.parameter("preload", g.preload, "N", "preload force F0, shared by all 4N rollers")
        self.parameter("roller_radius", g.contact.radius, "m", "roller radius R")
        self.parameter("roller_length", g.contact.length, "m", "roller length l")
        self.parameter("roller_load_1um", 0.0, "N",
                       "roller load at 1 um approach, k (1e-6 m)^(10/9); 0 selects Palmgren's formula")
        self.parameter("damping", 0.0, "N.s/m", "optional viscous damping of the net force (paper: none)")
        self.input("y", 0.0, "m", "vertical displacement of the moving body, positive along the load")
        self.input("y_dot", 0.0, "m/s", "vertical velocity of the moving body")
        self.input("u", 0.0, "m/s", "feed velocity of the moving body")
        self.output("F_contact", "N", "net contact force on the moving body, 2N sin(theta)(F_U - F_L) "
                    "+ damping y_dot, opposing positive y", _FEEDTHROUGH)
        self.output("F_upper", "N", "load of one roller in an upper groove", _FEEDTHROUGH)
        self.output("F_lower", "N", "load of one roller in a lower groove", _FEEDTHROUGH)
        self.output("h_upper", "m", "film thickness of an upper roller contact", _FEEDTHROUGH)
        self.output("h_lower", "m", "film thickness of a lower roller contact", _FEEDTHROUGH)
        self.output("K_contact", "N/m", "tangent stiffness dF_contact/dy", _FEEDTHROUGH)
        self.output("C_contact", "N.s/m", "tangent damping dF_contact/dy_dot", _FEEDTHROUGH)
        # the net force as a law over the next step (roller_contact.OpposedRows), for the body
        self.output("law_force_1um", "N", "force law: net force of the rows at 1 um approach "
                    "(0: the force is no such law, use K_contact and C_contact)")
        self.output("law_exponent", "1", "force law: exponent n of the row approaches")
        self.output("law_sine", "1", "force law: row approach per unit y, sin(theta)")
        self.output("law_approach_upper", "m", "force law: upper row approach at y = 0, delta0 + h_U")
        self.output("law_approach_lower", "m", "force law: lower row approach at y = 0, delta0 + h_L")
        self.output("law_rate_upper", "m/s", "force law: growth rate of the upper approach, dh_U/dt",
                    ("y", "u"))
        self.output("law_rate_lower", "m/s", "force law: growth rate of the lower approach, dh_L/dt",
                    ("y", "u"))

    #: parameters that shape the FMU's step only, not the physics (the monolithic reference
    #: leaves them out too)
    step_settings: tuple[str, ...] = ()

    def build_model(self):
        return guideway.from_parameters(**{k: v for k, v in self.parameter_values().items()
                                           if k not in self.step_settings})

    def _pack(self, force, f_u, f_l, h_u, h_l, stiffness, rates=(0.0, 0.0), is_law=True):
        """Outputs; ``is_law`` False: the force is not the frozen-film law (law_force_1um 0)."""
        law = self.model()[1].rows(h_u, h_l, *rates)
        return {"F_contact": float(force + self.damping * self.y_dot),
                "F_upper": float(f_u), "F_lower": float(f_l),
                "h_upper": float(h_u), "h_lower": float(h_l),
                "K_contact": float(stiffness), "C_contact": float(self.damping),
                "law_force_1um": law.force_1um if is_law else 0.0, "law_exponent": law.exponent,
                "law_sine": law.sine, "law_approach_upper": float(law.approach_upper),
                "law_approach_lower": float(law.approach_lower),
                "law_rate_upper": float(rates[0]), "law_rate_lower": float(rates[1])}


class ContactDryHertz(_RollerContact):
    """Dry roller contacts F = k delta^(10/9) with preload; no film. Algebraic, no state."""

    description = __doc__.splitlines()[0]

    def evaluate(self):
        force, k, f_u, f_l = self.model()[1].contact(self.y, 0.0, 0.0)
        return self._pack(force, f_u, f_l, 0.0, 0.0, k)


class ContactEHL(_RollerContact):
    """Lubricated roller contacts: the EHL film adds to each roller's approach (eqs. 3-5).

    film_model "extrapolated": the films are states obeying the published squeeze relation,
    integrated with Heun's method over each step, u held, on substeps of at most
    FILM_SUBSTEP h / |u| (about 1/30 of the film's relaxation time 99 h_s / |u|); they start from
    the steady film. Along the step y follows the inputs: extrapolated linearly from y, y_dot
    (FMI semantics: inputs hold at the start of the step), or, with interpolate_inputs, the cubic
    Hermite curve from the previous step's y, y_dot to the present ones, which then hold at the
    END of the step: what the stabilised coupling gives (the body steps first; its tangent
    settings switch this on). K_contact is the stiffness with the films held (they cannot change
    instantly); the law_* outputs hand the frozen-film force law and the film rates to the body.
    film_model "pan_hamrock": the steady Pan-Hamrock film, solved with the load at every
    evaluation (no state); K_contact is the quasi-static stiffness including the film.
    """

    description = __doc__.splitlines()[0]
    internal_state = ("films", "previous_inputs")
    step_settings = ("interpolate_inputs",)

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("interpolate_inputs", False, None,
                       "true: y, y_dot given before a step hold at its end (Gauss-Seidel after the "
                       "body) and the films follow the Hermite curve from the previous ones; "
                       "false: they hold at its start and are extrapolated")
        c = film.LineContact()
        self.parameter("e_reduced", c.e_reduced, "Pa", "reduced modulus E'")
        self.parameter("viscosity", c.viscosity, "Pa.s", "lubricant viscosity at ambient pressure mu0")
        self.parameter("pressure_viscosity", c.pressure_viscosity, "1/Pa", "pressure-viscosity coefficient alpha")
        self.parameter("film_model", c.model, None, f"film law, one of {film.FILM_MODELS}")
        self.films = [0.0, 0.0]
        self.previous_inputs = [0.0, 0.0]  # y [m], y_dot [m/s] given before the last step

    def _extrapolated(self):
        return self.model()[0].contact.model == "extrapolated"

    def initialise(self):
        _, _, h_u, h_l = guideway.quasi_static_state(self.model()[0], self.y, self.u)
        self.films = [float(h_u), float(h_l)]
        self.previous_inputs = [self.y, self.y_dot]

    def _path(self, h):
        """y [m] at time tau [s] into the step, from the inputs (class doc)."""
        y1, v1 = self.y, self.y_dot
        if not self.interpolate_inputs:
            return lambda tau: y1 + v1 * tau
        y0, v0 = self.previous_inputs
        dy, slope0, slope1 = y1 - y0, h * v0, h * v1
        # cubic Hermite y0 + x (slope0 + x (a + x b)), x = tau / h, matching y and h y' at both ends
        a, b = 3.0 * dy - 2.0 * slope0 - slope1, slope0 + slope1 - 2.0 * dy
        return lambda tau: y0 + (tau / h) * (slope0 + (tau / h) * (a + (tau / h) * b))

    def advance(self, t, h):
        if not self._extrapolated():
            return
        rates = self.model()[1].film_rates
        path, u = self._path(h), self.u
        hu, hl = self.films
        n = max(1, math.ceil(h * abs(u) / (FILM_SUBSTEP * max(min(hu, hl), FILM_FLOOR))))
        dt = h / n
        for i in range(n):
            ru, rl = rates(path(i * dt), hu, hl, u)
            pu, pl = rates(path((i + 1) * dt), hu + dt * ru, hl + dt * rl, u)
            hu, hl = hu + 0.5 * dt * (ru + pu), hl + 0.5 * dt * (rl + pl)
        if not (hu >= 0.0 and hl >= 0.0):
            raise RuntimeError(f"film integration lost the film (h_upper {hu}, h_lower {hl} m)")
        self.films = [hu, hl]
        self.previous_inputs = [self.y, self.y_dot]

    def evaluate(self):
        g, kernel = self.model()
        if self._extrapolated():
            h_u, h_l = self.films
            force, k, f_u, f_l = kernel.contact(self.y, h_u, h_l)
            rates = kernel.film_rates(self.y, h_u, h_l, self.u)
            return self._pack(force, f_u, f_l, h_u, h_l, k, rates)
        state = guideway.quasi_static_state(g, self.y, self.u)
        f_u, f_l, h_u, h_l = state
        k = guideway.quasi_static_stiffness(g, self.y, self.u, state=state)
        return self._pack(guideway.net_force(g, f_u, f_l), f_u, f_l, h_u, h_l, k, is_law=False)
