"""Results of the mixed-EHL solver: distributions, film and pressure figures, friction."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .. import greenwood_tripp as gt
from .inputs import LineContactEHL, lubricant_state


def friction(contact: LineContactEHL, x, p_h, p_a, h):
    """(boundary, viscous) friction per unit length [N/m] from the distributions (eqs. 27-31).

    Boundary (eqs. 25, 27-28), local form of tau_l A_a with tau_l = tau_l0 + beta_m W_a / A_a:
    int (tau_l0 a_a + beta_m p_a) dx, a_a = pi^2 (n beta sigma)^2 F_2(h / sigma) the real
    contact area fraction.
    Viscous (eqs. 29-30), the shear on surface 1 (velocity u_m + u_s / 2) opposing its motion:
    int (1 - a_a) tau dx over the full film (up to the cavitation point), with
    tau = mu u_s / h + (h / 2) dp_h/dx (the sign of eq. 29's +- for this surface). tau is bounded
    by the limiting shear stress tau_l0 + beta_m p_h: a Newtonian Couette stress at EHL
    viscosities (1e6 Pa s and more) would otherwise exceed any shear strength of the lubricant;
    Soleimanian et al. (2020) does not bound it.
    """
    c = contact
    dx = x[1] - x[0]
    surface = c.surface()
    fraction = np.zeros_like(h) if surface is None else gt.asperity_area(h, 1.0, surface)
    boundary = dx * np.sum(c.limiting_shear_stress * fraction + c.limiting_shear_slope * p_a)
    mu = c.viscosity * lubricant_state(p_h, c.viscosity, c.pressure_viscosity)[0]
    limit = c.limiting_shear_stress + c.limiting_shear_slope * p_h
    with np.errstate(divide="ignore", invalid="ignore"):
        couette = np.where(h > 0.0, mu * c.sliding_velocity / h,
                           np.sign(c.sliding_velocity) * np.inf)
    tau = np.clip(np.nan_to_num(couette, nan=0.0) + 0.5 * h * np.gradient(p_h, dx), -limit, limit)
    last = np.nonzero(p_h > 0.0)[0]
    full = np.arange(x.size) <= (last[-1] if last.size else -1)
    viscous = dx * np.sum(((1.0 - fraction) * tau)[full])
    return float(boundary), float(viscous)


@dataclass(frozen=True, eq=False)
class EHLResult:
    """One converged solution (a steady state or one time step), SI units.

    Dimensionless arrays use the Hertz scales of this result's own load: X = x / b,
    P = p / p_H, H = h R / b^2. The scalars use Hamrock's convention: H_c = h(0) / R,
    H_min = min h / R, P_max = max p / E'. ``mass_flow`` is the discrete mass flow per unit
    length divided by rho0 [m^2/s] through the n - 1 cell faces (constant in a steady state).
    """

    contact: LineContactEHL
    x: np.ndarray  # m
    p_h: np.ndarray  # hydrodynamic pressure, Pa
    p_a: np.ndarray  # asperity pressure, Pa
    h: np.ndarray  # film thickness, m
    mass_flow: np.ndarray  # m^2/s, at the faces between nodes
    iterations: int  # Newton iterations, all grid levels
    linear_iterations: int  # GMRES iterations, all grid levels
    time: float = 0.0  # s (transient steps)
    converged: bool = True  # a solution that did not converge raises EHLConvergenceError
    H_c: float = field(init=False)
    H_min: float = field(init=False)
    P_max: float = field(init=False)
    asperity_load_ratio: float = field(init=False)
    boundary_friction: float = field(init=False)  # N/m
    viscous_friction: float = field(init=False)  # N/m
    friction_coefficient: float = field(init=False)
    load_balance_error: float = field(init=False)

    def __post_init__(self):
        c = self.contact
        dx = self.x[1] - self.x[0]
        carried = dx * np.sum(self.p)
        fb, fv = friction(c, self.x, self.p_h, self.p_a, self.h)
        scalars = {
            "H_c": float(np.interp(0.0, self.x, self.h)) / c.radius,
            "H_min": float(np.min(self.h)) / c.radius,
            "P_max": float(np.max(self.p)) / c.e_reduced,
            "asperity_load_ratio": float(dx * np.sum(self.p_a) / carried),
            "boundary_friction": fb,
            "viscous_friction": fv,
            "friction_coefficient": (fb + fv) / c.load,
            "load_balance_error": float(abs(carried - c.load) / c.load),
        }
        for name, value in scalars.items():
            object.__setattr__(self, name, value)

    @property
    def p(self):
        """Total pressure p_h + p_a [Pa] (eq. 15)."""
        return self.p_h + self.p_a

    @property
    def X(self):
        return self.x / self.contact.half_width

    @property
    def P(self):
        return self.p / self.contact.hertz_pressure

    @property
    def H(self):
        return self.h * self.contact.radius / self.contact.half_width**2

    def to_dict(self) -> dict:
        """The inputs and scalar results as plain floats, ints and bools (JSON-ready)."""
        c = self.contact
        out = {"W": c.W, "U": c.U, "G": c.G, "load": c.load, "radius": c.radius,
               "entrainment_velocity": c.entrainment_velocity, "roughness": c.roughness,
               "time": float(self.time), "nodes": int(self.x.size),
               "peklenik": c.peklenik if c.average_flow and c.roughness else None}
        for name in ("H_c", "H_min", "P_max", "asperity_load_ratio", "friction_coefficient",
                     "boundary_friction", "viscous_friction", "load_balance_error"):
            out[name] = float(getattr(self, name))
        out["h_c"] = out["H_c"] * c.radius
        out["h_min"] = out["H_min"] * c.radius
        out["p_max"] = out["P_max"] * c.e_reduced
        out["iterations"] = int(self.iterations)
        out["linear_iterations"] = int(self.linear_iterations)
        out["converged"] = bool(self.converged)
        return out


@dataclass(frozen=True)
class TransientResult:
    """The time steps of a transient solution; steps[0] is the steady state at times[0]."""

    steps: tuple[EHLResult, ...]

    @property
    def times(self):
        return np.array([s.time for s in self.steps])

    def series(self, name: str):
        """The scalar ``name`` (e.g. "H_c") of every step as an array."""
        return np.array([getattr(s, name) for s in self.steps])

    def to_dict(self) -> dict:
        """Scalars of every step as lists (JSON-ready)."""
        per_step = [s.to_dict() for s in self.steps]
        return {key: [d[key] for d in per_step] for key in per_step[0]}
