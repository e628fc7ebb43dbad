"""Horizontal drive rig: the force a drive spends moving a mass against friction, SI units.

The drive moves the moving part (mass m [kg]) along the rail with acceleration a [m/s^2]
against the friction force F_friction [N] acting ON the part (opposing its motion):

    drive_force    = m a - F_friction + drive_offset
    friction_force = -F_friction + friction_offset   (what a rig reports as drive_force - m a)

The offsets [N] are sensor zeros of the measured channels.
"""
from __future__ import annotations

import numpy as np

from .. import checks
from ..dynamics import Algebraic


def drive_force(acceleration, friction, mass, offset=0.0):
    """Drive force [N] moving ``mass`` [kg] at ``acceleration`` [m/s^2] against ``friction`` [N]."""
    return mass * np.asarray(acceleration, dtype=float) - np.asarray(friction, dtype=float) + offset


def friction_force(friction, offset=0.0):
    """The friction force as a rig derives it [N]: the resistance along the motion, -F_friction."""
    return offset - np.asarray(friction, dtype=float)


def from_parameters(mass, drive_offset, friction_offset) -> Algebraic:
    """The validated model of the HorizontalRig FMU's parameters (fmus/README.md): inputs
    a [m/s^2], F_friction [N]; outputs drive_force, friction_force [N]."""
    checks.non_negative("mass", mass)
    checks.finite("drive_offset", drive_offset)
    checks.finite("friction_offset", friction_offset)
    return Algebraic(("a", "F_friction"), lambda a, F_friction: {
        "drive_force": drive_force(a, F_friction, mass, drive_offset),
        "friction_force": friction_force(F_friction, friction_offset)})
