"""Statistics of a response that hold where its trajectory does not: the envelope per load
cycle, the spectrum's peaks and the distribution of values.

``verify`` compares these between the co-simulation and the reference where the reference is
unpredictable pointwise (reference/criterion.py). Every function takes a time grid [s] and
values in any unit; results are in the unit of the values (frequencies in Hz).
"""
from __future__ import annotations

import numpy as np

from ..numerics.spectrum import peak_indices, spectrum

QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)
PEAKS = 3  # spectral peaks compared
PEAK_SEARCH_BINS = 2  # a peak is looked for this many bins either side of the reference's


def cycle_envelope(time, values, period: float) -> tuple[np.ndarray, np.ndarray]:
    """Maximum and minimum of ``values`` in each complete cycle [time[0] + i period,
    time[0] + (i + 1) period) of ``period`` [s]; the unfinished last cycle is left out.
    Raises ValueError when no cycle is complete or a cycle holds no sample."""
    time, values = np.asarray(time, float), np.asarray(values, float)
    cycles = int(np.floor((time[-1] - time[0]) / period * (1 + 1e-12)))
    if cycles < 1:
        raise ValueError(f"no complete cycle of {period} s in {time[-1] - time[0]} s")
    bounds = np.searchsorted(time, time[0] + period * np.arange(cycles + 1), side="left")
    if np.any(np.diff(bounds) == 0):
        raise ValueError(f"a cycle of {period} s holds no sample: sample more finely")
    last = bounds[-1]
    return (np.maximum.reduceat(values[:last], bounds[:-1]),
            np.minimum.reduceat(values[:last], bounds[:-1]))


def spectral_peaks(time, values, count: int = PEAKS) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies [Hz] and amplitudes of the ``count`` highest local maxima of the Hann-windowed
    amplitude spectrum (cosim.plots.spectrum), highest first."""
    freq, amplitude = spectrum(time, values)
    top = peak_indices(amplitude, count)
    return freq[top], amplitude[top]


def peaks_near(time, values, frequencies) -> tuple[np.ndarray, np.ndarray]:
    """For each of ``frequencies`` [Hz] (another run's peaks), the frequency and amplitude of the
    highest spectral bin of ``values`` within PEAK_SEARCH_BINS bins of it."""
    freq, amplitude = spectrum(time, values)
    bin_width = freq[1] - freq[0]
    found_f, found_a = [], []
    for f0 in frequencies:
        k = int(round(f0 / bin_width))
        lo, hi = max(k - PEAK_SEARCH_BINS, 0), min(k + PEAK_SEARCH_BINS + 1, freq.size)
        best = lo + int(np.argmax(amplitude[lo:hi]))
        found_f.append(freq[best])
        found_a.append(amplitude[best])
    return np.array(found_f), np.array(found_a)


def load_statistics(time, values, period: float, peak_frequencies) -> dict[str, float]:
    """The statistics of a load signal, by name: the mean and standard deviation over the cycles
    of ``period`` [s] of each cycle's maximum and minimum, the spectrum at ``peak_frequencies``
    [Hz] (the reference's peaks; ``peaks_near``) and the quantiles."""
    high, low = cycle_envelope(time, values, period)
    out = {"cycle_max_mean": float(np.mean(high)), "cycle_max_std": float(np.std(high)),
           "cycle_min_mean": float(np.mean(low)), "cycle_min_std": float(np.std(low))}
    f, a = peaks_near(time, values, peak_frequencies)
    for i, (fi, ai) in enumerate(zip(f, a), 1):
        out[f"peak{i}_frequency"], out[f"peak{i}_amplitude"] = float(fi), float(ai)
    return out | distribution(values)


def distribution(values) -> dict[str, float]:
    """The QUANTILES of ``values`` by name ("q05", "q50", ...), interpolated linearly between
    order statistics."""
    levels = np.quantile(np.asarray(values, float), QUANTILES)
    return {f"q{round(100 * q):02d}": float(v) for q, v in zip(QUANTILES, levels)}
