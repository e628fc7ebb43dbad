"""Continuous-time models of physical subsystems: the model-exchange view, SI units.

A model reads named inputs, may carry states, and gives named outputs, like SciPy's
``fun(t, y)``: ``derivatives(t, state, inputs)`` is the right-hand side and
``outputs(t, state, inputs)`` the algebraic part. The same object serves twice: an FMU advances
it over a communication step with the model's own fixed-step integrator (inputs held or
interpolated as its coupling needs), and the monolithic reference (``reference/``) stacks the
models of a whole scenario into one state vector and integrates it with SciPy. Each equation is
therefore written once, here in ``physics/``.

``inputs`` lists only the inputs the equations read; FMU inputs that serve the coupling alone
(tangents, interface laws) are not among them.
"""
from __future__ import annotations

import math
from abc import ABC, abstractmethod

import numpy as np


class ContinuousModel(ABC):
    """Base class; a stateless model overrides :meth:`outputs` only."""

    #: names of the inputs the equations read
    inputs: tuple[str, ...] = ()
    #: names of the states, in the order of the state vectors
    states: tuple[str, ...] = ()
    #: False where the derivatives jump with the state (contacts that close and part) or
    #: rise with an infinite slope (the film rate of a roller that lands): an implicit
    #: integrator's Jacobian fails there, so the reference steps such a model with an explicit
    #: Runge-Kutta method whose error control places its steps around them
    smooth: bool = True

    def state_scales(self) -> tuple[float, ...]:
        """Nominal magnitude of each state (its unit): the reference's absolute tolerances are
        its relative tolerance times these."""
        return ()

    def initial_state(self, t: float, inputs: dict) -> tuple[float, ...]:
        """The state at the start time t [s] from the inputs there."""
        return ()

    def derivatives(self, t: float, state, inputs: dict) -> tuple[float, ...]:
        """d(state)/dt at the time t [s]."""
        return ()

    @abstractmethod
    def outputs(self, t: float, state, inputs: dict, wanted=None) -> dict[str, float]:
        """The outputs at the time t [s]: every one, or at least the ``wanted`` names (a model
        with a cheaper path for a few of them may give only those)."""

    def evaluate(self, t: float, state, inputs: dict) -> tuple[tuple, dict]:
        """(derivatives, outputs) at once; a model whose two share work overrides it."""
        return self.derivatives(t, state, inputs), self.outputs(t, state, inputs)


class Algebraic(ContinuousModel):
    """A stateless model: ``function(**inputs)`` returns the outputs by name."""

    def __init__(self, inputs: tuple[str, ...], function):
        self.inputs, self.function = tuple(inputs), function

    def outputs(self, t, state, inputs, wanted=None):
        return self.function(**{name: inputs[name] for name in self.inputs})


#: Most substeps one communication step may take: past it an FMU refuses the step (discard,
#: naming the cause) instead of computing for minutes inside one FMI call
MAX_SUBSTEPS = 100_000


def substeps(count: float, what: str) -> int:
    """The whole number of substeps [-] a step needs, ``count`` rounded up (at least 1); raises
    ValueError naming ``what`` sets their length when that is more than MAX_SUBSTEPS or not a
    number."""
    if not count <= MAX_SUBSTEPS:
        raise ValueError(f"the step needs {count:.3g} substeps of {what} (more than "
                         f"{MAX_SUBSTEPS}): shorten the step or check the parameters")
    return max(1, math.ceil(count))


def rk4_step(model: ContinuousModel, t: float, state, inputs: dict, h: float):
    """The state after one classical Runge-Kutta step of ``h`` [s], inputs held over it."""
    y = np.asarray(state, dtype=float)
    k1 = np.asarray(model.derivatives(t, y, inputs))
    k2 = np.asarray(model.derivatives(t + h / 2, y + h / 2 * k1, inputs))
    k3 = np.asarray(model.derivatives(t + h / 2, y + h / 2 * k2, inputs))
    k4 = np.asarray(model.derivatives(t + h, y + h * k3, inputs))
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def regularised_sign(u, velocity_tolerance: float):
    """s(u) = tanh(u / velocity_tolerance) [-], or sign(u) when velocity_tolerance == 0.

    A regularised Coulomb switch, shared by the friction laws of every system: friction passes continuously through velocity reversals
    (and is zero at u = 0, i.e. there is no stiction) instead of jumping by twice its value.
    """
    u = np.asarray(u, dtype=float)
    if velocity_tolerance > 0.0:
        return np.tanh(u / velocity_tolerance)
    return np.sign(u)
