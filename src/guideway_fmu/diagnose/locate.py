"""Where model and measurement disagree: the fit/held-out split, the gap, the noise floor, and the
residual against time, motion, reversals, running distance and frequency."""
from __future__ import annotations

import numpy as np
from scipy.signal import lombscargle
from scipy.spatial import cKDTree

from ..numerics.spectrum import spectrum
from .signals import noise_rms, rounding_noise, sampling_step

BLOCK = 25  # samples per block (at least); every third block is held out
FOLDS = 3  # cross-validation folds: blocks k, k + 3, ... held out in fold k
MAX_BLOCKS = 600
BINS = 20  # quantile bins of the residual-against-signal statistics
PAIRS = 3000  # samples whose state-matched partner the incoherent noise estimate looks for
REFINE = 41  # trial frequencies over two bins of the spectrum refining a peak
RESOLUTION = 1e-12  # least noise floor, of the channel's range
#: a residual peak is evidence of a foreign force where the motion's signals hold less than this
#: share of a sinusoid at its frequency (on a sinusoidal stroke, all of it at the stroke's)
MOTION_SHARE = 0.5
NEIGHBOURS = 32  # nearest states searched for a partner from another pass


def blocks(n: int) -> int:
    """Number of blocks the record of n samples is cut into."""
    return int(np.clip(n // BLOCK, 3, MAX_BLOCKS))


def split(n: int, usable: np.ndarray, fold: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """(fit, held_out) masks: the record cut into :func:`blocks` equal blocks, every third held
    out, starting at block ``fold`` (0, 1 or 2; 1/3 of the record, spread over all of it; short
    blocks, so that a law of a slowly varying signal is tested between the fit samples around
    it); samples not ``usable`` belong to neither. The three folds hold out every usable sample
    once."""
    count = blocks(n)
    block = np.minimum(np.arange(n) * count // n, count - 1)
    held = (block % FOLDS == fold) & usable
    return usable & ~held, held


def folds(n: int, usable: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """The FOLDS (fit, held_out) splits of :func:`split`, the reported one (fold 1) first."""
    return [split(n, usable, (1 + k) % FOLDS) for k in range(FOLDS)]


def out_of_fold(splits, predictions) -> np.ndarray:
    """Each held-out sample of ``splits`` (:func:`folds`) from the prediction of the model
    fitted without it (``predictions``, one per fold)."""
    pooled = np.zeros_like(predictions[0])
    for (_, held), prediction in zip(splits, predictions):
        pooled[held] = prediction[held]
    return pooled


def gap(measured, simulated, mask) -> float:
    """Range-normalised RMS error on ``mask``: rms(measured - simulated) / range(measured)."""
    m = np.asarray(measured)[mask]
    return float(np.sqrt(np.mean((m - np.asarray(simulated)[mask]) ** 2)) / np.ptp(m))


def noise_floor(measured, residual, mask) -> float:
    """RMS of the measurement noise over the range of ``measured`` on ``mask``, the noise being
    estimated from the high-frequency part of the residual (second differences, robust MAD),
    at least the rounding noise of a channel on a lattice (an ADC step coarser than the noise
    leaves most differences 0 and their MAD 0) and RESOLUTION of the range (a record free of
    noise has the arithmetic's)."""
    span = float(np.ptp(np.asarray(measured)[mask]))
    noise = max(noise_rms(residual), rounding_noise(measured), RESOLUTION * span)
    return noise / span


def incoherent_noise(motion, residual, mask) -> float:
    """RMS [units of ``residual``] of the part of the residual that does not repeat with the
    feed's state: half the mean square difference between the residual at a sample and at the
    sample of nearest state (position, velocity, acceleration, each over its range) on another
    pass, at least half the median time between reversals away (robust: MAD of the
    differences). A model error that is a function of the state cancels in the differences;
    measurement noise of any colour (AR, 1/f, a slow drift) does not, for the partners are far
    apart in time. The white second-difference estimate (:func:`noise_floor`) sees only the
    noise's high-frequency part: for an AR(1) noise of pole 0.95 a fifth of its RMS. Returns 0
    where too few samples have a partner (a record of a single pass)."""
    t = motion.time
    idx = np.flatnonzero(mask)
    if idx.size < 4 * BINS:
        return 0.0
    state = np.column_stack([s / max(float(np.ptp(s[idx])), 1e-300)
                             for s in (motion.x, motion.v, motion.a)])
    turns = np.diff(t[motion.reversals]) if motion.reversals.size > 2 else np.array([np.ptp(t)])
    separation = 0.5 * float(np.median(turns))
    tree = cKDTree(state[idx])
    picked = idx[np.unique(np.linspace(0, idx.size - 1, min(PAIRS, idx.size)).astype(int))]
    _, near = tree.query(state[picked], k=min(NEIGHBOURS, idx.size))
    partners = idx[near]
    far = np.abs(t[partners] - t[picked, None]) >= separation
    found = far.any(axis=1)
    if found.sum() < 2 * BINS:
        return 0.0
    first = partners[found, np.argmax(far[found], axis=1)]
    d = residual[picked[found]] - residual[first]
    return float(1.4826 * np.median(np.abs(d - np.median(d))) / np.sqrt(2.0))


def whiteness(residual, mask, lags: int = 5) -> float:
    """Mean autocorrelation of the residual over lags 1..``lags`` on runs of consecutive samples
    of ``mask``: about 0 (+- 1/sqrt(n)) for noise alone, towards 1 for a structured gap."""
    r = np.where(mask, residual - residual[mask].mean(), 0.0)
    var = float(np.sum(r * r))
    if var == 0.0:
        return 0.0
    return float(np.mean([np.sum(r[k:] * r[:-k] * (mask[k:] & mask[:-k])) / var
                          for k in range(1, lags + 1)]))


def correlation_time(residual, mask, lags: int = 400) -> float:
    """Integrated autocorrelation time [samples] of the residual on runs of consecutive samples
    of ``mask``: 1 + 2 sum of its autocorrelations up to the first lag (at most ``lags``) where
    they are no longer positive; (1 + phi) / (1 - phi) for AR(1) noise of pole phi, 1 for white.
    n samples of such a residual hold about n / tau independent ones."""
    r = np.where(mask, residual - residual[mask].mean(), 0.0)
    var = float(np.sum(r * r))
    if var == 0.0:
        return 1.0
    tau = 1.0
    for k in range(1, min(lags, r.size - 1)):
        rho = float(np.sum(r[k:] * r[:-k] * (mask[k:] & mask[:-k]))) / var
        if rho <= 0.0:
            break
        tau += 2.0 * rho
    return tau


def explained(residual, signal, mask) -> float:
    """Share of the residual's variance explained by its means in quantile bins of ``signal``
    (correlation ratio eta^2, 0..1)."""
    r, s = residual[mask], signal[mask]
    if r.size < 4 * BINS or np.ptp(s) == 0.0:
        return 0.0
    edges = np.quantile(s, np.linspace(0.0, 1.0, BINS + 1))
    index = np.clip(np.searchsorted(edges, s, side="right") - 1, 0, BINS - 1)
    counts = np.bincount(index, minlength=BINS)
    means = np.bincount(index, r, minlength=BINS) / np.maximum(counts, 1)
    total = float(np.sum((r - r.mean()) ** 2))
    return float(np.sum(counts * (means - r.mean()) ** 2) / total) if total > 0 else 0.0


def peak_frequencies(time, residual, mask, count: int = 3) -> list[float]:
    """Up to ``count`` frequencies [Hz] whose residual amplitude stands 8x above the median,
    ignoring the lowest 3 bins (trends), each refined to the maximum of the Lomb-Scargle
    periodogram of the samples on ``mask`` within a bin of the spectrum's peak: a sinusoid
    fitted at a frequency off by a bin drifts half a cycle over the record. The spectrum is
    numerics.spectrum of the residual (zero where not ``mask``) resampled at the record's
    nominal step (signals.sampling_step); only where its peaks lie matters, not its scale."""
    step = sampling_step(time)
    grid = np.arange(time[0], time[-1], step)
    if grid.size < 14:  # fewer than 8 frequencies
        return []
    freq, amp = spectrum(grid, np.interp(grid, time, np.where(mask, residual, 0.0)))
    floor = np.median(amp[3:])
    found = []
    for i in np.argsort(amp[3:])[::-1][:50] + 3:
        if amp[i] < 8.0 * floor or len(found) == count:
            break
        if all(abs(freq[i] - f) > 3 * freq[1] for f in found):
            found.append(float(freq[i]))
    t, r = np.asarray(time)[mask], np.asarray(residual)[mask]
    r = r - r.mean()
    refined = []
    for f in found:  # one trial at a time: scipy's periodogram holds samples x trials arrays
        trial = np.linspace(f - freq[1], f + freq[1], REFINE)
        power = [lombscargle(t, r, np.full(1, 2.0 * np.pi * w)).item() for w in trial]
        refined.append(float(trial[np.argmax(power)]))
    return refined


def signals(ctx) -> dict[str, np.ndarray]:
    """The signals the residual is examined against, by name."""
    m = ctx.motion
    since_t, since_x = m.since_reversal()
    return {"time": m.time, "position": m.x, "velocity": m.v, "speed": np.abs(m.v),
            "acceleration": m.a, "time_since_reversal": since_t,
            "displacement_since_reversal": since_x, "running_distance": ctx.distance}


def locate(ctx, residual, mask) -> dict:
    """Share of the residual explained by each signal, the residual's spectral peaks
    ("frequencies" [Hz]) and those of them a force of foreign origin can be told by
    ("foreign_frequencies": where the motion's own signals, position, velocity, acceleration
    and direction, hold less than MOTION_SHARE of a sinusoid's power over ``mask``; on a
    sinusoidal stroke a missing mass is a sinusoid at the stroke's frequency)."""
    shares = {name: explained(residual, s, mask) for name, s in signals(ctx).items()}
    m = ctx.motion
    found = peak_frequencies(m.time, residual, mask)
    motion = np.column_stack([m.x, m.v, m.a, np.sign(m.v), np.ones(m.time.size)])[mask]
    t = m.time[mask]

    def held_by_motion(f):  # share of the sinusoid's power the motion's signals reproduce
        wave = np.column_stack([np.sin(2 * np.pi * f * t), np.cos(2 * np.pi * f * t)])
        fitted = motion @ np.linalg.lstsq(motion, wave, rcond=None)[0]
        return float(np.sum(fitted**2) / np.sum(wave**2))

    return {"explained": shares, "frequencies": found,
            "foreign_frequencies": [f for f in found if held_by_motion(f) < MOTION_SHARE]}
