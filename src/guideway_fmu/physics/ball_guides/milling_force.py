"""Cutting force of a straight-fluted end mill on the workpiece (mechanistic model with edge
forces, as in Altintas, Manufacturing Automation, 2nd ed. 2012, ch. 2), SI units: a force
source for the feed unit.

Tooth j of N sits at the immersion angle phi_j = phi_0 + 2 pi (n t + j / N) (n the spindle speed
[rev/s]); while phi_j lies in [phi_st, phi_ex] it cuts the chip h = c sin phi_j, with the feed
per tooth c = |u| / (N n), at the axial depth a:

    F_t = K_tc a h + K_te a,   F_r = K_rc a h + K_re a,   F_a = K_ac a h + K_ae a

and pushes on the tool with F_x = -F_t cos phi - F_r sin phi, F_y = F_t sin phi - F_r cos phi
(x along the feed of the tool through the work, y across) and the axial F_a. The workpiece,
clamped to the table, takes the opposite: (-F_x, -F_y) summed over the cutting teeth, and
-F_a along z (the axial force presses the table down for a positive K_ac, K_ae).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import checks
from ..dynamics import ContinuousModel

FORCES = ("F_x", "F_y", "F_z")


@dataclass(frozen=True)
class EndMill:
    """Spindle speed n [rev/s], teeth N, axial depth a [m], entry and exit angles [rad], the
    cutting coefficients K_tc, K_rc, K_ac [Pa] and edge coefficients K_te, K_re, K_ae [N/m], and
    the angle phi_0 of tooth 0 at t = 0 [rad]."""

    spindle_speed: float
    teeth: int
    axial_depth: float
    entry_angle: float
    exit_angle: float
    K_tc: float
    K_rc: float
    K_ac: float
    K_te: float
    K_re: float
    K_ae: float
    start_angle: float = 0.0

    def __post_init__(self):
        checks.positive("spindle_speed", self.spindle_speed)
        checks.positive_integer("teeth", self.teeth)
        checks.non_negative("axial_depth", self.axial_depth)
        checks.in_range("entry_angle", self.entry_angle, 0.0, np.pi)
        checks.in_range("exit_angle", self.exit_angle, 0.0, np.pi)
        if not self.exit_angle > self.entry_angle:
            raise ValueError(f"exit_angle ({self.exit_angle!r} rad) must exceed entry_angle "
                             f"({self.entry_angle!r} rad)")
        for name in ("K_tc", "K_rc", "K_ac", "K_te", "K_re", "K_ae", "start_angle"):
            checks.finite(name, getattr(self, name))

    def feed_per_tooth(self, feed_velocity: float) -> float:
        """c = |u| / (N n) [m]."""
        return abs(float(feed_velocity)) / (self.teeth * self.spindle_speed)

    def force_on_table(self, t, feed_velocity: float) -> np.ndarray:
        """(F_x, F_y, F_z) [N] on the workpiece at the time(s) t [s]; shape (3,) + shape of t."""
        t = np.asarray(t, dtype=float)
        c = self.feed_per_tooth(feed_velocity)
        teeth = np.arange(self.teeth).reshape((-1,) + (1,) * t.ndim)
        phi = np.mod(self.start_angle + 2 * np.pi * (self.spindle_speed * t + teeth / self.teeth),
                     2 * np.pi)
        cutting = (phi >= self.entry_angle) & (phi <= self.exit_angle)
        h = np.where(cutting, c * np.sin(phi), 0.0)
        edge = np.where(cutting, self.axial_depth, 0.0)
        f_t = self.K_tc * self.axial_depth * h + self.K_te * edge
        f_r = self.K_rc * self.axial_depth * h + self.K_re * edge
        f_a = self.K_ac * self.axial_depth * h + self.K_ae * edge
        on_tool_x = (-f_t * np.cos(phi) - f_r * np.sin(phi)).sum(axis=0)
        on_tool_y = (f_t * np.sin(phi) - f_r * np.cos(phi)).sum(axis=0)
        return np.array([-on_tool_x, -on_tool_y, -f_a.sum(axis=0)])


class MillingForceModel(ContinuousModel):
    """The end mill as a stateless model: input the feed velocity u_feed [m/s], outputs the
    force on the table F_x, F_y, F_z [N] at the time t."""

    inputs = ("u_feed",)

    def __init__(self, mill: EndMill):
        self.mill = mill

    def outputs(self, t, state, inputs, wanted=None):
        return dict(zip(FORCES, map(float, self.mill.force_on_table(t, inputs["u_feed"]))))


def from_parameters(spindle_speed, teeth, axial_depth, entry_angle, exit_angle, K_tc, K_rc, K_ac,
                    K_te, K_re, K_ae, start_angle) -> MillingForceModel:
    """The validated model of the MillingForce FMU's parameters (fmus/README.md)."""
    return MillingForceModel(EndMill(spindle_speed, teeth, axial_depth, entry_angle, exit_angle,
                                     K_tc, K_rc, K_ac, K_te, K_re, K_ae, start_angle))
