"""Reduced outputs of a run: one number per recorded variable, after an optional settle time.

peak      largest magnitude max |x|                           [unit of x]
rms       root mean square sqrt(int x^2 dt / T) (trapezoid, so uneven samples weigh by time)
envelope  max x - min x (the width of the band the signal fills)
dominant_frequency
          frequency of the highest line of the Hann-windowed amplitude spectrum, the mean
          removed (cosim.plots.spectrum), refined between bins by a parabola through the
          logarithms of the three highest bins                 [Hz]
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..numerics.spectrum import spectrum, uniform_grid
from ..cosim.recording import Recording


def peak(time, values) -> float:
    return float(np.max(np.abs(values)))


def rms(time, values) -> float:
    from scipy.integrate import trapezoid  # here: scipy.integrate takes long to import
    return float(np.sqrt(trapezoid(np.square(values), time) / (time[-1] - time[0])))


def envelope(time, values) -> float:
    return float(np.max(values) - np.min(values))


def dominant_frequency(time, values) -> float:
    grid = uniform_grid(time)
    freq, amplitude = spectrum(grid, np.interp(grid, time, values))
    k = 1 + int(np.argmax(amplitude[1:]))  # bin 0 is the (removed) mean
    if k + 1 < amplitude.size and min(amplitude[k - 1], amplitude[k + 1]) > 0:
        a, b, c = np.log(amplitude[k - 1:k + 2])
        if a - 2 * b + c < 0:
            return float(freq[k] + 0.5 * (a - c) / (a - 2 * b + c) * (freq[1] - freq[0]))
    return float(freq[k])


REDUCTIONS = {f.__name__: f for f in (peak, rms, envelope, dominant_frequency)}
QUANTITY = {"peak": "peak |x| of", "rms": "RMS of", "envelope": "max - min of",
            "dominant_frequency": "dominant frequency of"}  # axis labels: "<QUANTITY> <variable>"


@dataclass(frozen=True)
class Output:
    """A reduced output a sweep asks for: ``kind`` (a name of REDUCTIONS) of the recorded
    ``variable`` ("<instance>.<variable>") over the run after its first ``settle`` seconds."""

    variable: str
    kind: str
    settle: float = 0.0

    @property
    def column(self) -> str:
        return f"{self.kind}({self.variable})"

    def unit(self, variable_unit: str) -> str:
        return "Hz" if self.kind == "dominant_frequency" else variable_unit

    def of(self, recording: Recording) -> float:
        """The reduced value; ValueError naming the column when too few samples remain."""
        time, values = recording.time, recording.columns[self.variable]
        keep = time >= time[0] + self.settle
        if np.count_nonzero(keep) < 8:
            raise ValueError(f"{self.column}: {np.count_nonzero(keep)} recorded samples after the "
                             f"settle time {self.settle:g} s, need at least 8")
        return REDUCTIONS[self.kind](time[keep], values[keep])
