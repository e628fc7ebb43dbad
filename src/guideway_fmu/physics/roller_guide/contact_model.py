"""The four-row roller contact as a continuous-time model (Soleimanian et al. 2020, eqs. 1b-5).

Inputs y [m], y_dot [m/s] (the carriage) and u [m/s] (the feed). States: the films h_upper,
h_lower [m] of the ``extrapolated`` film model, which obey the published squeeze relation solved
for dh/dt (:func:`four_rows.film_rates`); the dry contact and the quasi-static Pan-Hamrock film
have none. :data:`OUTPUTS` is the contact FMUs' output contract, computed in one place
(:meth:`RollerContact.outputs`) for the FMUs and the reference alike: net force (plus an optional
damping), row loads, films, the tangent stiffness and damping, and the frozen-film force law with
the films' rates (:class:`~.roller_law.OpposedRows`) that the stabilised coupling hands to the
carriage. K_contact is the stiffness with the films held (they cannot change instantly), or the
quasi-static stiffness including the film for ``pan_hamrock``, whose force is no frozen-film law
(law_force_1um 0).

The film integrator (:meth:`RollerContact.advance`) takes Heun steps with u held, on substeps of
at most FILM_SUBSTEP h / |u| (about 1/30 of the film's relaxation time 99 h_s / |u|), while y
follows a path over the step (:func:`linear_path`, :func:`hermite_path`).
"""
from __future__ import annotations

from ..dynamics import ContinuousModel, substeps
from .. import checks
from .film import LineContact
from .four_rows import Guideway, RowKernel, net_force, quasi_static_state, quasi_static_stiffness
from .roller_law import EXPONENT, MICRON

OUTPUTS = ("F_contact", "F_upper", "F_lower", "h_upper", "h_lower", "K_contact", "C_contact",
           "law_force_1um", "law_exponent", "law_sine", "law_approach_upper",
           "law_approach_lower", "law_rate_upper", "law_rate_lower")
FILM_SUBSTEP = 13.2  # largest Heun substep of the film integration, in units of h / |u|
FILM_FLOOR = 1e-9  # m, films below this size the substeps as if they were this thick
#: Heun substeps of a step in which a roller lifts off or lands: its film rate has a cusp there
#: (h / h_s = h F^m / C(u), m = 0.045, rises from 0 with infinite slope: physics/roller_guide/film.py)
TOUCHDOWN_SUBSTEPS = 16


def linear_path(y: float, y_dot: float):
    """y [m] at tau [s] into a step, extrapolated from its start (FMI's held inputs)."""
    return lambda tau: y + y_dot * tau


def hermite_path(y0: float, v0: float, y1: float, v1: float, h: float):
    """y [m] at tau [s] into a step of h [s]: the cubic Hermite curve from (y0, v0) at its start
    to (y1, v1) at its end."""
    dy, slope0, slope1 = y1 - y0, h * v0, h * v1
    # y0 + x (slope0 + x (a + x b)), x = tau / h, matching y and h y' at both ends
    a, b = 3.0 * dy - 2.0 * slope0 - slope1, slope0 + slope1 - 2.0 * dy
    return lambda tau: y0 + (tau / h) * (slope0 + (tau / h) * (a + (tau / h) * b))


