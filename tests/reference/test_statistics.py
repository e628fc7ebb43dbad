"""Statistics of a response (guideway_fmu.reference.statistics) against hand calculations."""
import numpy as np
import pytest

from guideway_fmu.reference import statistics


def test_cycle_envelope_of_an_amplitude_modulated_sine_is_the_modulation_at_its_crests():
    # x = (1 + 0.5 sin(2 pi fm t)) sin(2 pi fc t): by hand, cycle i of the carrier has its crest
    # at t = (i + 1/4) / fc and its trough at (i + 3/4) / fc, where |x| is the modulation there
    # (the modulation moves the crest by (fm / fc)^2 / 2 ~ 3e-4 of it, within the tolerance)
    fc, fm = 1000.0, 25.0
    t = np.arange(0.0, 10.5e-3, 1e-6)
    x = (1 + 0.5 * np.sin(2 * np.pi * fm * t)) * np.sin(2 * np.pi * fc * t)
    high, low = statistics.cycle_envelope(t, x, 1 / fc)
    i = np.arange(10)  # the half cycle at the end is left out
    assert high == pytest.approx(1 + 0.5 * np.sin(2 * np.pi * fm * (i + 0.25) / fc), abs=5e-4)
    assert low == pytest.approx(-(1 + 0.5 * np.sin(2 * np.pi * fm * (i + 0.75) / fc)), abs=5e-4)


def test_cycle_envelope_refuses_a_run_shorter_than_a_cycle():
    t = np.arange(0.0, 1e-3, 1e-5)
    with pytest.raises(ValueError, match="no complete cycle"):
        statistics.cycle_envelope(t, np.sin(t), 2e-3)


def test_spectral_peaks_of_two_sines_are_their_frequencies_and_amplitudes():
    # by hand: 3 sin(2 pi 1250 t) + sin(2 pi 4000 t), both on bins of 10 Hz (0.1 s), so the
    # Hann-windowed spectrum scaled to amplitudes peaks at 3 and 1 there
    t = np.arange(10000) * 1e-5
    x = 3 * np.sin(2 * np.pi * 1250 * t) + np.sin(2 * np.pi * 4000 * t)
    f, a = statistics.spectral_peaks(t, x, 2)
    assert f.tolist() == [1250.0, 4000.0]
    assert a == pytest.approx([3.0, 1.0], rel=1e-3)


def test_peaks_near_follows_a_peak_one_bin_away_but_not_five():
    # a sine one bin (10 Hz) above the asked 1250 Hz is found there, at its amplitude; one five
    # bins above is outside the search, whose highest bin then holds only the Hann leakage
    # (a few 1e-4 of the amplitude five bins away, by measurement)
    t = np.arange(10000) * 1e-5
    f, a = statistics.peaks_near(t, 2 * np.sin(2 * np.pi * 1260 * t), [1250.0])
    assert f.tolist() == [1260.0] and a[0] == pytest.approx(2.0, rel=1e-3)
    _, a = statistics.peaks_near(t, 2 * np.sin(2 * np.pi * 1300 * t), [1250.0])
    assert a[0] < 1e-3


def test_distribution_is_the_quantiles_by_hand():
    # 0, 1, ..., 100 in any order: the quantile p is 100 p; 1, 2, 3, 4: q25 lies 0.75 of the way
    # from the first to the second order statistic (position 0.25 x 3), 1.75
    values = np.random.default_rng(1).permutation(101).astype(float)
    assert statistics.distribution(values) == pytest.approx(
        {"q05": 5.0, "q25": 25.0, "q50": 50.0, "q75": 75.0, "q95": 95.0})
    assert statistics.distribution([4.0, 1.0, 3.0, 2.0])["q25"] == pytest.approx(1.75)


def test_load_statistics_of_a_steady_sine_by_hand():
    # 5 + 2 sin(2 pi 500 t) over whole cycles: every cycle peaks at 7 and dips to 3 (no
    # spread over cycles); the spectrum's peak is 2 at 500 Hz; the median is the mean, 5
    t = np.arange(20000) * 1e-6
    s = statistics.load_statistics(t, 5 + 2 * np.sin(2 * np.pi * 500 * t), 2e-3, [500.0])
    assert s["cycle_max_mean"] == pytest.approx(7.0, rel=1e-6)
    assert s["cycle_min_mean"] == pytest.approx(3.0, rel=1e-6)
    assert s["cycle_max_std"] == pytest.approx(0.0, abs=1e-6)
    assert s["peak1_frequency"] == 500.0 and s["peak1_amplitude"] == pytest.approx(2.0, rel=1e-3)
    assert s["q50"] == pytest.approx(5.0, abs=1e-3)
