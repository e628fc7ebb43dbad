"""The one amplitude spectrum of the project and what goes with it: a uniform time grid to
resample onto, and the highest peaks.

Scaling: a Hann window, the mean removed, ``numpy.fft.rfft`` scaled by 2 / sum(window), so a
sine of amplitude A [unit] at a bin frequency shows a peak of height A (spectral leakage
spreads a sine between bins over at most a few neighbours). Run plots, sweeps, the reference's
statistics, the analyses and the discrepancy workflow all read amplitudes on this scale.
"""
from __future__ import annotations

import numpy as np

_RTOL_UNIFORM = 1e-6


def _uniform_step(time: np.ndarray) -> float | None:
    """The sampling step [s] if ``time`` is uniformly sampled (relative tolerance 1e-6), else None."""
    dt = np.diff(time)
    step = dt.mean() if dt.size else 0.0
    uniform = step > 0 and np.all(np.abs(dt - step) <= _RTOL_UNIFORM * step)
    return float(step) if uniform else None


def uniform_grid(time) -> np.ndarray:
    """``time`` [s] itself if uniformly sampled, else a uniform grid over its span at its median
    step (to resample a recording onto with ``numpy.interp``); ValueError unless increasing."""
    time = np.asarray(time, float)
    if _uniform_step(time) is not None:
        return time
    if np.any(np.diff(time) <= 0):
        raise ValueError("time must be strictly increasing")
    step = np.median(np.diff(time))
    return time[0] + step * np.arange(int((time[-1] - time[0]) / step) + 1)


def spectrum(time, values, skip: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum of a uniformly sampled signal.

    ``time`` [s] and ``values`` [any unit] have equal length. The first ``skip`` seconds
    (transient) are dropped, the mean of the rest removed, a Hann window applied and the
    ``numpy.fft.rfft`` scaled by ``2 / sum(window)``, so a sine of amplitude A at a bin frequency
    shows a peak of height A. Returns ``(freq [Hz], amplitude [unit of values])``.
    Raises ValueError if ``time`` is not uniformly sampled (relative tolerance 1e-6) or fewer
    than 8 samples remain after ``skip``.
    """
    time, values = np.asarray(time, float), np.asarray(values, float)
    if time.shape != values.shape or time.ndim != 1:
        raise ValueError(f"time and values must be 1-D of equal length, got {time.shape} and {values.shape}")
    if skip < 0:
        raise ValueError(f"skip must be >= 0 s, got {skip}")
    keep = time - time[:1] >= skip
    time, values = time[keep], values[keep]
    if time.size < 8:
        raise ValueError(f"need at least 8 samples after skipping {skip} s, got {time.size}")
    step = _uniform_step(time)
    if step is None:
        raise ValueError("time is not uniformly sampled (relative tolerance 1e-6); "
                         "resample it first, e.g. with numpy.interp")
    window = np.hanning(time.size)
    amplitude = np.abs(np.fft.rfft((values - values.mean()) * window)) * 2 / window.sum()
    amplitude[0] /= 2  # DC (and Nyquist, below) have no mirror image to fold in
    if time.size % 2 == 0:
        amplitude[-1] /= 2
    return np.fft.rfftfreq(time.size, step), amplitude


def peak_indices(amplitude: np.ndarray, count: int) -> np.ndarray:
    """Indices of the ``count`` highest local maxima of ``amplitude``, highest first."""
    inner = np.flatnonzero((amplitude[1:-1] > amplitude[:-2]) & (amplitude[1:-1] >= amplitude[2:])) + 1
    return inner[np.argsort(amplitude[inner])[::-1][:count]]
