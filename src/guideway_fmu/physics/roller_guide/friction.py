"""Friction force of a roller guideway on its moving part (the rail), SI units.

Geometry (Soleimanian et al. 2020, Table 2): 4 grooves, 2 upper and 2 lower, each with N rollers; every
roller has one contact with the moving part, loaded by F_upper or F_lower [N] with film
thickness h_upper or h_lower [m]. The force on the moving part sums 2N upper and 2N lower
contacts. Forces are returned with the sign of the force ON the moving part (opposing u).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .. import checks
from ..papers import soleimanian2020 as paper
from ..dynamics import Algebraic, regularised_sign
from . import greenwood_tripp as gt, hertz_line


@dataclass(frozen=True)
class MixedFrictionParams:
    """Mixed-EHL friction model; defaults from Soleimanian et al. (2020) Tables 2 and 3.

    Call :meth:`validate` once at set-up: the friction functions do not re-check it per call.
    """

    surface: gt.Surface = field(default_factory=gt.Surface)
    roller_radius: float = paper.ROLLER_RADIUS  # R [m]
    roller_length: float = paper.ROLLER_LENGTH  # l [m]
    rollers_per_groove: int = paper.ROLLERS_PER_GROOVE  # N [-]
    viscosity: float = paper.VISCOSITY  # mu_0 [Pa s]
    limiting_shear_stress: float = paper.LIMITING_SHEAR_STRESS  # tau_l0 [Pa]
    limiting_shear_slope: float = paper.LIMITING_SHEAR_SLOPE  # beta_m [-]
    velocity_tolerance: float = 1e-4  # of regularised_sign [m/s]

    def validate(self) -> None:
        """Raise ValueError naming the first invalid field (including those of ``surface``)."""
        self.surface.validate()
        checks.check_fields(
            self,
            {
                "roller_radius": checks.positive,
                "roller_length": checks.positive,
                "rollers_per_groove": checks.positive_integer,
                "viscosity": checks.positive,
                "limiting_shear_stress": checks.positive,
                "limiting_shear_slope": checks.non_negative,
                "velocity_tolerance": checks.non_negative,
            },
        )


def _contact(load, h, u, p: MixedFrictionParams):
    """(boundary, viscous) friction magnitudes [N] of one contact; arguments already checked."""
    area = hertz_line.contact_area(load, p.roller_length, p.roller_radius, p.surface.e_reduced)
    asperity_load = np.minimum(gt.asperity_load(h, area, p.surface), load)
    asperity_area = gt.asperity_area(h, area, p.surface)
    # Eqs. 27-28, F_b = (tau_l0 + beta_m W_a / A_a) A_a, written without the 0/0 at A_a = 0.
    boundary = p.limiting_shear_stress * asperity_area + p.limiting_shear_slope * asperity_load

    p_mean = np.divide(load, area, out=np.zeros_like(area), where=area > 0.0)
    tau_limit = p.limiting_shear_stress + p.limiting_shear_slope * p_mean
    with np.errstate(divide="ignore", invalid="ignore"):
        couette = np.where(h > 0.0, p.viscosity * np.abs(u) / h, np.inf)
    # A - A_a >= 0 already holds while pi^2 (n beta sigma)^2 / 2 < 1 (0.0066 with Table 3 values).
    viscous = np.minimum(couette, tau_limit) * np.maximum(area - asperity_area, 0.0)
    return boundary, viscous


def mixed_from_parameters(rollers_per_groove, velocity_tolerance, asperity_density,
                          asperity_radius, roughness, e_reduced, roller_radius, roller_length,
                          viscosity, limiting_shear_stress, limiting_shear_slope):
    """The validated model of the FrictionMixedEHL FMU's parameters (fmus/README.md): inputs
    F_upper, F_lower [N], h_upper, h_lower [m], u [m/s]; outputs F_friction, F_boundary,
    F_viscous [N] (:func:`mixed_ehl_friction`)."""
    params = MixedFrictionParams(
        surface=gt.Surface(asperity_density=asperity_density, asperity_radius=asperity_radius,
                           roughness=roughness, e_reduced=e_reduced),
        roller_radius=roller_radius, roller_length=roller_length,
        rollers_per_groove=rollers_per_groove, viscosity=viscosity,
        limiting_shear_stress=limiting_shear_stress, limiting_shear_slope=limiting_shear_slope,
        velocity_tolerance=velocity_tolerance)
    params.validate()

    def outputs(F_upper, F_lower, h_upper, h_lower, u):
        parts = mixed_ehl_friction(F_upper, F_lower, h_upper, h_lower, u, params)
        return dict(zip(("F_friction", "F_boundary", "F_viscous"), parts))

    return Algebraic(("F_upper", "F_lower", "h_upper", "h_lower", "u"), outputs)


def contact_friction(load, h, u, params: MixedFrictionParams):
    """Boundary and viscous friction magnitudes (F_b, F_v) >= 0 [N] of one roller contact.

    load [N] >= 0, film thickness h [m] (h <= 0: no film), sliding velocity u [m/s];
    vectorised with numpy broadcasting. The apparent area is the Hertz area A = 2 b l.

    Boundary (eqs. 24-25, 27-28): F_b = tau_l0 A_a + beta_m W_a, i.e. tau_l A_a with
    tau_l = tau_l0 + beta_m W_a / A_a. W_a is capped at the contact load, because the
    Greenwood-Tripp law knows only the film and not the total load it must not exceed.

    Viscous (eqs. 29-30, lumped over the contact for an analytical film):
    F_v = tau_v (A - A_a) with the Couette stress tau_v = mu_0 |u| / h, bounded by the
    lubricant's limiting shear stress tau_L = tau_l0 + beta_m load / A; at h <= 0,
    tau_v = tau_L, so F_v stays finite as h -> 0. The Poiseuille term (+-h/2 dp/dx) needs the
    pressure distribution of a numerical EHL solution and is omitted.

    Zero load gives zero friction (A = 0).
    """
    load = checks.non_negative("load", load)
    return _contact(load, checks.finite("h", h), checks.finite("u", u), params)


def mixed_ehl_friction(F_upper, F_lower, h_upper, h_lower, u, params: MixedFrictionParams):
    """Mixed-EHL friction force on the moving part, (total, boundary, viscous) [N] (eq. 31).

    Per-roller loads F_upper, F_lower [N] >= 0, films h_upper, h_lower [m], sliding velocity
    u [m/s] of the moving part; arrays of equal shape (or broadcastable). The magnitudes of
    :func:`contact_friction`, summed over 2N upper and 2N lower contacts, are multiplied by
    -regularised_sign(u): each force opposes u. total = boundary + viscous.
    """
    f_upper, f_lower, h_upper, h_lower, u = np.broadcast_arrays(
        checks.non_negative("F_upper", F_upper), checks.non_negative("F_lower", F_lower),
        checks.finite("h_upper", h_upper), checks.finite("h_lower", h_lower), checks.finite("u", u))
    # both rows in one evaluation, along a leading axis (the special functions cost per call)
    b, v = _contact(np.stack([f_upper, f_lower]), np.stack([h_upper, h_lower]), u, params)
    scale = -2.0 * params.rollers_per_groove * regularised_sign(u, params.velocity_tolerance)
    boundary = scale * (b[0] + b[1])
    viscous = scale * (v[0] + v[1])
    return boundary + viscous, boundary, viscous


@dataclass(frozen=True)
class CoulombParams:
    """Constant-coefficient friction; the default mu = 0.005 is an order of magnitude only (no
    source): take mu from the guideway's catalogue or fit it to a measurement.

    Call :meth:`validate` once at set-up: :func:`coulomb_friction` does not re-check it.
    """

    coefficient: float = 0.005  # mu [-]
    rollers_per_groove: int = paper.ROLLERS_PER_GROOVE  # N [-]
    velocity_tolerance: float = 1e-4  # of regularised_sign [m/s]

    def validate(self) -> None:
        """Raise ValueError naming the first invalid field."""
        checks.check_fields(
            self,
            {
                "coefficient": checks.non_negative,
                "rollers_per_groove": checks.positive_integer,
                "velocity_tolerance": checks.non_negative,
            },
        )


def coulomb_from_parameters(rollers_per_groove, velocity_tolerance, coefficient):
    """The validated model of the FrictionCoulomb FMU's parameters (fmus/README.md): inputs
    F_upper, F_lower [N], u [m/s]; output F_friction [N] (:func:`coulomb_friction`)."""
    params = CoulombParams(coefficient=coefficient, rollers_per_groove=rollers_per_groove,
                           velocity_tolerance=velocity_tolerance)
    params.validate()
    return Algebraic(("F_upper", "F_lower", "u"), lambda F_upper, F_lower, u: {
        "F_friction": coulomb_friction(F_upper, F_lower, u, params)})


def coulomb_friction(F_upper, F_lower, u, params: CoulombParams):
    """Coulomb friction on the moving part, -mu 2N (F_upper + F_lower) s(u) [N].

    Per-roller loads F_upper, F_lower [N] must be >= 0 (ValueError naming the argument
    otherwise); u [m/s] is the sliding velocity, s = :func:`regularised_sign`.
    """
    f_upper = checks.non_negative("F_upper", F_upper)
    f_lower = checks.non_negative("F_lower", F_lower)
    s = regularised_sign(checks.finite("u", u), params.velocity_tolerance)
    return -params.coefficient * 2.0 * params.rollers_per_groove * (f_upper + f_lower) * s
