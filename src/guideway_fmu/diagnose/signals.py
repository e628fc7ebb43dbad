"""The feed motion that drives the model, from the measured channels, and where it reverses.

Position, velocity and acceleration come from the channels where measured; what is missing is
derived with a Savitzky-Golay filter (cubic, zero phase: no delay) on a uniform grid at the
median sampling interval (uneven records are interpolated onto it and back). A measured channel
is smoothed with the same filter only when its own noise (robust second-difference estimate)
exceeds 1e-4 of its range. The window spans about 1/40 of the median time between velocity
reversals, 5 to 51 samples, shorter where the motion has faster content (:func:`_window`).
The acceleration is then scaled by its least-squares gain against a short-window derivative of
the position (:func:`_acceleration_gain`), which undoes on average how differencing and
smoothing lower short acceleration pulses.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import cumulative_trapezoid
from scipy.signal import savgol_filter

NOISY = 1e-4  # channel noise / range above which a measured channel is smoothed
STANDSTILL = 0.01  # |v| below this fraction of max |v|: direction of motion ambiguous
SHORT = 7  # samples of the cubic filter giving the unbiased acceleration the gain refers to


def noise_rms(y) -> float:
    """RMS of white noise in y, from the MAD of its second differences (robust to steps)."""
    d2 = np.diff(np.asarray(y, dtype=float), 2)
    return float(1.4826 * np.median(np.abs(d2 - np.median(d2))) / np.sqrt(6.0))


def channel_noise(y) -> float:
    """RMS noise of a measured channel: :func:`noise_rms`, but at least the rounding noise
    q / sqrt(12) of a channel whose values lie on a lattice of step q (an encoder count, or a
    difference of counts), where most second differences are 0 and their MAD says nothing."""
    y = np.asarray(y, dtype=float)
    steps = np.abs(np.diff(y))
    steps = steps[steps > 1e-9 * max(float(np.max(np.abs(y))), 1e-300)]
    if steps.size == 0:
        return noise_rms(y)
    q = float(np.min(steps))
    on_lattice = np.mean(np.abs(steps / q - np.round(steps / q)) < 1e-3) > 0.99
    return max(noise_rms(y), q / np.sqrt(12.0) if on_lattice else 0.0)


@dataclass
class Motion:
    """Feed motion at the samples: x [m], v [m/s], a [m/s^2]; ``standstill`` marks samples whose
    direction is ambiguous; ``how`` says how each signal was obtained."""

    time: np.ndarray
    x: np.ndarray
    v: np.ndarray
    a: np.ndarray
    standstill: np.ndarray
    reversals: np.ndarray  # sample indices where the direction of motion changes
    how: dict

    def since_reversal(self) -> tuple[np.ndarray, np.ndarray]:
        """Time [s] and displacement [m] since the last reversal (since the start before the first)."""
        last = np.zeros(self.time.size, dtype=int)
        last[self.reversals] = self.reversals
        last = np.maximum.accumulate(last)
        return self.time - self.time[last], np.abs(self.x - self.x[last])


class _Grid:
    """Savitzky-Golay derivatives on a uniform grid at the median step of ``time``."""

    def __init__(self, time, window):
        self.time = time
        self.step = float(np.median(np.diff(time)))
        self.uniform = np.ptp(np.diff(time)) <= 1e-6 * self.step
        self.grid = time if self.uniform else np.arange(time[0], time[-1] + 0.5 * self.step, self.step)
        self.longest = int(self.grid.size - (1 - self.grid.size % 2))  # odd, within the grid
        self.window = min(int(window), self.longest)

    def filter(self, y, deriv=0, window=None):
        on_grid = y if self.uniform else np.interp(self.grid, self.time, y)
        window = self.window if window is None else min(window, self.longest)
        out = savgol_filter(on_grid, window, 3, deriv=deriv, delta=self.step, mode="interp")
        return out if self.uniform else np.interp(self.time, self.grid, out)


def _window(time, velocity_like) -> int:
    """Odd window [samples]: about 1/40 of the median samples between sign changes, 5..51, and
    short enough that the cubic filter's cutoff, about 4 / (3.2 M - 4.6) of the Nyquist frequency
    for 2 M + 1 samples (Schafer 2011), lies 3x above the highest frequency standing 30x above
    the median of the velocity's spectrum."""
    signs = np.sign(velocity_like)
    moving = np.flatnonzero(signs != 0)
    changes = moving[1:][signs[moving[1:]] != signs[moving[:-1]]]
    per_stroke = np.median(np.diff(changes)) if changes.size > 2 else time.size
    amplitude = np.abs(np.fft.rfft(velocity_like - np.mean(velocity_like)))
    strong = np.flatnonzero(amplitude[1:] > 30.0 * np.median(amplitude[1:])) + 1
    if strong.size:
        highest = strong[-1] / (amplitude.size - 1)  # fraction of the Nyquist frequency
        half = (4.0 / min(3.0 * highest, 1.0) + 4.6) / 3.2
        per_stroke = min(per_stroke, 80 * half)
    return int(np.clip(2 * (per_stroke // 80) + 1, 5, 51))


def _acceleration_gain(grid: _Grid, columns: dict, a) -> float:
    """Least-squares gain [-] of an unbiased acceleration on ``a`` [m/s^2]: the second derivative
    of the position (first of the velocity where no position is recorded) by a cubic filter over
    only SHORT samples, exact for cubic motion. Differencing and smoothing spread and lower short
    acceleration pulses (a ramp of a few ms); their least-squares scale then errs by several per
    cent, which a mass term would take up. The short filter's noise averages out in the gain."""
    if "feed_position" in columns:
        short = grid.filter(columns["feed_position"], deriv=2, window=SHORT)
    else:
        short = grid.filter(columns["feed_velocity"], deriv=1, window=SHORT)
    power = float(np.dot(a, a))
    return float(np.dot(short, a) / power) if power > 0.0 else 1.0


def derive_motion(time, columns: dict) -> Motion:
    """Motion from the measured ``feed_position`` / ``feed_velocity`` / ``feed_acceleration``."""
    time = np.asarray(time, dtype=float)
    how = {}
    if "feed_velocity" in columns:
        rough = columns["feed_velocity"]
    else:
        rough = np.gradient(columns["feed_position"], time)
    coarse = _Grid(time, max(5, 2 * (time.size // 400) + 1)).filter(rough)
    grid = _Grid(time, _window(time, coarse))
    filt = (f"Savitzky-Golay, cubic, {grid.window} samples ({grid.window * grid.step:.4g} s), "
            f"zero phase (no delay)" + ("" if grid.uniform else ", on a uniform grid at the "
                                        "median step, interpolated back"))

    def measured(name):
        y = columns[name]
        if channel_noise(y) > NOISY * max(np.ptp(y), 1e-300):
            how[name] = f"measured, smoothed ({filt})"
            return grid.filter(y)
        how[name] = "measured"
        return np.asarray(y, dtype=float)

    if "feed_velocity" in columns:
        v = measured("feed_velocity")
    else:
        v = grid.filter(columns["feed_position"], deriv=1)
        how["feed_velocity"] = f"derived from feed_position: first derivative, {filt}"
    if "feed_position" in columns:
        x = measured("feed_position")
    else:
        x = cumulative_trapezoid(v, time, initial=0.0)
        how["feed_position"] = "integrated from feed_velocity (trapezoid rule, x = 0 at the start)"
    if "feed_acceleration" in columns:
        a = measured("feed_acceleration")
    elif "feed_velocity" in columns:
        a = grid.filter(v, deriv=1)
        how["feed_acceleration"] = f"derived from feed_velocity: first derivative, {filt}"
    else:
        a = grid.filter(columns["feed_position"], deriv=2)
        how["feed_acceleration"] = f"derived from feed_position: second derivative, {filt}"
    gain = _acceleration_gain(grid, columns, a)
    a = gain * a
    how["feed_acceleration"] += (f"; scaled by {gain:.4g}, the least-squares gain of the "
                                 f"{SHORT}-sample second derivative of feed_position (first of "
                                 f"feed_velocity without it) on it")
    limit = STANDSTILL * np.max(np.abs(v))
    standstill = np.abs(v) <= limit
    how["standstill"] = f"|feed_velocity| <= {limit:.4g} m/s ({STANDSTILL:.0%} of its maximum)"
    moving = np.flatnonzero(~standstill)
    signs = np.sign(v[moving])
    reversals = moving[1:][signs[1:] != signs[:-1]]
    return Motion(time, x, v, a, standstill, reversals, how)
