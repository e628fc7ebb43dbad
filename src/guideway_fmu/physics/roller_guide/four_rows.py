"""Vertical contact mechanics of a four-row roller guideway (Soleimanian et al. 2020, eqs. 1b, 2, 3, 6-14).

Geometry: two upper and two lower grooves of N rollers each, contact angle theta measured from
the horizontal (x) direction. y [m] is the vertical displacement of the moving body, positive in
the direction of gravity and of the external load; it compresses the upper rollers and relieves
the lower ones.

Kinematics. The normal approach of a roller caused by y is y sin(theta), which is what the net
force of eq. 1b, 2 N sin(theta) (F_U - F_L), requires by virtual work. The published eq. 3 writes
y / (2 sin(theta)); the two agree only at theta = 45 deg (the paper's guideway, INA RUE45-E), so
the paper's results are reproduced exactly there and the consistent form is used at other angles.
The film adds to the approach: delta_U = delta0 + y sin(theta) + h_U, delta_L = delta0 - y sin(theta) + h_L.

Preload. The preload force F0 is taken as shared equally by all 4 N rollers, Q0 = F0 / (4 N), so
delta0 is the approach at which one roller carries Q0. The paper's Table 2 gives 9200 N without
saying over what it is shared; the default F0 = 36800 N reads it per groove (Q0 = 460 N), the
reading that reproduces the most of the paper's stated results (analysis/soleimanian2020.py).

Quasi-static stiffness, derived here because the published eqs. 8, 10 and 12 print 10/(9k) where
(10/9) k belongs. With the steady film h(F) = C F^-m of :mod:`film`,
  dF_U/dy =  k' sin(theta) / (1 - k' dh/dF_U),   dF_L/dy = -k' sin(theta) / (1 - k' dh/dF_L),
  k' = (10/9) k delta^(1/9),  dh/dF = -m h / F,  K = 2 N sin(theta) (dF_U/dy - dF_L/dy).
Dry (h = 0), K = 2 N sin^2(theta) (k'_U + k'_L), which is eq. 14 at theta = 45 deg.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import math

import numpy as np

from .. import checks
from ..papers import soleimanian2020 as paper
from ..roots import bracketed_root
from .film import (S_MAX, S_MIN, SQUEEZE_GAIN, SQUEEZE_WEIGHT, LineContact, film_law, film_rate,
                   speed_exponent, squeeze_factor, steady_film, unsqueezed_film)
from .roller_law import (EXPONENT, MICRON, OpposedRows, approach_for_load, contact_force,
                         contact_stiffness, palmgren_stiffness)


@dataclass(frozen=True)
class Guideway:
    """A four-row roller guideway; defaults from Soleimanian et al. (2020) Table 2 and the INA RUE45-E."""

    rollers_per_groove: int = paper.ROLLERS_PER_GROOVE
    contact_angle: float = paper.CONTACT_ANGLE  # rad, from the horizontal
    preload: float = paper.GUIDEWAY_PRELOAD  # N, F0 over all 4 N rollers: 9200 N per groove
    contact: LineContact = field(default_factory=LineContact)  # roller and lubricant
    stiffness: float = 0.0  # N/m^(10/9), k per roller; 0 selects Palmgren's formula

    def validate(self) -> None:
        checks.check_fields(self, {
            "rollers_per_groove": checks.positive_integer, "contact_angle": checks.positive,
            "preload": checks.positive, "stiffness": checks.non_negative})
        checks.in_range("Guideway.contact_angle", self.contact_angle, 1e-3, np.pi / 2)
        self.contact.validate()

    @property
    def k(self) -> float:
        """Roller stiffness constant [N/m^(10/9)] of F = k delta^(10/9)."""
        return self.stiffness if self.stiffness > 0 else palmgren_stiffness(self.contact.length)

    @property
    def preload_per_roller(self) -> float:
        """Q0 = F0 / (4 N) [N]."""
        return self.preload / (4 * self.rollers_per_groove)

    @property
    def delta0(self) -> float:
        """Preload approach of one roller [m]."""
        return float(approach_for_load(self.preload_per_roller, self.k))

    def _geometric_approach(self, y):
        s = np.sin(self.contact_angle) * np.asarray(y, dtype=float)
        return self.delta0 + s, self.delta0 - s


def row_approach(g: Guideway, y, h_upper=0.0, h_lower=0.0):
    """Roller approaches (delta_U, delta_L) [m] of eq. 3 (consistent form, module doc)."""
    du, dl = g._geometric_approach(y)
    return du + h_upper, dl + h_lower


def row_loads(g: Guideway, y, h_upper=0.0, h_lower=0.0):
    """Loads (F_U, F_L) [N] of one upper and one lower roller at displacement y and given films."""
    du, dl = row_approach(g, y, h_upper, h_lower)
    return contact_force(du, g.k), contact_force(dl, g.k)


def net_force(g: Guideway, f_upper, f_lower):
    """Net vertical contact force on the moving body [N], 2 N sin(theta) (F_U - F_L), eq. 1b/6."""
    return 2 * g.rollers_per_groove * np.sin(g.contact_angle) * (
        np.asarray(f_upper) - np.asarray(f_lower))


def frozen_film_stiffness(g: Guideway, y, h_upper=0.0, h_lower=0.0):
    """dF_N/dy [N/m] with the films held fixed: the dry stiffness (eq. 14) at the given films."""
    du, dl = row_approach(g, y, h_upper, h_lower)
    n, s = g.rollers_per_groove, np.sin(g.contact_angle)
    return 2 * n * s * s * (contact_stiffness(du, g.k) + contact_stiffness(dl, g.k))


def _solve_steady_load(g: Guideway, delta_geom, c, m, rtol=1e-12, max_iter=200):
    """Roller load F [N] > 0 of the steady lubricated contact: z(F) = delta_geom + C F^-m with
    z(F) = (F / k)^(9/10) the elastic approach, vectorised.

    The difference of both sides rises monotonically from -inf (F -> 0: the law's film
    diverges) to +inf, so every row has one solution: a row whose geometry has parted
    (delta_geom < 0) carries the load whose steady film closes the gap, vanishingly small
    (about 1e-16 N for a gap of five films). Solved for q = ln F by Newton steps safeguarded by
    bisection within a bracket widened by e^8 until it holds the root, converged when each
    residual is below ``rtol`` of its scale |delta_geom| + C F^-m. (scipy's elementwise
    bracketing solver does the same at about 3 ms a call, too slow for a contact FMU.)
    Raises ValueError naming the approaches whose load is no double (the bracket then grows
    past MAX_WIDENINGS) and RuntimeError naming those not converged within ``max_iter`` steps.
    """
    d = np.asarray(delta_geom, dtype=float)
    c = np.broadcast_to(np.asarray(c, dtype=float), d.shape)

    def residual(q):
        z, h = (np.exp(q) / g.k) ** (1.0 / EXPONENT), c * np.exp(-m * q)
        return z - d - h, z / EXPONENT + m * h, np.abs(d) + h

    dry = c == 0.0  # no entrainment (u = 0): no film
    c = np.where(dry, 1.0, c)
    q = np.log(contact_force(np.maximum(d, 0.0) + c, g.k))  # the gap's load, a film added
    lo, hi = _widened(residual, q - 8.0, -8.0, d), _widened(residual, q + 8.0, 8.0, d)
    for _ in range(max_iter):
        val, slope, scale = residual(q)
        if np.all(converged := np.abs(val) <= rtol * scale):
            return np.where(dry, contact_force(d, g.k), np.exp(q))
        lo, hi = np.where(val < 0.0, q, lo), np.where(val > 0.0, q, hi)
        step = q - val / slope
        q = np.where((step > lo) & (step < hi), step, 0.5 * (lo + hi))
    raise RuntimeError(f"steady roller load: Newton's method did not converge within {max_iter} "
                       f"steps for the geometric approach {_listed(d[~converged])} m")


#: widenings of a bracket end of ln F by 8: from any finite start, 200 of them pass the whole
#: range of doubles (ln F from -745 to 710), so a bracket still without the root has none
MAX_WIDENINGS = 200


def _widened(residual, end, by: float, d):
    """The bracket ``end`` of ln F moved by ``by`` where the residual has not yet changed sign
    there (below the root for by < 0, above it for by > 0), at most MAX_WIDENINGS times."""
    for _ in range(MAX_WIDENINGS):
        short = residual(end)[0] * by < 0.0  # the residual's sign at the end is not yet by's
        if not np.any(short):
            return end
        end = np.where(short, end + by, end)
    raise ValueError(f"steady roller load: no roller load [N] balances the geometric approach "
                     f"{_listed(d[short])} m (its elastic load exceeds the largest double)")


def _listed(values) -> str:
    return ", ".join(f"{v:.3g}" for v in np.ravel(values))


def quasi_static_state(g: Guideway, y, u=0.0, lubricated: bool = True):
    """Steady state of the rows at displacement y [m] and feed velocity u [m/s], squeeze neglected.

    Returns (F_U, F_L, h_U, h_L): roller loads [N] and films [m], solving each roller's load
    and film together (the film thins as the load grows). A row whose geometry has parted keeps a
    vanishing load under the film that closes the gap (:func:`_solve_steady_load`).
    ``lubricated=False`` is the dry contact.
    """
    du, dl = g._geometric_approach(y)
    if not lubricated:
        return (contact_force(du, g.k), contact_force(dl, g.k), np.zeros_like(du), np.zeros_like(dl))
    c, m = film_law(g.contact, u)
    geom = np.stack(np.broadcast_arrays(du, dl))
    f = _solve_steady_load(g, geom, np.broadcast_to(c, geom.shape), m)
    h = steady_film(g.contact, f, u)
    return f[0], f[1], h[0], h[1]


def quasi_static_stiffness(g: Guideway, y, u=0.0, lubricated: bool = True, state=None):
    """Quasi-static stiffness K(y) = dF_N/dy [N/m] (eqs. 6-14, corrected: module doc).

    ``state`` is :func:`quasi_static_state` at the same arguments where the caller has it.
    """
    fu, fl, hu, hl = quasi_static_state(g, y, u, lubricated) if state is None else state
    _, m = film_law(g.contact, u)
    s = np.sin(g.contact_angle)

    def row_gain(load, h, delta_geom):  # dh/dF = -m h / F; no film (u = 0): the dry k'
        kp = contact_stiffness(delta_geom + h, g.k)
        softening = np.divide(m * h, load, out=np.zeros_like(h), where=h > 0.0)
        return kp / (1.0 + kp * softening)

    du, dl = g._geometric_approach(y)
    return 2 * g.rollers_per_groove * s * s * (row_gain(fu, hu, du) + row_gain(fl, hl, dl))


def static_displacement(g: Guideway, load: float, u: float = 0.0,
                        lubricated: bool = True) -> float:
    """y [m] at which the rows carry the vertical load [N] (positive along y) in the steady state
    of :func:`quasi_static_state` at the feed velocity u [m/s]: a body at rest in static
    equilibrium, its films steady. The bracket's ends are tried at 2^0 ... 2^63 times the
    preload's reach (MAX_DOUBLINGS); a load no displacement within them carries is refused
    (ValueError naming it)."""
    def excess(y):
        return float(net_force(g, *quasi_static_state(g, y, u, lubricated)[:2])) - load

    what = f"static displacement under {load:.6g} N at u = {u:.6g} m/s"
    reach = g.delta0 / np.sin(g.contact_angle)
    high = _doubled(excess, reach, 1.0, what)
    low = _doubled(excess, -reach, -1.0, what)
    return bracketed_root(excess, low, high, what, xtol=1e-18, rtol=1e-14)


MAX_DOUBLINGS = 64  # ends tried on each side of the static displacement's bracket


def _doubled(excess, end: float, sign: float, what: str) -> float:
    """``end`` [m] doubled until the excess load there has the ``sign`` of the bracket's side
    (> 0 above the root, < 0 below it); at most MAX_DOUBLINGS ends are tried."""
    for _ in range(MAX_DOUBLINGS):
        if not sign * excess(end) < 0.0:
            return end
        end *= 2.0
    raise ValueError(f"{what}: no displacement within {abs(end) / 2.0:.3g} m carries the load")


def film_rates(g: Guideway, y, h_upper, h_lower, u):
    """Film growth rates (dh_U/dt, dh_L/dt) [m/s] of the extrapolated film with its squeeze term.

    Each row's film relaxes towards a quarter of its unsqueezed value h_s at the current load,
    through :func:`film.film_rate` (the published squeeze relation solved for dh/dt).
    """
    f_u, f_l = row_loads(g, y, h_upper, h_lower)
    hs = unsqueezed_film(g.contact, np.stack([f_u, f_l]), u)
    return film_rate(np.stack([h_upper, h_lower]), hs, u)


class RowKernel:
    """The contact of a :class:`Guideway` on Python floats, constants computed once.

    The fast path that the contact FMU and the monolithic reference evaluate every step (about a
    microsecond a call against tens for the array functions above, which the tests use as its
    independent check). Films [m] are inputs: the frozen-film view of :func:`row_loads`.
    """

    def __init__(self, g: Guideway):
        self.k, self.delta0 = g.k, g.delta0
        self.sin = math.sin(g.contact_angle)
        self.gain = 2 * g.rollers_per_groove * self.sin  # net force per unit load difference
        self.force_1um = self.gain * self.k * MICRON ** EXPONENT  # N, net force at 1 um approach
        c1, self.m = film_law(g.contact, 1.0)
        self.speed_exponent = speed_exponent(g.contact)
        # unsqueezed film h_s = coeff |u|^p F^-m (extrapolated law); steady film h_s * 0.25
        self.hs_coeff = float(c1 / squeeze_factor(0.0, 1.0)) if g.contact.model == "extrapolated" else 0.0

    def loads(self, y: float, h_upper: float, h_lower: float):
        """(F_U, F_L) [N] of one upper and one lower roller, as :func:`row_loads`."""
        s = self.sin * y
        du, dl = self.delta0 + s + h_upper, self.delta0 - s + h_lower
        return (self.k * du ** (10 / 9) if du > 0.0 else 0.0,
                self.k * dl ** (10 / 9) if dl > 0.0 else 0.0)

    def contact(self, y: float, h_upper: float, h_lower: float):
        """(F_net [N], K [N/m] frozen films, F_U [N], F_L [N]) as :func:`net_force` and
        :func:`frozen_film_stiffness`."""
        s = self.sin * y
        du, dl = self.delta0 + s + h_upper, self.delta0 - s + h_lower
        fu = self.k * du ** (10 / 9) if du > 0.0 else 0.0
        fl = self.k * dl ** (10 / 9) if dl > 0.0 else 0.0
        ku = 10 / 9 * fu / du if du > 0.0 else 0.0
        kl = 10 / 9 * fl / dl if dl > 0.0 else 0.0
        return self.gain * (fu - fl), self.gain * self.sin * (ku + kl), fu, fl

    def rows(self, h_upper: float, h_lower: float, rate_upper: float = 0.0,
             rate_lower: float = 0.0) -> OpposedRows:
        """The net force as the interface law the body integrates over a step: films h [m]
        moving at the given rates [m/s]; ``rows(...).force(y)`` is ``contact(y, ...)[0]``."""
        return OpposedRows(self.force_1um, EXPONENT, self.sin,
                           self.delta0 + h_upper, self.delta0 + h_lower, rate_upper, rate_lower)

    def film_rate(self, h: float, load: float, speed: float) -> float:
        """dh/dt [m/s] of one row's extrapolated film h [m] under load [N] at |u| = speed [m/s]
        (h / h_s = h F^m / C(u), 0 for an unloaded roller: :mod:`film`)."""
        if speed == 0.0:
            return 0.0
        ratio = (h * load ** self.m / (self.hs_coeff * speed ** self.speed_exponent)
                 if load > 0.0 else 0.0)
        arg = (1.0 - ratio) / SQUEEZE_WEIGHT
        s = math.log(arg) if arg > 0.0 else S_MIN
        return speed * min(max(s, S_MIN), S_MAX) / SQUEEZE_GAIN

    def film_rates(self, y: float, h_upper: float, h_lower: float, u: float):
        """(dh_U/dt, dh_L/dt) [m/s] as :func:`film_rates`."""
        fu, fl = self.loads(y, h_upper, h_lower)
        speed = abs(u)
        return self.film_rate(h_upper, fu, speed), self.film_rate(h_lower, fl, speed)
