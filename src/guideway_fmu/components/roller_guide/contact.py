"""Contact FMUs of the four-row roller guideway (Soleimanian et al. 2020): ContactDryHertz and
ContactEHL, declarations around physics/roller_guide/contact_model.RollerContact."""
from __future__ import annotations

from ...physics.roller_guide import film, four_rows, contact_model
from ..base import GuidewaySlave

_FEEDTHROUGH = ("y", "y_dot", "u")


class _RollerContact(GuidewaySlave):
    """Shared interface: inputs y, y_dot, u; loads, films, net force and its tangents as outputs."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        g = four_rows.Guideway()
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
        # the net force as a law over the next step (roller_law.OpposedRows), for the body
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

    #: parameters that shape the FMU's step only, not the physics
    step_settings: tuple[str, ...] = ()
    lubricated = True

    @classmethod
    def continuous_model(cls, parameters):
        return contact_model.from_parameters(
            **{k: v for k, v in parameters.items() if k not in cls.step_settings},
            lubricated=cls.lubricated)


class ContactDryHertz(_RollerContact):
    """Dry roller contacts F = k delta^(10/9) with preload; no film. Algebraic, no state."""

    description = __doc__.splitlines()[0]
    lubricated = False


class ContactEHL(_RollerContact):
    """Lubricated roller contacts: the EHL film adds to each roller's approach (eqs. 3-5).

    film_model "extrapolated": the films are states obeying the published squeeze relation,
    integrated over each step (physics/roller_guide/contact_model.py); they start from the steady film.
    Along the step y follows the inputs: extrapolated linearly from y, y_dot (FMI semantics:
    inputs hold at the start of the step), or, with interpolate_inputs, the cubic Hermite curve
    from the previous step's y, y_dot to the present ones, which then hold at the END of the
    step: what the stabilised coupling gives (the carriage steps first; its tangent settings
    switch this on). film_model "pan_hamrock": the steady Pan-Hamrock film, solved with the
    load at every evaluation (no state).
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
        self.parameter("film_model", c.model, None, f"film law, one of {film.FILM_MODELS}",
                       choices=film.FILM_MODELS)
        self.films = (0.0, 0.0)  # m, h_upper and h_lower of the extrapolated film
        self.previous_inputs = [0.0, 0.0]  # y [m], y_dot [m/s] given before the last step

    def initialise(self):
        if self.model().states:
            self.films = self.model().initial_state(0.0, self.model_inputs())
        self.previous_inputs = [self.y, self.y_dot]

    def _films(self):
        return self.films if self.model().states else ()

    def advance(self, t, h):
        if not self.model().states:
            return
        path = (contact_model.hermite_path(*self.previous_inputs, self.y, self.y_dot, h)
                if self.interpolate_inputs else contact_model.linear_path(self.y, self.y_dot))
        self.films = self.model().advance(self.films, path, self.u, h)
        self.previous_inputs = [self.y, self.y_dot]

    def evaluate(self):
        return self.model().outputs(0.0, self._films(), self.model_inputs())