class RollerContact(ContinuousModel):
    """The contact of a :class:`~.four_rows.Guideway` (module doc); ``lubricated`` False is the
    dry contact (no film), ``damping`` [N s/m] a viscous term added to the net force."""

    inputs = ("y", "y_dot", "u")

    def __init__(self, guideway: Guideway, damping: float = 0.0, lubricated: bool = True):
        self.guideway, self.kernel, self.damping = guideway, RowKernel(guideway), damping
        self.film_model = guideway.contact.model if lubricated else "dry"
        self.states = ("h_upper", "h_lower") if self.film_model == "extrapolated" else ()
        # the film rate rises from a landing roller's zero load as F^0.045 (physics/roller_guide/film.py):
        # LSODA stalls on it where rollers lift off, an explicit method steps across
        self.smooth = not self.states

    def state_scales(self):
        return (self.guideway.delta0,) * len(self.states)

    def initial_state(self, t, inputs):
        if not self.states:
            return ()
        _, _, h_u, h_l = quasi_static_state(self.guideway, inputs["y"], inputs["u"])
        return float(h_u), float(h_l)

    def derivatives(self, t, state, inputs):
        return self.kernel.film_rates(inputs["y"], state[0], state[1], inputs["u"])

    def evaluate(self, t, state, inputs):
        outputs = self.outputs(t, state, inputs)
        return (outputs["law_rate_upper"], outputs["law_rate_lower"]), outputs

    def outputs(self, t, state, inputs, wanted=None):
        y, u = inputs["y"], inputs["u"]
        kernel, is_law = self.kernel, True
        if self.film_model == "pan_hamrock":
            f_u, f_l, h_u, h_l = (float(v) for v in quasi_static_state(self.guideway, y, u))
            force = float(net_force(self.guideway, f_u, f_l))
            k = float(quasi_static_stiffness(self.guideway, y, u, state=(f_u, f_l, h_u, h_l)))
            rates, is_law = (0.0, 0.0), False
        else:
            h_u, h_l = state if self.states else (0.0, 0.0)
            force, k, f_u, f_l = kernel.contact(y, h_u, h_l)
            rates = kernel.film_rates(y, h_u, h_l, u) if self.states else (0.0, 0.0)
        return {"F_contact": force + self.damping * inputs["y_dot"], "F_upper": f_u,
                "F_lower": f_l, "h_upper": h_u, "h_lower": h_l, "K_contact": k,
                "C_contact": self.damping, "law_force_1um": kernel.force_1um if is_law else 0.0,
                "law_exponent": EXPONENT, "law_sine": kernel.sin,
                "law_approach_upper": kernel.delta0 + h_u, "law_approach_lower": kernel.delta0 + h_l,
                "law_rate_upper": rates[0], "law_rate_lower": rates[1]}

    def advance(self, films, path, u: float, h: float) -> tuple[float, float]:
        """The films [m] after a step of h [s] from ``films``, y following ``path`` (a function
        of the time into the step) at the feed velocity u [m/s]. Raises RuntimeError when a
        film turns negative."""
        rates = self.kernel.film_rates
        hu, hl = films
        n = substeps(h * abs(u) / (FILM_SUBSTEP * max(min(hu, hl), FILM_FLOOR)),
                     "the film (FILM_SUBSTEP h / |u|)")
        loads = self.kernel.loads
        (su, sl), (eu, el) = loads(path(0.0), hu, hl), loads(path(h), hu, hl)
        if (su > 0.0) != (eu > 0.0) or (sl > 0.0) != (el > 0.0):
            n = max(n, TOUCHDOWN_SUBSTEPS)  # a roller lifts off or lands: the rate's cusp
        dt = h / n
        for i in range(n):
            ru, rl = rates(path(i * dt), hu, hl, u)
            pu, pl = rates(path((i + 1) * dt), hu + dt * ru, hl + dt * rl, u)
            hu, hl = hu + 0.5 * dt * (ru + pu), hl + 0.5 * dt * (rl + pl)
        if not (hu >= 0.0 and hl >= 0.0):
            raise RuntimeError(f"film integration lost the film (h_upper {hu}, h_lower {hl} m)")
        return hu, hl


def from_parameters(rollers_per_groove, contact_angle, preload, roller_radius, roller_length,
                    roller_load_1um, damping, e_reduced=LineContact.e_reduced,
                    viscosity=LineContact.viscosity,
                    pressure_viscosity=LineContact.pressure_viscosity,
                    film_model=LineContact.model, lubricated: bool = True) -> RollerContact:
    """The validated model of the contact FMUs' parameters (fmus/README.md).

    roller_load_1um [N] is k (1e-6 m)^(10/9), 0 for Palmgren's k. The dry contact
    (``lubricated`` False) has no lubricant parameters (e_reduced [Pa], viscosity [Pa s],
    pressure_viscosity [1/Pa], film_model): their defaults. Raises ValueError naming the
    parameter that is wrong.
    """
    checks.non_negative("roller_load_1um", roller_load_1um)
    checks.non_negative("damping", damping)
    g = Guideway(rollers_per_groove=rollers_per_groove, contact_angle=contact_angle,
                 preload=preload, stiffness=roller_load_1um / MICRON ** EXPONENT,
                 contact=LineContact(radius=roller_radius, length=roller_length,
                                     e_reduced=e_reduced, viscosity=viscosity,
                                     pressure_viscosity=pressure_viscosity, model=film_model))
    g.validate()
    return RollerContact(g, damping, lubricated)
