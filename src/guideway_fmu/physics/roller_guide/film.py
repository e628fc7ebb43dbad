"""Lubricant film thickness of a roller-raceway line contact, SI units.

Two film laws, both power laws in the roller load F, h = C(u) * F^(-m):

* ``extrapolated`` (Soleimanian et al. 2020, eqs. 4-5, after Mohammadpour et al.):
  h = R * 13.924 Fbar^-0.045 U^0.647 G^0.46 * (1 - 0.75 exp(132 h_dot / u)),
  Fbar = F / (E' R l), U = mu0 |u| / (E' R) with u the feed velocity as published, G = alpha E'.
  With no squeeze (h_dot = 0) the bracket is 0.25: the paper's eq. 11 carries that 0.25.
* ``pan_hamrock``: Pan & Hamrock's minimum film of a smooth line contact,
  H_min = 1.714 W^-0.128 U^0.694 G^0.568 (Hamrock's convention: W = F / (l E' R),
  U = mu0 u_m / (E' R), G = alpha E'), with u_m = |u| / 2 the mean entrainment velocity of a roller
  rolling between a raceway moving at u and one at rest. It has no squeeze term.

The published squeeze factor divides by the feed velocity u, which passes through zero twice a
cycle: for a growing film (h_dot > 0) the exponential then explodes and the film turns negative.
This module regularises it in two documented ways:

1. the direction of entrainment does not matter, so |u| is used;
2. the exponent s = 132 h_dot / |u| is clipped to [S_MIN, S_MAX], which bounds the factor to
   [FACTOR_MIN, 1 - 0.75 FACTOR_MIN]: the film never falls below 1 % of the unsqueezed value and
   never turns negative, and it thins at most at |u| ln(1/FACTOR_MIN) / 132. (A clip far below,
   such as s = -30, changes the factor by less than 1 % but makes the film relation as stiff as
   e^30 |u| / h_s just below h = h_s: an implicit integrator then crawls at each feed reversal.)

:func:`film_rate` solves the same relation for h_dot, h_dot = |u| s / 132 with
s = ln((1 - h / h_s) / 0.75), which is how the contact FMU integrates the film as a state: it is
regular at u = 0 (the film is then frozen: nothing is entrained or squeezed out by rolling) and
relaxes to the steady film h_s / 4 with the time constant 99 h_s / |u|.

The film of an unloaded roller. Both laws diverge as F -> 0 (h_s ~ F^-0.045), far outside the
loads they were fitted to (Fbar of about 1e-6 to 1e-3): the steady film of a roller that lifts
off is infinite. The film as a state is not: as h / h_s -> 0 the squeeze relation gives
h_dot -> |u| ln(4/3) / 132 (|u| S_MAX / 132 with the clip above), the rate at which rolling
draws lubricant into the widening gap. A roller that unloads therefore keeps the film it had,
which grows at that bounded rate (about 0.4 mm/s at 0.2 m/s, a few nanometres over a period of
the load at kHz) until the gap closes and the roller carries load again; in the paper's eq. 3
the film adds to the approach, so the growth itself closes the gap. No threshold enters:
h / h_s = h F^m / C(u) is continuous at F = 0. (An earlier floor held h_s at its value for
Fbar = 1e-7, 0.4 N for the paper's roller; results moved by 3-26 % RMS between floors of 4 N
and 1e-9 N, converging only as floor^0.045: docs/physics.md.) In the steady state
(four_rows.quasi_static_state) a row whose geometry has parted keeps the vanishing load whose
steady film closes its gap.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import checks
from ..papers import soleimanian2020 as paper

FILM_MODELS = ("extrapolated", "pan_hamrock")

SQUEEZE_GAIN = 132.0
SQUEEZE_WEIGHT = 0.75
FACTOR_MIN = 0.01
S_MAX = float(np.log((1.0 - FACTOR_MIN) / SQUEEZE_WEIGHT))
S_MIN = float(np.log(FACTOR_MIN))

_LAWS = {  # coefficient, exponents of (Fbar, U, G), velocity used in U as a fraction of |u|
    "extrapolated": (13.924, 0.045, 0.647, 0.46, 1.0),
    "pan_hamrock": (1.714, 0.128, 0.694, 0.568, 0.5),
}


@dataclass(frozen=True)
class LineContact:
    """What the film law needs of one roller-raceway contact (Soleimanian et al. 2020, Tables 2 and 3)."""

    radius: float = paper.ROLLER_RADIUS  # m, roller radius
    length: float = paper.ROLLER_LENGTH  # m, roller length
    e_reduced: float = paper.E_REDUCED  # Pa, E'
    viscosity: float = paper.VISCOSITY  # Pa s, mu0 at ambient pressure
    pressure_viscosity: float = paper.PRESSURE_VISCOSITY  # 1/Pa, alpha
    model: str = "extrapolated"

    def validate(self) -> None:
        checks.check_fields(self, {
            "radius": checks.positive, "length": checks.positive, "e_reduced": checks.positive,
            "viscosity": checks.positive, "pressure_viscosity": checks.non_negative})
        if self.model not in FILM_MODELS:
            raise ValueError(f"LineContact.model must be one of {FILM_MODELS}, got {self.model!r}")


def film_law(contact: LineContact, u):
    """Coefficient C [m N^m] and exponent m of the steady film h = C * F^-m at feed velocity u [m/s].

    For ``extrapolated`` the steady film includes the squeeze bracket at h_dot = 0 (0.25).
    """
    coeff, m_load, m_speed, m_g, speed_fraction = _LAWS[contact.model]
    er = contact.e_reduced * contact.radius
    speed = speed_fraction * np.abs(np.asarray(u, dtype=float))
    c = (contact.radius * coeff * (contact.length * er) ** m_load
         * (contact.viscosity * speed / er) ** m_speed
         * (contact.pressure_viscosity * contact.e_reduced) ** m_g)
    if contact.model == "extrapolated":
        c = c * squeeze_factor(0.0, 1.0)
    return c, m_load


def speed_exponent(contact: LineContact) -> float:
    """Exponent p of the feed speed in the film law, C(u) = C(1 m/s) |u|^p."""
    return _LAWS[contact.model][2]


def steady_film(contact: LineContact, load, u):
    """Steady (no squeeze) film thickness [m] under the roller load [N] at feed velocity u [m/s]:
    infinite for an unloaded roller while anything is entrained (module doc: the film of an
    unloaded roller), 0 at u = 0."""
    c, m = film_law(contact, u)
    load = np.asarray(load, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):  # 0 x inf where nothing is entrained
        power = np.where(load > 0.0, load, 0.0) ** (-m)
        return np.where(c > 0.0, c * power, 0.0)


def unsqueezed_film(contact: LineContact, load, u):
    """The extrapolated film without its squeeze bracket, h_s [m] (= 4 x the steady film)."""
    if contact.model != "extrapolated":
        raise ValueError("unsqueezed_film applies to the 'extrapolated' film model only")
    return steady_film(contact, load, u) / squeeze_factor(0.0, 1.0)


def squeeze_factor(h_dot, u, regularised: bool = True):
    """The bracket 1 - 0.75 exp(132 h_dot / u) of Soleimanian et al. (2020) eq. 4.

    ``regularised=False`` evaluates the published expression literally (singular at u = 0,
    negative for fast film growth); the default uses |u| and clips the exponent (module doc).
    """
    h_dot = np.asarray(h_dot, dtype=float)
    u = np.asarray(u, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if not regularised:
            return 1.0 - SQUEEZE_WEIGHT * np.exp(SQUEEZE_GAIN * h_dot / u)
        s = np.where(np.abs(u) > 0.0, SQUEEZE_GAIN * h_dot / np.abs(u),
                     np.where(h_dot > 0.0, S_MAX, np.where(h_dot < 0.0, S_MIN, 0.0)))
    return 1.0 - SQUEEZE_WEIGHT * np.exp(np.clip(s, S_MIN, S_MAX))


def film_rate(h, h_unsqueezed, u):
    """Film growth rate h_dot [m/s] that makes h = h_s * squeeze_factor(h_dot, u) hold.

    The inverse of :func:`squeeze_factor` (regularised) for the film h [m] and the unsqueezed
    film h_s [m]; zero at u = 0.
    """
    h = np.asarray(h, dtype=float)
    hs = np.asarray(h_unsqueezed, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(hs > 0.0, h / hs, np.inf)
        arg = (1.0 - ratio) / SQUEEZE_WEIGHT
        s = np.where(arg > 0.0, np.log(np.where(arg > 0.0, arg, 1.0)), S_MIN)
    return np.abs(np.asarray(u, dtype=float)) * np.clip(s, S_MIN, S_MAX) / SQUEEZE_GAIN
