"""Noise estimates of measured channels (diagnose/signals.py) against hand calculations."""
from __future__ import annotations

import tempfile

import numpy as np
import pytest
from scipy.signal import savgol_coeffs, savgol_filter

from guideway_fmu.diagnose import signals
from guideway_fmu.diagnose.signals import (ORDER, Derivation, channel_noise, derive_motion,
                                           noise_rms, rounding_noise, smooth_channel)


def test_channel_noise_of_encoder_counts_is_the_rounding_noise_by_hand():
    # a slow ramp read with a 1 um encoder: second differences are mostly 0 (MAD 0), the
    # rounding error is uniform over one count: q / sqrt(12)
    t = np.linspace(0.0, 1.0, 4001)
    counts = np.round(4e-4 * t / 1e-6) * 1e-6  # a tenth of a count per sample
    assert noise_rms(counts) == 0.0
    assert channel_noise(counts) == pytest.approx(1e-6 / np.sqrt(12.0), rel=1e-9)


def test_rounding_noise_of_a_fast_encoder_never_moving_one_count_per_sample_by_hand():
    # a feed at 8-72 counts of 0.2 um per sample: consecutive steps are never one count, but
    # the positions still lie on the count lattice, q / sqrt(12); a smooth unrounded channel
    # has none
    t = np.linspace(0.0, 2.0, 4001)
    x = 0.002 * np.sin(2 * np.pi * t) + 0.016 * t
    counts = np.round(x / 2e-7) * 2e-7
    assert np.min(np.abs(np.diff(counts))) >= 8 * 2e-7 * (1 - 1e-9)
    assert rounding_noise(counts) == pytest.approx(2e-7 / np.sqrt(12.0), rel=1e-6)
    assert rounding_noise(x) == 0.0


def test_channel_noise_of_a_difference_of_counts_uses_its_own_lattice_by_hand():
    # acceleration as a centred difference of counts over +-3 samples at 1 ms: lattice 1 um / 9 ms^2
    rng = np.random.default_rng(3)
    counts = np.cumsum(rng.integers(-2, 3, 3000)) * 1e-6
    acc = (counts[6:] - 2 * counts[3:-3] + counts[:-6]) / (3e-3) ** 2
    q = 1e-6 / 9e-6
    assert channel_noise(acc) >= q / np.sqrt(12.0) * (1 - 1e-9)


def test_channel_noise_of_white_noise_is_its_rms():
    y = np.random.default_rng(4).normal(0.0, 0.2, 20000)
    assert channel_noise(y) == pytest.approx(0.2, rel=0.05)


def test_quantised_acceleration_channel_without_position_is_smoothed_and_says_so():
    t = np.arange(4000) * 1e-3
    x = np.round(0.02 * np.sin(2 * np.pi * 0.5 * t) / 1e-6) * 1e-6
    v = (x[2:] - x[:-2]) / 2e-3
    a = (x[2:] - 2 * x[1:-1] + x[:-2]) / 1e-6
    motion = derive_motion(t[1:-1], {"feed_velocity": v, "feed_acceleration": a}, None)
    how = motion.how["feed_acceleration"]
    assert how.source == "" and how.derivative == 0 and how.window >= 5  # measured, smoothed
    truth = -(2 * np.pi * 0.5) ** 2 * 0.02 * np.sin(2 * np.pi * 0.5 * t[1:-1])
    inner = slice(50, -50)
    assert np.sqrt(np.mean((motion.a - truth)[inner] ** 2)) < 0.2 * np.sqrt(np.mean((a - truth)[inner] ** 2))


def _sine_counts(step):
    # 0.37 Hz: not a whole number of periods, so the rounding error does not repeat
    t = np.arange(4000) * 1e-3
    w = 2 * np.pi * 0.37
    x = 0.02 * np.sin(w * t)
    return t, (np.round(x / step) * step if step else x), -w ** 2 * 0.02 * np.sin(w * t)


