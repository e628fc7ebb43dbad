"""Root finding with a bound and a named failure, shared by the physics' solves.

:func:`bracketed_root` is SciPy's Brent method on a bracket the caller found, limited to
MAX_ITERATIONS; where it cannot answer it raises an error that says what was being solved for
and at which input, which a component passes on to its FMU log unchanged (an FMU must never
compute without end inside one FMI call, nor report a solver's bare message).

:func:`newton_system` is Newton's method on a small system with its analytic Jacobian, bounded
in iterations, and :func:`load_steps` applies a load in ever finer steps where a direct solve
misses: the equilibria of the ball guides (feed unit, carriage), which track a root from step to
step and need no more than Newton's method from a near start. Both report the error left and
let the caller word the failure.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

MAX_ITERATIONS = 100  # Brent iterations of one root (SciPy's default)


def bracketed_root(f, low: float, high: float, what: str, **options) -> float:
    """The root of ``f`` in [low, high] (``options``: brentq's xtol, rtol). Raises ValueError
    naming ``what`` (the quantity and the input it was solved at) when f does not change sign
    over the bracket or is not a number at an end, RuntimeError when Brent's method does not
    converge within MAX_ITERATIONS."""
    f_low, f_high = f(low), f(high)
    if not (f_low <= 0.0 <= f_high or f_high <= 0.0 <= f_low):  # no sign change, or NaN
        raise ValueError(f"{what}: no root between {low:.6g} and {high:.6g} (the residual is "
                         f"{f_low:.3g} and {f_high:.3g} there)")
    root, info = brentq(f, low, high, maxiter=MAX_ITERATIONS, full_output=True, disp=False,
                        **options)
    if not (info.converged and math.isfinite(root)):
        raise RuntimeError(f"{what}: Brent's method did not converge within {MAX_ITERATIONS} "
                           f"iterations between {low:.6g} and {high:.6g}")
    return float(root)


def newton_system(residual, jacobian, start, tolerance: float, iterations: int):
    """(x, max |residual(x)|) after Newton's method from ``start``: x -= J(x)^-1 r(x) until
    max |r| <= ``tolerance`` or ``iterations`` steps. The caller judges the answer by the error
    (NaN or inf when the residual overflowed or the Jacobian was singular): Newton's method
    converges quadratically from a start near the root, so a caller that tracks a root starts
    from its last answer and falls back to continuation where this fails."""
    x = np.asarray(start, dtype=float)
    r = residual(x)
    error = float(np.max(np.abs(r)))
    for _ in range(iterations):
        if error <= tolerance or not np.isfinite(error):
            break
        try:
            x = x - np.linalg.solve(jacobian(x), r)
        except np.linalg.LinAlgError:  # singular: no ball resists some motion
            return x, math.inf
        r = residual(x)
        error = float(np.max(np.abs(r)))
    return x, error


def load_steps(solve, load, start, tolerance: float, finest: int):
    """(x, error) of ``solve(load, start)`` (a solve that returns (x, error), such as
    :func:`newton_system` bound to a residual of the load); where the error misses the tolerance,
    the load is applied again from x = 0 in 4, then 16, ... up to ``finest`` equal steps, each
    solved from the last step's answer."""
    x, error = solve(load, start)
    steps = 1
    while not error <= tolerance and steps < finest:
        steps *= 4
        x = np.zeros_like(start)
        for step in range(1, steps + 1):
            x, error = solve(step / steps * load, x)
    return x, error
