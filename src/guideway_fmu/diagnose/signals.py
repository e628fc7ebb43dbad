"""The feed motion that drives the model, from the measured channels, and where it reverses.

Position, velocity and acceleration come from the channels where measured; what is missing is
derived with a Savitzky-Golay filter (zero phase: no delay) on a uniform grid at the median
sampling interval (uneven records are interpolated onto it and back by cubic splines). A
measured channel is smoothed with the cubic filter only when its own noise (robust
second-difference estimate) exceeds 1e-4 of its range. The cubic window spans about 1/40 of the
median time between velocity reversals, 5 to 51 samples, shorter where the motion has faster
content (:func:`_window`).

Where the model states how much acceleration noise it can take (the workflow: a share of the
force noise over the moving mass, since the acceleration enters as m a), the acceleration is
the position's second derivative, or without a position and a recorded acceleration the
velocity's first, by a filter of polynomial order ORDER over the shortest window whose noise,
the channel's noise (an encoder's rounding) through the filter, stays within that
(:func:`_acceleration_from`). A recorded acceleration channel is not used beside a position:
rigs difference it from the same encoder with a smoothing of their own, which lowers short
ramps. Otherwise the acceleration comes from the
recorded acceleration, the velocity's or the position's derivative by the cubic filter, scaled
by its least-squares gain against a short-window derivative of the position (or velocity)
(:func:`_acceleration_gain`), which undoes on average how differencing and smoothing lower
short acceleration pulses.

The direction of motion is ambiguous (``Motion.standstill``) where the speed is below 1 % of its
maximum, or, where the position is recorded, below 3 times the velocity's noise or the
regularised sign's width, and at the samples next to such a rest whose position has not left it
(:func:`_at_rest`). Recorded encoder counts are then de-quantised by the acceleration's filter. A
load channel that enters a law as a regressor is smoothed by :func:`smooth_channel`.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from math import comb

import numpy as np
from scipy.integrate import cumulative_trapezoid
from scipy.interpolate import CubicHermiteSpline, CubicSpline
from scipy.signal import get_window, istft, savgol_coeffs, savgol_filter, stft
from scipy.stats import chi2

from ..numerics.spectrum import spectrum

NOISY = 1e-4  # channel noise / range above which a measured channel is smoothed
STANDSTILL = 0.01  # |v| below this fraction of max |v|: direction of motion ambiguous
#: ... or, where the position tells rests apart, below this many times the velocity's noise RMS
#: or the regularised sign's width: samples right after a reversal, slower than 1 % of the top
#: speed, carry pre-sliding friction
AMBIGUOUS = 3.0
#: width v_tol of the models' regularised sign tanh(v / v_tol), as a fraction of max |v| [-];
#: within AMBIGUOUS widths the sign is a numerical smoothing (tanh 3 = 0.995), not physics
SIGN_WIDTH = 1e-3
SHORT = 7  # samples of the cubic filter giving the unbiased acceleration the gain refers to
CONFIDENCE = 3.0  # noise RMS either side of an estimate: its interval in the ICI rule
ORDER = 7  # polynomial order of the filter that differentiates the position twice
#: longest window of that filter: scipy's coefficients of order 7 lose their precision beyond
#: about 150 samples (their sum is 0.002 instead of 0 at 101 samples, 1800 at 201)
LONGEST = 101
COUNTS = 64  # the most lattice steps the least step between samples is searched for
#: false-alarm probability of the lack-of-fit test that marks an acceleration as unresolved
LACK_OF_FIT = 1e-4
NEGLIGIBLE = 1e-4  # acceleration noise / range below which no model can tell it
SMOOTHEST = 513  # longest window [samples] of smooth_channel
LINE = 9.0  # power over white noise's expected one below which denoise_spectrum drops a bin
SEGMENT = 512  # samples of denoise_spectrum's windows (98-390 Hz bins at 50-200 kHz)
SHORTEST_SEGMENT = 16  # samples of its windows on a short record
GAP = 1.5  # intervals over this many nominal steps are filled in Motion.path
CLUSTER = 0.1  # samples closer than this many grid steps are averaged before interpolation
CHUNK = 65536  # windows of the lack-of-fit test evaluated at a time


def noise_rms(y, order: int = 2) -> float:
    """RMS of white noise in y, from the MAD of its differences of ``order`` (robust to steps;
    white noise of RMS s gives them the RMS s sqrt(binomial(2 order, order)); a higher order
    sees less of a smooth signal's curvature)."""
    d = np.diff(np.asarray(y, dtype=float), order)
    return float(1.4826 * np.median(np.abs(d - np.median(d))) / np.sqrt(comb(2 * order, order)))


def rounding_noise(y) -> float:
    """Rounding noise q / sqrt(12) of a channel whose values lie on a lattice of step q (an
    encoder count, or a difference of counts), else 0: the largest q, the least step between
    consecutive samples over 1 to COUNTS, of which 99 % of the steps are whole multiples (a
    fast axis may never move a single count between samples)."""
    y = np.asarray(y, dtype=float)
    steps = np.abs(np.diff(y))
    steps = steps[steps > 1e-9 * max(float(np.max(np.abs(y))), 1e-300)]
    if steps.size == 0:
        return 0.0
    for counts in range(1, COUNTS + 1):
        q = float(np.min(steps)) / counts
        if np.mean(np.abs(steps / q - np.round(steps / q)) < 1e-3) > 0.99:
            return q / np.sqrt(12.0)
    return 0.0


def channel_noise(y, orders=(2,)) -> float:
    """RMS noise of a measured channel: :func:`noise_rms`, the least over the difference
    ``orders`` given (a smooth signal only adds to each; a load with 8 samples per period adds
    many times its noise to the second differences, little to the sixth), but at least its
    :func:`rounding_noise`, where most differences are 0 and their MAD says nothing."""
    return max(min(noise_rms(y, order) for order in orders), rounding_noise(y))


def denoise_spectrum(time, y) -> tuple[np.ndarray, float, float]:
    """(values, noise RMS, share of time-frequency bins kept) of a measured channel that drives a
    lightly damped model, a normal force into an undamped resonance: its white noise would ring
    the model at the natural frequency, where the load itself may hold nothing. On the uniform
    grid (:class:`_Grid`), less the line through its end values, the short-time Fourier transform
    (Hann windows of SEGMENT samples, half overlapping; a Hann window's side lobes fall fast, so
    a line's power stays in its own bins) keeps of each bin X the share 1 - E / |X|^2 by which
    it stands above the expected power E of white noise of RMS sigma (spectral subtraction),
    nothing where |X|^2 is under LINE times E: a bin of noise alone passes once in e^LINE. Two
    sines 10-100 noise RMS high leave 1-4 % of the noise's power an octave above them. The
    channel itself (noise 0, all bins) where its noise is under NOISY of its range; as it is,
    with its noise, where it is shorter than two of the shortest windows (16 samples), too
    short to tell a line from noise."""
    y = np.asarray(y, dtype=float)
    sigma = channel_noise(y, orders=(2, 4, 6))
    if sigma <= NOISY * max(float(np.ptp(y)), 1e-300):
        return y, 0.0, 1.0
    grid = _Grid(time, 5)
    g = grid.on_grid(y)
    if g.size < 2 * SHORTEST_SEGMENT:
        return y, sigma, 1.0
    line = g[0] + (g[-1] - g[0]) * np.linspace(0.0, 1.0, g.size)
    segment = int(min(SEGMENT, 2 ** int(np.log2(max(g.size // 4, SHORTEST_SEGMENT)))))
    _, _, z = stft(g - line, window="hann", nperseg=segment)
    window = get_window("hann", segment)
    ratio = np.abs(z) ** 2 / (sigma**2 * np.sum(window**2) / np.sum(window) ** 2)
    gain = np.where(ratio > LINE, 1.0 - 1.0 / np.maximum(ratio, 1e-300), 0.0)
    gain[0] = 1.0  # the slow part is the load's, not noise
    _, out = istft(gain * z, window="hann", nperseg=segment)
    return grid.back(line + out[:g.size]), sigma, float(np.mean(gain[1:] > 0))


def smooth_channel(time, y) -> tuple[np.ndarray, "Derivation"]:
    """(values, how) of a measured channel that enters a law as a regressor (a load): its noise
    would bias the law's coefficient toward 0 and add to the residual, so a channel noisier than
    NOISY of its range is smoothed by the cubic Savitzky-Golay filter of the longest window,
    doubling from 5 to SMOOTHEST samples, whose residual RMS stays within the channel's noise
    (discrepancy principle: a longer window would take signal with the noise). ``how.noise`` is
    set where the channel is noisy; ``how.window`` is 0 where even 5 samples take signal."""
    y = np.asarray(y, dtype=float)
    noise = channel_noise(y)
    if noise <= NOISY * max(float(np.ptp(y)), 1e-300):
        return y, Derivation()
    grid = _Grid(time, 5)
    kept, how = y, Derivation(noise=noise)
    for window in 2 ** np.arange(2, int(np.log2(SMOOTHEST - 1)) + 1) + 1:
        if window > grid.longest:
            break
        smooth = grid.filter(y, window=int(window))
        if np.sqrt(np.mean((y - smooth) ** 2)) > noise:
            break
        kept, how = smooth, grid.derivation(window=int(window), noise=noise)
    return kept, how


def _resolution(position, rounding) -> float:
    """Half-width [m] of the band within which a recorded position has not moved: half an encoder
    count on a lattice (``rounding`` = q / sqrt(12) > 0), else three times the position's noise
    RMS."""
    return 0.5 * np.sqrt(12.0) * rounding if rounding > 0.0 else 3.0 * noise_rms(position, 4)


def _at_rest(x, standstill, band):
    """``standstill`` widened, around each run of it, by the neighbouring samples whose position
    x [m] stays within ``band`` [m] of the run's median position."""
    rest = standstill.copy()
    idx = np.flatnonzero(standstill)
    if idx.size == 0:
        return rest
    breaks = np.flatnonzero(np.diff(idx) > 1)
    for first, last in zip(idx[np.r_[0, breaks + 1]], idx[np.r_[breaks, idx.size - 1]]):
        home = np.median(x[first:last + 1])
        for j, step in ((first - 1, -1), (last + 1, 1)):
            while 0 <= j < x.size and abs(x[j] - home) <= band:
                rest[j] = True
                j += step
    return rest


@dataclass(frozen=True)
class Derivation:
    """How one signal of the motion was obtained from the record (report.py words it).

    ``source``: the channel it comes from ("" where it is that channel itself); ``derivative``:
    the order of the derivative taken (-1: integrated by the trapezoid rule); ``window`` [samples]
    and ``order``: the zero-phase Savitzky-Golay filter applied (window 0: none), at the grid step
    ``step`` [s], on a uniform grid built by cubic splines unless ``uniform``; ``noise_limit``
    [m/s^2]: the acceleration noise that chose the window, ``output_noise`` [m/s^2] the noise RMS
    the window leaves (the channel's noise through the filter); ``gain`` [-]: a least-squares scale
    applied; ``recorded_unused``: a recorded channel of the same name is set aside; ``dequantised``:
    encoder count steps filtered out; ``noise``: the channel's noise RMS where it was smoothed
    for being noisy."""

    source: str = ""
    derivative: int = 0
    window: int = 0
    order: int = 3
    step: float = 0.0
    uniform: bool = True
    noise_limit: float | None = None
    gain: float | None = None
    recorded_unused: bool = False
    dequantised: bool = False
    noise: float | None = None
    output_noise: float | None = None


@dataclass
class Motion:
    """Feed motion at the samples: x [m], v [m/s], a [m/s^2]; ``standstill`` marks samples whose
    direction is ambiguous (|v| <= ``standstill_speed`` [m/s], widened by the neighbours whose
    position stays within ``rest_band`` [m] of the rest where the position is recorded, else
    None), ``ends`` those within half a filter window of the record's ends, where the
    acceleration is extrapolated; ``how`` says how each signal was obtained."""

    time: np.ndarray
    x: np.ndarray
    v: np.ndarray
    a: np.ndarray
    standstill: np.ndarray
    reversals: np.ndarray  # sample indices where the direction of motion changes
    how: dict[str, Derivation]
    ends: np.ndarray
    standstill_speed: float
    rest_band: float | None
    unresolved: np.ndarray  # samples whose acceleration the filter cannot resolve

    def path(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(time [s], position [m], velocity [m/s], acceleration [m/s^2], indices of the samples
        in it): the motion on a path dense enough for laws that follow it (Dahl states, the
        running distance) and for a replay of it. Where a gap between samples exceeds GAP
        nominal steps (a dropout, a bursty record), points at the nominal step are inserted,
        position and velocity by cubic Hermite interpolation of the samples' position and
        velocity, so that a reversal inside the gap is travelled (the acceleration linearly);
        else the path is the samples."""
        step = sampling_step(self.time)
        gaps = np.flatnonzero(np.diff(self.time) > GAP * step)
        if gaps.size == 0:
            return self.time, self.x, self.v, self.a, np.arange(self.time.size)
        times, first = np.unique(self.time, return_index=True)
        inserted = [np.linspace(self.time[i], self.time[i + 1],
                                int(np.ceil((self.time[i + 1] - self.time[i]) / step)) + 1)[1:-1]
                    for i in gaps]
        fine = np.union1d(times, np.concatenate(inserted))
        spline = CubicHermiteSpline(times, self.x[first], self.v[first])
        return (fine, spline(fine), spline(fine, 1), np.interp(fine, times, self.a[first]),
                np.searchsorted(fine, self.time))

    def since_reversal(self) -> tuple[np.ndarray, np.ndarray]:
        """Time [s] and displacement [m] since the last reversal (since the start before the first)."""
        last = np.zeros(self.time.size, dtype=int)
        last[self.reversals] = self.reversals
        last = np.maximum.accumulate(last)
        return self.time - self.time[last], np.abs(self.x - self.x[last])


def sampling_step(time) -> float:
    """The record's nominal sampling interval [s]: the median interval, or the mean where the
    median is under half of it (bursty timestamps: clusters of samples a fraction of a
    microsecond apart and gaps between them)."""
    intervals = np.diff(time)
    median, mean = float(np.median(intervals)), float(np.mean(intervals))
    return median if median >= 0.5 * mean else mean


class _Grid:
    """Savitzky-Golay derivatives on a uniform grid at the :func:`sampling_step` of ``time``,
    carried to the instants ``at`` (``time`` less a delay). Samples closer than CLUSTER steps
    are averaged into one before the cubic spline carries an uneven record onto the grid: a
    spline through near-coincident, quantised samples would ring."""

    def __init__(self, time, window, delay=0.0):
        self.time = time
        self.at = time - delay if delay else time  # where the outputs are wanted
        intervals = np.diff(time)
        self.step = sampling_step(time)
        self.uniform = np.ptp(intervals) <= 1e-6 * self.step
        self.grid = time if self.uniform else np.arange(time[0], time[-1] + 0.5 * self.step, self.step)
        self.longest = int(self.grid.size - (1 - self.grid.size % 2))  # odd, within the grid
        self.window = min(int(window), self.longest)
        # cluster index of every sample: a new cluster where the gap reaches CLUSTER steps
        self.cluster = np.r_[0, np.cumsum(intervals >= CLUSTER * self.step)]

    def on_grid(self, y):
        """``y`` at the grid times (cubic-spline interpolation of an uneven record, through the
        means of its clusters)."""
        if self.uniform:
            return y
        count = np.bincount(self.cluster)
        t = np.bincount(self.cluster, self.time) / count
        v = np.bincount(self.cluster, np.asarray(y, dtype=float)) / count
        return CubicSpline(t, v)(self.grid)

    def filter(self, y, deriv=0, window=None, order=3):
        window = self.window if window is None else min(window, self.longest)
        out = savgol_filter(self.on_grid(y), window, order, deriv=deriv, delta=self.step,
                            mode="interp")
        return self.back(out)

    def back(self, on_grid):
        """Values on the grid carried to the output instants ``at`` (cubic spline)."""
        if self.uniform and self.at is self.time:
            return on_grid
        return CubicSpline(self.grid, on_grid)(self.at)

    def values(self, y):
        """A channel at the output instants, unfiltered."""
        return np.asarray(y, dtype=float) if self.at is self.time else self.back(self.on_grid(y))

    def ends(self, window):
        """The samples within half a ``window`` [samples] of either end (fewer than window // 2
        steps in), where a filter extrapolates its polynomial."""
        reach = (window // 2 - 0.5) * self.step
        return (self.time < self.time[0] + reach) | (self.time > self.time[-1] - reach)

    def derivation(self, source="", derivative=0, window=None, order=3, **details) -> Derivation:
        """The :class:`Derivation` of :meth:`filter` with these arguments."""
        window = self.window if window is None else min(window, self.longest)
        return Derivation(source, derivative, window, order, self.step, self.uniform, **details)


def _window(time, velocity_like) -> int:
    """Odd window [samples]: about 1/40 of the median samples between sign changes, 5..51, and
    short enough that the cubic filter's cutoff, about 4 / (3.2 M - 4.6) of the Nyquist frequency
    for 2 M + 1 samples (Schafer 2011), lies 3x above the highest frequency standing 30x above
    the median of the velocity's spectrum (numerics.spectrum without a window, over the sample
    index as the filter sees the samples; only where it stands above its median matters)."""
    signs = np.sign(velocity_like)
    moving = np.flatnonzero(signs != 0)
    changes = moving[1:][signs[moving[1:]] != signs[moving[:-1]]]
    per_stroke = np.median(np.diff(changes)) if changes.size > 2 else time.size
    _, amplitude = spectrum(np.arange(velocity_like.size), velocity_like, window="rectangular")
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


def _acceleration_from(grid: _Grid, channel, derivative, sigma, tolerance, per_stroke) -> tuple:
    """(acceleration [m/s^2], window [samples], ends [bool mask], its noise RMS [m/s^2], the
    samples it does not resolve [bool mask, :func:`_unresolved`]): the
    ``derivative``-th derivative (2 of a position [m], 1 of a velocity [m/s]) of ``channel`` by
    the ORDER filter over the shortest odd window whose output noise, the channel's noise
    ``sigma`` times the norm of the filter's coefficients, is at most ``tolerance`` [m/s^2]
    (the least bias the noise allows; at least NEGLIGIBLE of the acceleration's range, which
    matters where the force is noise-free), over at most a quarter of ``per_stroke``, the median
    samples between reversals, and at most LONGEST samples. ``sigma`` 0: the noise of the
    channel's fourth differences on the grid (a smooth motion's curvature hardly shows in them).

    Where that window is biased (a ramp shorter than it), a shorter one takes over, sample by
    sample, by the intersection of confidence intervals (Katkovnik's ICI rule): the longest of
    the windows up to it whose interval, the estimate +- CONFIDENCE times its noise, still
    meets those of all shorter windows. The noise RMS returned is over the samples."""
    on_grid = grid.on_grid(channel)
    longest = min(grid.longest, LONGEST, max(2 * int(per_stroke // 8) + 1, ORDER + 2))
    sigma = sigma or noise_rms(on_grid, order=4)
    smooth = savgol_filter(on_grid, longest, ORDER, deriv=derivative, delta=grid.step,
                           mode="interp")
    allowed = max(tolerance, NEGLIGIBLE * float(np.ptp(smooth)))

    def noise(w):
        return sigma * float(np.linalg.norm(savgol_coeffs(w, ORDER, deriv=derivative,
                                                          delta=grid.step)))

    window = next((w for w in range(ORDER + 2, longest, 2) if noise(w) <= allowed), longest)
    windows = np.unique(2 * (np.geomspace(ORDER + 2, window, 8) // 2).astype(int) + 1)
    low = np.full(grid.at.size, -np.inf)
    high = np.full(grid.at.size, np.inf)
    a = np.empty(grid.at.size)
    spread = np.empty(grid.at.size)
    consistent = np.ones(grid.at.size, dtype=bool)
    for w in windows:
        estimate = grid.filter(channel, deriv=derivative, window=int(w), order=ORDER)
        sigma_w = noise(w)
        low = np.maximum(low, estimate - CONFIDENCE * sigma_w)
        high = np.minimum(high, estimate + CONFIDENCE * sigma_w)
        consistent &= low <= high
        a[consistent] = estimate[consistent]
        spread[consistent] = sigma_w
    # within half a window of the ends the filter extrapolates its polynomial, which at ORDER
    # amplifies the noise many times: the cubic fit over the same window takes over there (still
    # an extrapolation: the ends are marked)
    ends = grid.ends(window)
    a[ends] = grid.filter(channel, deriv=derivative, window=window)[ends]
    return (a, window, ends, float(np.sqrt(np.mean(spread[~ends] ** 2))),
            _unresolved(grid, on_grid, window, sigma))


def _unresolved(grid: _Grid, on_grid, window, sigma) -> np.ndarray:
    """Samples [bool] whose ``window`` [samples] of ``on_grid`` (a channel on the grid, of noise
    RMS ``sigma``) departs from its ORDER polynomial by more than the noise: lack-of-fit test,
    the residual sum of squares over sigma^2 against chi^2 of window - ORDER - 1 degrees of
    freedom at LACK_OF_FIT. A motion whose acceleration has a corner (a ramp of cosine blends,
    a jerk step) is not locally polynomial there, and no window of the filter resolves it: on
    strokes with 36-sample blends every window from 9 samples up errs at the corners by about a
    tenth of the peak acceleration, many times a drive's force noise once times its mass. On an
    uneven record the grid holds a spline's values, not measurements of known noise: no sample
    is marked there."""
    if sigma <= 0.0 or on_grid.size < window or not grid.uniform:
        return np.zeros(grid.at.size, dtype=bool)
    flagged = np.zeros(on_grid.size, dtype=bool)
    half = window // 2
    basis = np.vander((np.arange(window) - half) / half, ORDER + 1, increasing=True)
    maker = np.eye(window) - basis @ np.linalg.pinv(basis)  # residuals of the polynomial fit
    windows = np.lib.stride_tricks.sliding_window_view(on_grid, window)  # a view: no copy
    squares = np.empty(windows.shape[0])
    for start in range(0, windows.shape[0], CHUNK):  # CHUNK windows at a time: all of them,
        part = windows[start:start + CHUNK]  # 1e6 x 101 samples, would take 0.8 GB a copy
        part = part - part[:, half:half + 1]  # the excursion: a position's size would
        squares[start:start + CHUNK] = np.sum((part @ maker) * part, axis=1)  # swamp eps x^2
    squares /= sigma ** 2
    flagged[half:on_grid.size - half] = squares > chi2.ppf(1.0 - LACK_OF_FIT, window - ORDER - 1)
    return np.interp(grid.at, grid.grid, flagged.astype(float)) > 0.0


def derive_motion(time, columns: dict, acceleration_noise: float | None,
                  delay: float = 0.0) -> Motion:
    """Motion from the measured ``feed_position`` / ``feed_velocity`` / ``feed_acceleration``;
    ``acceleration_noise`` [m/s^2]: the noise RMS the acceleration may carry where it is derived
    from the position (None: the model sets no limit; the acceleration then comes as without
    the position, or from the position by the cubic filter, scaled by its gain). ``delay`` [s]:
    the motion is wanted that long before each sample (a channel recorded behind the motion):
    the derived signals are carried there by cubic splines from the grid, the smooth motion, not
    the switching force, being interpolated across a bursty record's gaps."""
    time = np.asarray(time, dtype=float)
    how = {}
    if "feed_velocity" in columns:
        rough = columns["feed_velocity"]
    else:
        rough = np.gradient(columns["feed_position"], time)
    coarse = _Grid(time, max(5, 2 * (time.size // 400) + 1)).filter(rough)
    grid = _Grid(time, _window(time, coarse), delay)

    def measured(name):
        y = columns[name]
        if channel_noise(y) > NOISY * max(np.ptp(y), 1e-300):
            how[name] = grid.derivation()
            return grid.filter(y)
        how[name] = Derivation()
        return grid.values(y)

    if "feed_velocity" in columns:
        v = measured("feed_velocity")
    else:
        v = grid.filter(columns["feed_position"], deriv=1)
        how["feed_velocity"] = grid.derivation("feed_position", 1)
    if "feed_position" in columns:
        x = measured("feed_position")
    else:
        x = cumulative_trapezoid(v, time, initial=0.0)
        how["feed_position"] = Derivation("feed_velocity", -1)
    limit = STANDSTILL * np.max(np.abs(v))
    rounding = rounding_noise(columns["feed_position"]) if "feed_position" in columns else 0.0
    band = None
    if "feed_position" in columns:  # rests are told by the position: the velocity's noise decides
        limit = min(limit, AMBIGUOUS * max(channel_noise(rough), SIGN_WIDTH * np.max(np.abs(v))))
        band = _resolution(columns["feed_position"], rounding)
        standstill = _at_rest(x, np.abs(v) <= limit, band)
    else:
        standstill = np.abs(v) <= limit
    moving = np.flatnonzero(~standstill)
    signs = np.sign(v[moving])
    reversals = moving[1:][signs[1:] != signs[:-1]]
    per_stroke = np.median(np.diff(reversals)) if reversals.size > 2 else time.size
    if "feed_position" in columns and acceleration_noise is not None:
        a, window, ends, noise, unresolved = _acceleration_from(
            grid, columns["feed_position"], 2, rounding, acceleration_noise, per_stroke)
        if rounding > 0.0:  # encoder counts: de-quantised
            x = grid.filter(columns["feed_position"], window=window, order=ORDER)
            how["feed_position"] = grid.derivation(window=window, order=ORDER, dequantised=True)
        how["feed_acceleration"] = grid.derivation(
            "feed_position", 2, window, ORDER, noise_limit=acceleration_noise,
            output_noise=noise, recorded_unused="feed_acceleration" in columns)
    elif ("feed_velocity" in columns and "feed_acceleration" not in columns
          and acceleration_noise is not None):  # the velocity's noise limits the window alike
        raw = columns["feed_velocity"]
        a, window, ends, noise, unresolved = _acceleration_from(
            grid, raw, 1, channel_noise(raw), acceleration_noise, per_stroke)
        how["feed_acceleration"] = grid.derivation("feed_velocity", 1, window, ORDER,
                                                   noise_limit=acceleration_noise,
                                                   output_noise=noise)
    else:
        ends, unresolved = grid.ends(grid.window), np.zeros(time.size, dtype=bool)
        if "feed_acceleration" in columns:
            a = measured("feed_acceleration")
        elif "feed_velocity" in columns:  # the derivative of the velocity as measured (or
            raw = columns["feed_velocity"]  # smoothed) at the samples, not of v moved by delay
            here = _Grid(time, grid.window).filter(raw) if how["feed_velocity"].window else raw
            a = grid.filter(here, deriv=1)
            how["feed_acceleration"] = grid.derivation("feed_velocity", 1)
        else:
            a = grid.filter(columns["feed_position"], deriv=2)
            how["feed_acceleration"] = grid.derivation("feed_position", 2)
        gain = _acceleration_gain(grid, columns, a)
        a = gain * a
        how["feed_acceleration"] = replace(how["feed_acceleration"], gain=gain)
    return Motion(time, x, v, a, standstill, reversals, how, ends, float(limit), band,
                  unresolved)
