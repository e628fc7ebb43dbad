"""A law for a residual no candidate explains: sequentially thresholded least squares (STLSQ)
over terms built from the measured channels, written as a plain-Python expression.

The expression uses the channel names of the format and numpy's ``sign``, ``sin``, ``cos`` and
``pi``; evaluate it with ``eval(expr, {"sign": np.sign, "sin": np.sin, "cos": np.cos,
"pi": np.pi, **channels})``.
"""
from __future__ import annotations

import numpy as np

THRESHOLD = 0.05  # a term is dropped when it changes the prediction by < 5 % of the residual's RMS
ITERATIONS = 10


def library(ctx, frequencies, foreign: bool = False) -> dict[str, np.ndarray]:
    """Candidate terms by expression over the channel names (derived signals where unmeasured).

    ``foreign``: only the terms no candidate effect contains (the normal force, sinusoids at
    ``frequencies`` [Hz]: the residual's peaks the motion does not hold, locate.locate) and the
    baseline's own (constant, Coulomb). The normal force is the recorded channel smoothed
    (Context.load), so that its noise neither biases nor blurs the law.
    """
    m = ctx.motion
    values = {"feed_velocity": m.v, "feed_position": m.x, "feed_acceleration": m.a,
              "time": m.time, "sign": np.sign, "sin": np.sin, "cos": np.cos, "pi": np.pi}
    terms = ["1", "sign(feed_velocity)"] if foreign else [
        "1", "sign(feed_velocity)", "feed_velocity", "feed_velocity**2*sign(feed_velocity)",
        "feed_position", "feed_position*sign(feed_velocity)", "feed_acceleration",
        "time*sign(feed_velocity)"]
    if ctx.load is not None:
        values["normal_force"] = ctx.load
        terms += ["normal_force", "normal_force*sign(feed_velocity)"]
    for f in frequencies:
        terms += [f"sin(2*pi*{f:.6g}*time)", f"cos(2*pi*{f:.6g}*time)"]
    return {t: np.broadcast_to(np.asarray(eval(t, {"__builtins__": {}}, values), dtype=float),
                               m.time.shape) for t in terms}


def stlsq(terms: dict, residual, mask) -> dict[str, float]:
    """Sparse coefficients of ``terms`` fitting ``residual`` on ``mask`` (STLSQ)."""
    names = list(terms)
    matrix = np.column_stack([terms[n][mask] for n in names])
    target = residual[mask]
    scale = np.sqrt(np.mean(matrix ** 2, axis=0))
    scale[scale == 0.0] = 1.0
    active = np.ones(len(names), dtype=bool)
    coef = np.zeros(len(names))
    limit = THRESHOLD * np.sqrt(np.mean(target ** 2))
    for _ in range(ITERATIONS):
        coef[:] = 0.0
        solution, *_ = np.linalg.lstsq(matrix[:, active] / scale[active], target, rcond=None)
        coef[active] = solution / scale[active]
        keep = active & (np.abs(coef) * scale >= limit)
        if np.array_equal(keep, active):
            break
        active = keep
    return {n: float(c) for n, c in zip(names, coef) if c != 0.0}


def expression(coefficients: dict[str, float]) -> str:
    """The sparse law as a plain-Python expression (``0.0`` when empty)."""
    parts = [f"{c:.6g}" if n == "1" else f"{c:.6g}*{n}" for n, c in coefficients.items()]
    return " + ".join(parts).replace("+ -", "- ") or "0.0"


def propose(ctx, residual, fit_mask, frequencies, foreign: bool = False):
    """(expression, its values over all samples, number of terms) of the residual law fitted on
    ``fit_mask`` (``foreign``: from the foreign terms of :func:`library` only)."""
    terms = library(ctx, frequencies, foreign)
    coefficients = stlsq(terms, residual, fit_mask)
    values = sum((c * terms[n] for n, c in coefficients.items()), np.zeros_like(residual))
    return expression(coefficients), values, len(coefficients)
