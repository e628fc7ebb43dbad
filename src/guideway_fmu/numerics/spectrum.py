"""The one amplitude spectrum of the project and what goes with it: a uniform time grid to
resample onto, the highest peaks, and the power spectrum (a different quantity: variance per
bin).

Scaling: a window (Hann by default, or none: ``window="rectangular"``), the mean removed,
``numpy.fft.rfft`` scaled by 2 / sum(window), so a sine of amplitude A [unit] at a bin frequency
shows a peak of height A whatever the window and the zero padding (spectral leakage spreads a
sine between bins over a few neighbours with Hann's window, over many without one). Run plots,
sweeps, the reference's statistics, the analyses and the discrepancy workflow all read
amplitudes on this scale. A caller that needs only where a peak lies, or how it stands against
the median of the spectrum, reads it here too: those are unchanged by the scale.
"""
from __future__ import annotations

import numpy as np

_RTOL_UNIFORM = 1e-6
#: the windows :func:`spectrum` takes, each with the fewest samples it needs: Hann's (little
#: leakage far from a line; its ends are zeros, so 8 samples leave 6 weighted) or none (the
#: narrowest line, every sample weighted alike: for short series, whose ends a taper would drop)
WINDOWS = {"hann": (np.hanning, 8), "rectangular": (np.ones, 2)}


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


def _checked(time, values, skip: float, least: int) -> tuple[np.ndarray, float]:
    """(values after the first ``skip`` seconds, the sampling step [s]); ValueError for unequal
    or non-1-D arrays, a negative ``skip``, fewer than ``least`` samples left or a non-uniform
    ``time``."""
    time, values = np.asarray(time, float), np.asarray(values, float)
    if time.shape != values.shape or time.ndim != 1:
        raise ValueError(f"time and values must be 1-D of equal length, got {time.shape} and {values.shape}")
    if skip < 0:
        raise ValueError(f"skip must be >= 0 s, got {skip}")
    keep = time - time[:1] >= skip
    time, values = time[keep], values[keep]
    if time.size < least:
        raise ValueError(f"need at least {least} samples after skipping {skip} s, got {time.size}")
    step = _uniform_step(time)
    if step is None:
        raise ValueError("time is not uniformly sampled (relative tolerance 1e-6); "
                         "resample it first, e.g. with numpy.interp onto uniform_grid(time)")
    return values, step


def spectrum(time, values, skip: float = 0.0, pad: int = 1,
             window: str = "hann") -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum of a uniformly sampled signal.

    ``time`` [s] and ``values`` [any unit] have equal length. The first ``skip`` seconds
    (transient) are dropped, the mean of the rest removed, the ``window`` (a key of WINDOWS)
    applied and the ``numpy.fft.rfft`` of ``pad`` times as many samples (the rest zeros: a
    ``pad`` times finer grid of frequencies, no finer resolution) scaled by ``2 / sum(window)``,
    so a sine of amplitude A at a bin frequency shows a peak of height A. Returns
    ``(freq [Hz], amplitude [unit of values])``. Raises ValueError if ``time`` is not uniformly
    sampled (relative tolerance 1e-6), fewer samples than the window needs (WINDOWS) remain
    after ``skip``, ``pad`` is not a whole number >= 1 or ``window`` is not one of WINDOWS.
    """
    if window not in WINDOWS:
        raise ValueError(f"window must be one of {', '.join(WINDOWS)}, got {window!r}")
    if isinstance(pad, bool) or not isinstance(pad, (int, np.integer)) or pad < 1:
        raise ValueError(f"pad must be a whole number >= 1, got {pad!r}")
    shape, least = WINDOWS[window]
    values, step = _checked(time, values, skip, least)
    taper = shape(values.size)
    size = int(pad) * values.size
    amplitude = np.abs(np.fft.rfft((values - values.mean()) * taper, size)) * 2 / taper.sum()
    amplitude[0] /= 2  # DC (and Nyquist, below) have no mirror image to fold in
    if size % 2 == 0:
        amplitude[-1] /= 2
    return np.fft.rfftfreq(size, step), amplitude


def power_spectrum(time, values) -> tuple[np.ndarray, np.ndarray]:
    """One-sided power spectrum (periodogram) of a uniformly sampled signal: ``(freq [Hz],
    power [unit of values squared])``, the variance of ``values`` per bin, no window, so that
    the bins sum to the variance (Parseval) and a band's sum is its share of it; a sine of
    amplitude A at a bin frequency puts A^2 / 2 into its bin. Raises ValueError as
    :func:`spectrum` without a window."""
    values, step = _checked(time, values, 0.0, WINDOWS["rectangular"][1])
    power = np.abs(np.fft.rfft(values - values.mean())) ** 2 * (2 / values.size**2)
    power[0] /= 2  # DC and Nyquist are their own mirror images
    if values.size % 2 == 0:
        power[-1] /= 2
    return np.fft.rfftfreq(values.size, step), power


def peak_indices(amplitude: np.ndarray, count: int) -> np.ndarray:
    """Indices of the ``count`` highest local maxima of ``amplitude``, highest first."""
    inner = np.flatnonzero((amplitude[1:-1] > amplitude[:-2]) & (amplitude[1:-1] >= amplitude[2:])) + 1
    return inner[np.argsort(amplitude[inner])[::-1][:count]]
