"""Vertical dynamics of the moving body (paper 000, eq. 1b): M y'' = M g + F_ext - F_contact.

y [m] is positive in the direction of gravity and of the external load. Over one communication
step of length H the contact force is taken as its value at the start of the step plus its
tangent, F_contact(t) = F0 + K (y - y0) + C (y' - v0), with the contact model's tangent stiffness
K [N/m] and damping C [N s/m] (K = C = 0: the force is held constant). The resulting linear ODE
with constant coefficients is integrated exactly with a matrix exponential, so the step is exact
for the held/linearised force whatever H is, and unconditionally stable for K, C >= 0.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

from . import checks

STANDARD_GRAVITY = 9.80665  # m/s^2


@dataclass(frozen=True)
class Body:
    """The moving body of eq. 1b; the default mass is our assumption (see ``mass``)."""

    # 2.9 kg: about 0.26 m of a 45 mm x 38 mm steel rail (about 11 kg/m), which puts the
    # unloaded natural frequency of the default guideway at the paper's 6590 Hz (within 1 %).
    mass: float = 2.9  # kg
    gravity: float = STANDARD_GRAVITY  # m/s^2

    def validate(self) -> None:
        checks.check_fields(self, {"mass": checks.positive, "gravity": checks.finite})


def step(body: Body, y: float, v: float, h: float, f_ext: float, f_contact: float,
         k_contact: float = 0.0, c_contact: float = 0.0):
    """Advance (y [m], v [m/s]) by the step h [s]; returns (y, v, a) at the end of the step."""
    checks.non_negative("k_contact", k_contact)
    checks.non_negative("c_contact", c_contact)
    m = body.mass
    # y'' = b - (K/M) y - (C/M) y' with everything held over the step folded into b.
    b = body.gravity + (f_ext - f_contact + k_contact * y + c_contact * v) / m
    a_mat = np.array([[0.0, 1.0, 0.0],
                      [-k_contact / m, -c_contact / m, b],
                      [0.0, 0.0, 0.0]])
    y1, v1, _ = expm(a_mat * h) @ np.array([y, v, 1.0])
    return float(y1), float(v1), float(b - (k_contact * y1 + c_contact * v1) / m)