def test_acceleration_window_is_the_shortest_within_the_noise_tolerance_by_hand():
    # a 1 um encoder: rounding noise q / sqrt(12) through the order-7 second-derivative filter
    # of w samples has the RMS q / sqrt(12) |h_w|; the window is the shortest that keeps it
    # within the tolerance
    t, x, truth = _sine_counts(1e-6)
    tolerance = 0.01  # m/s^2
    motion = derive_motion(t, {"feed_position": x}, tolerance)
    how = motion.how["feed_acceleration"]
    assert (how.source, how.derivative, how.order, how.noise_limit) == ("feed_position", 2, ORDER,
                                                                        tolerance)
    window = how.window
    noise = [1e-6 / np.sqrt(12.0) * np.linalg.norm(savgol_coeffs(w, ORDER, deriv=2, delta=1e-3))
             for w in (window - 2, window)]
    assert noise[1] <= tolerance < noise[0]
    assert motion.ends.sum() == 2 * (window // 2)  # extrapolated there: marked
    inner = slice(window, -window)
    assert np.sqrt(np.mean((motion.a - truth)[inner] ** 2)) < 1.5 * tolerance


def test_acceleration_of_an_exact_position_takes_the_shortest_window_limiting_case():
    # no rounding, no noise: no smoothing is needed, the shortest window of order 7 is exact to
    # the sine's Taylor remainder
    t, x, truth = _sine_counts(0.0)
    motion = derive_motion(t, {"feed_position": x}, 1e-3)
    how = motion.how["feed_acceleration"]
    assert (how.order, how.window) == (ORDER, ORDER + 2)
    error = np.abs(motion.a - truth) / np.max(np.abs(truth))
    assert np.max(error[ORDER:-ORDER]) < 1e-6  # the cubic fit at the ends: within 1e-4 there
    assert np.max(error) < 1e-4


def test_acceleration_from_position_beats_the_rigs_channel_against_true_motion():
    # seed 1003, jittered time stamps, 0.5 % force noise: the rig's double centred difference
    # over +-3 samples lowers the ramps; the order-7 derivative of the counts, at the window the
    # workflow's tolerance gives, errs by less than half as much
    from guideway_fmu.diagnose import decide
    from guideway_synthetic import truth
    from guideway_fmu.diagnose.run_io import load_run

    run = truth.simulate("none", np.random.default_rng(1003), noise=0.005, uneven=True,
                         n_samples=4000)
    true, moving = run.truth["acceleration"], run.truth["moving"]
    with tempfile.TemporaryDirectory() as folder:
        truth.write_run(f"{folder}/run", run)
        motion = decide.motion_of(load_run(f"{folder}/run"))

    def rms(a):
        return np.sqrt(np.mean((a - true)[moving] ** 2))

    assert rms(motion.a) < 0.5 * rms(run.columns["feed_acceleration"])
    assert motion.how["feed_acceleration"].recorded_unused


def test_acceleration_gain_undoes_the_attenuation_of_short_ramps_against_true_motion():
    # seed 7066: jogs with ramps of about 10 ms; the rig's double centred difference over +-3
    # samples lowers those pulses by 9 %. Without the position the gain refers to a short
    # derivative of the velocity channel, itself a centred difference, so it undoes only part;
    # with the position but no tolerance, to the position's short second derivative
    from guideway_synthetic import truth

    run = truth.simulate("none", np.random.default_rng(7066), noise=0.015, n_samples=4000)
    true, moving = run.truth["acceleration"], run.truth["moving"]

    def gain(a):
        return np.dot(true[moving], a[moving]) / np.dot(a[moving], a[moving])

    before = gain(run.columns["feed_acceleration"]) - 1.0
    assert before > 0.05
    motion = derive_motion(run.columns["time"], {c: run.columns[c] for c in
                                                 ("feed_velocity", "feed_acceleration")}, None)
    assert abs(gain(motion.a) - 1.0) < 0.7 * before
    assert motion.how["feed_acceleration"].gain > 1.0
    motion = derive_motion(run.columns["time"], {c: run.columns[c] for c in
                                                 ("feed_position", "feed_velocity",
                                                  "feed_acceleration")}, None)
    assert abs(gain(motion.a) - 1.0) < min(0.03, before / 3)
    assert motion.how["feed_acceleration"].gain > 1.0


def test_dequantised_counts_lie_closer_to_the_true_position_than_the_counts():
    # seed 1000, 1 um encoder: the counts err by the rounding noise q / sqrt(12) = 0.29 um; the
    # order-7 filter at the acceleration's window takes most of it out (measured 0.11 um)
    from guideway_fmu.diagnose import decide
    from guideway_synthetic import truth
    from guideway_fmu.diagnose.run_io import load_run

    run = truth.simulate("none", np.random.default_rng(1000), noise=0.005, n_samples=4000)
    with tempfile.TemporaryDirectory() as folder:
        truth.write_run(f"{folder}/run", run)
        motion = decide.motion_of(load_run(f"{folder}/run"))
    inner, true = ~motion.ends, run.truth["position"]

    def rms(x):
        return np.sqrt(np.mean((x - true)[inner] ** 2))

    assert rms(run.columns["feed_position"]) == pytest.approx(1e-6 / np.sqrt(12.0), rel=0.05)
    assert rms(motion.x) < 0.5 * 1e-6 / np.sqrt(12.0)
    assert motion.how["feed_position"].dequantised


def test_rest_is_where_the_encoder_has_not_moved_and_slow_motion_is_not_by_hand():
    # a 10 mm move from rest to rest in 0.2 s read by a 1 um encoder, the velocity differenced
    # over +-3 samples as rigs do. The direction is clear above 3 times that velocity's rounding
    # noise, (1 um / 6 ms) / sqrt(12), or the regularised sign's width, 1e-3 of the top speed
    # (here the larger), by hand; but the differenced velocity rises 3 samples before
    # the first count and falls 3 after the last, where the carriage still rests (the count has
    # not changed): those samples are at rest, and every sample off the rests above the noise
    # limit is moving, also those slower than 1 % of the top speed
    t = np.arange(2000) * 1e-3
    phase = np.clip((t - 0.5) / 0.2, 0.0, 1.0)
    counts = np.round(1e-2 * (phase - np.sin(2 * np.pi * phase) / (2 * np.pi)) / 1e-6) * 1e-6
    v = np.zeros_like(t)
    v[3:-3] = (counts[6:] - counts[:-6]) / 6e-3
    motion = derive_motion(t, {"feed_position": counts, "feed_velocity": v}, None)
    noise_limit = 3.0 * max(1e-6 / 6e-3 / np.sqrt(12.0), 1e-3 * np.max(np.abs(motion.v)))
    assert noise_limit > 3.0 * 1e-6 / 6e-3 / np.sqrt(12.0)
    assert motion.standstill_speed == pytest.approx(noise_limit, rel=1e-9)
    assert motion.rest_band == pytest.approx(5e-7, rel=1e-9)
    home = (counts == 0.0) | (counts == counts[-1])
    assert np.any(home & (np.abs(motion.v) > noise_limit))  # the velocity alone: moving
    first, last = np.flatnonzero(~home)[[0, -1]]
    assert np.all(motion.standstill[:first]) and np.all(motion.standstill[last + 1:])
    clear = ~home & (np.abs(motion.v) > noise_limit)
    assert not np.any(motion.standstill[clear])
    slow = clear & (np.abs(motion.v) < 0.01 * np.max(np.abs(motion.v)))
    assert slow.sum() >= 4


@pytest.mark.parametrize("frequency, share", [(0.2, 0.1), (40.0, 0.6)])
def test_smoothed_load_channel_keeps_its_signal_and_sheds_its_noise_against_truth(frequency, share):
    # a load varying at 0.2 Hz (the longest window fits) or at 40 Hz (a 33-sample window would
    # take most of the signal: the discrepancy principle must stop short of it), white noise of
    # 5 N; the error against the noise-free load must stay below ``share`` of the noise
    t = np.arange(4000) * 1e-3
    load = 800.0 + 200.0 * np.sin(2 * np.pi * frequency * t)
    noisy = load + np.random.default_rng(2).normal(0.0, 5.0, t.size)
    smooth, how = smooth_channel(t, noisy)
    error = np.sqrt(np.mean((smooth - load)[300:-300] ** 2))
    assert error < share * 5.0
    assert how.window >= 5 and how.noise > 0.0  # smoothed for its noise


def test_noise_free_slow_load_channel_is_left_as_recorded_limiting_case():
    t = np.arange(4000) * 1e-3
    load = 800.0 + 200.0 * np.sin(2 * np.pi * 0.2 * t)
    kept, how = smooth_channel(t, load)
    assert np.array_equal(kept, load) and how == Derivation()  # measured, kept


@pytest.mark.parametrize("pole", [0.0, 0.95])
def test_incoherent_noise_is_the_rms_of_noise_of_any_colour_beside_a_state_coherent_error(pole):
    # known by construction: 40 sinusoidal strokes, a model error that is a function of the
    # state (x, v) ten times the noise, plus AR(1) noise of unit RMS (white at pole 0). The
    # state-matched estimate gives the noise's RMS; the white second-difference estimate sees
    # sqrt((1 - p)(3 - p) / 3) of it (0.19 at p = 0.95, hand value)
    from types import SimpleNamespace

    from scipy.signal import lfilter

    from guideway_fmu.diagnose import locate
    t = np.linspace(0.0, 40.0, 20001)
    w = 2 * np.pi
    x, v, a = np.sin(w * t), w * np.cos(w * t), -w**2 * np.sin(w * t)
    reversals = np.flatnonzero(np.diff(np.sign(v)) != 0) + 1
    motion = SimpleNamespace(time=t, x=x, v=v, a=a, reversals=reversals)
    noise = lfilter([1.0], [1.0, -pole], np.random.default_rng(3).standard_normal(t.size))
    noise = (noise - noise.mean()) / noise.std()
    residual = 10.0 * (x**2 * np.sign(v) + 0.3 * v / w) + noise
    mask = np.ones(t.size, dtype=bool)
    assert locate.incoherent_noise(motion, residual, mask) == pytest.approx(1.0, rel=0.1)
    white = np.sqrt((1 - pole) * (3 - pole) / 3)
    assert noise_rms(noise) == pytest.approx(white, rel=0.1)


def test_acceleration_from_a_noisy_velocity_takes_the_shortest_window_within_tolerance_by_hand():
    # a velocity-only record with white tacho noise s: the order-7 first-derivative filter of w
    # samples leaves s |h_w| of noise; the window is the shortest keeping that within the
    # tolerance, and the derivation reports it
    t = np.arange(4000) * 1e-3
    w = 2 * np.pi * 0.37
    s = 1e-4
    v = 0.02 * w * np.cos(w * t) + s * np.random.default_rng(5).standard_normal(t.size)
    tolerance = 0.02  # m/s^2
    motion = derive_motion(t, {"feed_velocity": v}, tolerance)
    how = motion.how["feed_acceleration"]
    assert (how.source, how.derivative, how.order, how.noise_limit) == ("feed_velocity", 1, ORDER,
                                                                        tolerance)
    noise = [s * np.linalg.norm(savgol_coeffs(n, ORDER, deriv=1, delta=1e-3))
             for n in (how.window - 2, how.window)]
    assert noise[1] <= 1.05 * tolerance and noise[0] > 0.95 * tolerance  # s estimated
    assert how.output_noise == pytest.approx(noise[1], rel=0.05)
    truth = -0.02 * w**2 * np.sin(w * t)
    inner = ~motion.ends
    assert motion.ends.sum() == 2 * (how.window // 2)
    error = np.sqrt(np.mean((motion.a - truth)[inner] ** 2))
    assert error == pytest.approx(how.output_noise, rel=0.15)  # noise, no bias on a slow sine


def test_ends_of_a_cubic_filtered_motion_are_marked_limiting_case():
    # a position-derived velocity at a record's last samples is the filter's extrapolated
    # polynomial: at a dwell it may have either sign. The half window at each end is marked
    t = np.arange(2000) * 1e-3
    x = np.round(1e-4 * np.clip(np.sin(2 * np.pi * 2 * t) * 1.3, -1, 1) / 1e-8) * 1e-8
    motion = derive_motion(t, {"feed_position": x}, None)
    half = motion.how["feed_velocity"].window // 2
    assert half >= 2
    assert motion.ends[:half].all() and motion.ends[-half:].all()
    assert not motion.ends[half:-half].any()


def test_acceleration_on_short_ramps_takes_shorter_windows_there_against_true_motion():
    # constant-speed strokes reversing through cosine blends of 12 samples (a triangular
    # profile), position noise 2 um RMS: the noise-limited window is longer than the blends
    # and would flatten their acceleration peaks; the ICI rule shortens it at the blends only
    t = np.arange(4000) * 1e-3
    period, blend, speed = 0.5, 0.012, 0.05
    # velocity: +speed, a cosine blend to -speed at period / 2, back at period
    def velocity(p):
        out = np.where(p < period / 2, speed, -speed)
        for centre, sign in ((period / 2, -1.0), (period, 1.0), (0.0, 1.0)):
            inside = np.abs(p - centre) < blend / 2
            out = np.where(inside, -sign * speed * np.cos(np.pi * (p - centre) / blend + np.pi / 2),
                           out)
        return out
    fine = np.arange(0.0, t[-1] + 1e-3, 1e-6)
    v_fine = velocity(np.mod(fine, period))
    x_fine = np.cumsum(v_fine) * 1e-6
    x = np.interp(t, fine, x_fine) + 2e-6 * np.random.default_rng(8).standard_normal(t.size)
    a_true = np.gradient(np.interp(t, fine, v_fine), t)
    tolerance = 0.05
    motion = derive_motion(t, {"feed_position": x}, tolerance)
    how = motion.how["feed_acceleration"]
    assert how.window > 12  # the noise-limited window spans more than a blend
    fixed = savgol_coeffs(how.window, ORDER, deriv=2, delta=1e-3)
    plain = savgol_filter(x, how.window, ORDER, deriv=2, delta=1e-3)
    inner = ~motion.ends
    at_blends = inner & (np.abs(a_true) > 0.5 * np.max(np.abs(a_true)))
    error = np.sqrt(np.mean((motion.a - a_true)[at_blends] ** 2))
    error_plain = np.sqrt(np.mean((plain - a_true)[at_blends] ** 2))
    assert error < 0.5 * error_plain
    # a window away from the blends, the long window's noise (false alarms of the rule are rare)
    near = np.convolve(np.abs(a_true) > 0, np.ones(2 * how.window + 1), mode="same") > 0
    cruise = inner & ~near
    assert np.sqrt(np.mean(motion.a[cruise] ** 2)) < 1.2 * 2e-6 * np.linalg.norm(fixed)


def test_unresolved_acceleration_is_marked_around_the_corners_of_cosine_blends_only_by_hand(
        cosine_blend_strokes):
    # strokes reversing through half-cosine blends (corners of the acceleration at both ends of
    # each blend, instants known by construction), encoder of 0.2 um: the lack-of-fit test
    # marks samples within the filter's half window of a corner, and none a window away
    t, x, _, _, corners = cosine_blend_strokes
    motion = derive_motion(t, {"feed_position": np.round(x / 2e-7) * 2e-7}, 1e-3)
    window = motion.how["feed_acceleration"].window
    distance = np.min(np.abs(t[:, None] - corners[None, :]), axis=1) / (t[1] - t[0])
    inner = ~motion.ends
    assert np.all(distance[inner & motion.unresolved] <= window // 2 + 1)
    assert not np.any(motion.unresolved[inner & (distance > window)])
    # every corner inside the record is seen
    assert all(motion.unresolved[np.argmin(np.abs(t - c))] for c in corners
               if window < c / (t[1] - t[0]) < t.size - window)


def test_smooth_motion_half_a_metre_out_on_a_10_nm_encoder_is_resolved_everywhere_limiting_case():
    # the lack-of-fit test's residuals are of the excursion within each window, not of the
    # position: eps x^2 at x = 0.5 m is about 30 times a 10 nm count's rounding variance, and a
    # quadratic form in the positions themselves marked half the samples
    t = np.arange(20000) * 5e-4
    x = 0.5 + 0.01 * np.sin(2 * np.pi * 0.5 * t)
    motion = derive_motion(t, {"feed_position": np.round(x / 1e-8) * 1e-8}, 1e-4)
    assert motion.how["feed_acceleration"].window > 2 * ORDER
    assert not motion.unresolved.any()


@pytest.mark.parametrize("sigma", [0.5, 2.0, 5.0])
def test_denoised_load_keeps_its_lines_and_drops_white_noise_between_them_hand_spectrum(sigma):
    """Two sines of 30 and 50 N under white noise of sigma: the noise's power an octave above
    them (2.5-3.5 kHz, where a resonance would ring) falls to under 5 % (spectral check,
    independent of the short-time transform), the lines stay within a quarter of the noise RMS,
    and the noise RMS is estimated within 5 %."""
    rng = np.random.default_rng(0)
    t = np.arange(20000) / 1e5
    clean = 1000 + 50 * np.sin(2 * np.pi * 731 * t + 0.3) + 30 * np.sin(2 * np.pi * 1212.7 * t)
    noise = sigma * rng.standard_normal(t.size)
    values, estimate, kept = signals.denoise_spectrum(t, clean + noise)
    f = np.fft.rfftfreq(t.size, 1e-5)
    band = (f > 2500) & (f < 3500)
    left = np.abs(np.fft.rfft(values - clean)[band]) ** 2
    assert left.sum() < 0.05 * (np.abs(np.fft.rfft(noise)[band]) ** 2).sum()
    assert np.std(values - clean) < 0.25 * sigma
    assert estimate == pytest.approx(sigma, rel=0.05)
    assert 0.0 < kept < 0.1


def test_denoising_white_noise_alone_leaves_its_mean_and_an_exact_channel_unchanged_limits():
    """Limiting cases: white noise on a constant leaves under a tenth of its RMS (only the
    slowest bins pass, the share of noise bins passing is e^-LINE); a channel without noise
    comes back as it is, noise 0 (on even instants: jittered ones make a sine look noisy)."""
    rng = np.random.default_rng(1)
    t = np.sort(np.arange(8000) / 5e4 + rng.uniform(-2e-6, 2e-6, 8000))  # jittered instants
    values, estimate, _ = signals.denoise_spectrum(t, 200.0 + 2.0 * rng.standard_normal(t.size))
    assert np.std(values - 200.0) < 0.1 * 2.0
    even = np.arange(8000) / 5e4
    exact = 200.0 + 30.0 * np.sin(2 * np.pi * 900.0 * even)
    values, estimate, kept = signals.denoise_spectrum(even, exact)
    assert np.array_equal(values, exact) and estimate == 0.0 and kept == 1.0


@pytest.mark.parametrize("samples", [10, 31])
def test_a_record_too_short_to_tell_lines_from_noise_is_returned_as_it_is_with_its_noise(samples):
    """Limiting case: under two 16-sample windows the channel comes back unchanged, its noise
    estimated (so the model's response to it still enters the floor), every bin kept."""
    rng = np.random.default_rng(2)
    t = np.arange(samples) / 1e4
    noisy = 100.0 + 10.0 * np.sin(3000.0 * t) + rng.standard_normal(samples)
    values, estimate, kept = signals.denoise_spectrum(t, noisy)
    assert np.array_equal(values, noisy) and estimate > 0.0 and kept == 1.0
