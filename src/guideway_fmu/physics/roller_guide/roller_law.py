"""Roller-raceway contact law F = k * delta^(10/9) (Soleimanian et al. 2020, eq. 2) and its stiffness constant.

``delta`` is the total elastic approach of one roller between its two raceways [m]; a roller
whose approach is zero or negative has lost contact and carries no load (not an error).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import checks

EXPONENT = 10.0 / 9.0
MICRON = 1e-6  # m, the reference approach of the "per micrometre" loads (OpposedRows, FMUs)

# Palmgren's line-contact deflection of ONE roller-raceway contact: delta[mm] = 3.84e-5 Q^0.9 / l^0.8,
# Q in N, l in mm (Palmgren, Ball and Roller Bearing Engineering, 1959; Harris & Kotzalas, eq. 7.8).
PALMGREN_COEFFICIENT_MM = 3.84e-5


def palmgren_stiffness(roller_length: float, contacts_in_series: int = 2) -> float:
    """Stiffness constant k [N/m^(10/9)] of one roller from Palmgren's formula.

    Both contacts of a roller (rail side and carriage side) deform in series, so the
    approach of the roller is ``contacts_in_series`` times that of one contact.
    """
    checks.positive("roller_length", roller_length)
    length_mm = roller_length * 1e3
    c_mm = contacts_in_series * PALMGREN_COEFFICIENT_MM / length_mm**0.8  # mm per N^0.9
    # delta_mm = c_mm Q^0.9  =>  Q = (1e3 delta_m / c_mm)^(1/0.9)
    return float((1e3 / c_mm) ** (1.0 / 0.9))


def contact_force(delta, k: float):
    """Roller load [N] for the approach ``delta`` [m]; zero where ``delta`` <= 0."""
    d = np.maximum(np.asarray(delta, dtype=float), 0.0)
    return k * d**EXPONENT


def contact_stiffness(delta, k: float):
    """dF/d(delta) [N/m] = (10/9) k delta^(1/9); zero where ``delta`` <= 0."""
    d = np.maximum(np.asarray(delta, dtype=float), 0.0)
    return EXPONENT * k * d ** (EXPONENT - 1.0)


def approach_for_load(load, k: float):
    """Inverse of :func:`contact_force`: the approach [m] at which a roller carries ``load`` [N]."""
    return (np.maximum(np.asarray(load, dtype=float), 0.0) / k) ** (1.0 / EXPONENT)


@dataclass(frozen=True)
class OpposedRows:
    """Net force of two opposed rows of power-law contacts over one step: the interface model
    that a contact FMU hands to the body it loads (the stabilised coupling, cosim/algorithms.py).

    F(y, tau) = force_1um [(d_U / 1 um)_+^n - (d_L / 1 um)_+^n] [N], opposing positive y, with the
    row approaches d_U = approach_upper + rate_upper tau + sine y and
    d_L = approach_lower + rate_lower tau - sine y [m], y [m] the body's displacement and tau [s]
    the time since the start of the step (the films move at the given rates [m/s]). For the
    guideway, force_1um = 2 N sin(theta) k (1 um)^(10/9), n = 10/9, sine = sin(theta) and the
    approaches are delta0 + h (module doc of four_rows.py).
    """

    force_1um: float  # N
    exponent: float = EXPONENT
    sine: float = 1.0
    approach_upper: float = 0.0  # m
    approach_lower: float = 0.0  # m
    rate_upper: float = 0.0  # m/s
    rate_lower: float = 0.0  # m/s

    def _approaches(self, y: float, tau: float):
        s = self.sine * y
        return (self.approach_upper + self.rate_upper * tau + s,
                self.approach_lower + self.rate_lower * tau - s)

    def force(self, y: float, tau: float = 0.0) -> float:
        """F(y, tau) [N]."""
        du, dl = self._approaches(y, tau)
        n = self.exponent
        return self.force_1um * (_power(du / MICRON, n) - _power(dl / MICRON, n))

    def stiffness(self, y: float, tau: float = 0.0) -> float:
        """dF/dy [N/m] at (y, tau)."""
        du, dl = self._approaches(y, tau)
        n = self.exponent
        return self.force_1um * n * self.sine / MICRON * (
            _power(du / MICRON, n - 1.0) + _power(dl / MICRON, n - 1.0))


def _power(x: float, n: float) -> float:
    """x^n for x > 0, else 0 (a contact that has opened)."""
    return x**n if x > 0.0 else 0.0
