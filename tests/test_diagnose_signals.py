"""Noise estimates of measured channels (diagnose/signals.py) against hand calculations."""
from __future__ import annotations

import numpy as np
import pytest

from guideway_fmu.diagnose.signals import channel_noise, derive_motion, noise_rms


def test_channel_noise_of_encoder_counts_is_the_rounding_noise_by_hand():
    # a slow ramp read with a 1 um encoder: second differences are mostly 0 (MAD 0), the
    # rounding error is uniform over one count: q / sqrt(12)
    t = np.linspace(0.0, 1.0, 4001)
    counts = np.round(4e-4 * t / 1e-6) * 1e-6  # a tenth of a count per sample
    assert noise_rms(counts) == 0.0
    assert channel_noise(counts) == pytest.approx(1e-6 / np.sqrt(12.0), rel=1e-9)


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


def test_quantised_acceleration_channel_is_smoothed_and_says_so():
    t = np.arange(4000) * 1e-3
    x = np.round(0.02 * np.sin(2 * np.pi * 0.5 * t) / 1e-6) * 1e-6
    v = (x[2:] - x[:-2]) / 2e-3
    a = (x[2:] - 2 * x[1:-1] + x[:-2]) / 1e-6
    motion = derive_motion(t[1:-1], {"feed_position": x[1:-1], "feed_velocity": v,
                                     "feed_acceleration": a})
    assert motion.how["feed_acceleration"].startswith("measured, smoothed")
    truth = -(2 * np.pi * 0.5) ** 2 * 0.02 * np.sin(2 * np.pi * 0.5 * t[1:-1])
    inner = slice(50, -50)
    assert np.sqrt(np.mean((motion.a - truth)[inner] ** 2)) < 0.2 * np.sqrt(np.mean((a - truth)[inner] ** 2))


def test_acceleration_gain_undoes_the_attenuation_of_short_ramps_against_true_motion():
    # seed 7006: jogs with ramps of about 10 ms; the rig's double centred difference over +-3
    # samples lowers those pulses: least squares scales the recorded channel by more than 1.05
    from guideway_fmu.diagnose import truth

    run = truth.simulate("none", np.random.default_rng(7006), noise=0.015, n_samples=4000)
    true, moving = run.truth["acceleration"], run.truth["moving"]

    def gain(a):
        return np.dot(true[moving], a[moving]) / np.dot(a[moving], a[moving])

    before = gain(run.columns["feed_acceleration"]) - 1.0
    assert before > 0.05
    motion = derive_motion(run.columns["time"], {c: run.columns[c] for c in
                                                 ("feed_position", "feed_velocity",
                                                  "feed_acceleration")})
    after = gain(motion.a) - 1.0  # what remains: the short filter's own bias on 10 ms ramps
    assert abs(after) < 0.03 and abs(after) < before / 3
    assert "scaled by" in motion.how["feed_acceleration"]
