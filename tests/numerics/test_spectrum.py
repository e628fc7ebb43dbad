"""numerics.spectrum's options (zero padding, window) and the power spectrum against hand values.
(The default spectrum's sums of sines, skip and peaks: tests/cosim/test_plots.py.)"""
import numpy as np
import pytest

from guideway_fmu.numerics.spectrum import power_spectrum, spectrum

FS, N = 1000.0, 1000  # 1 s at 1 kHz: bins of 1 Hz
T = np.arange(N) / FS


@pytest.mark.parametrize("pad", [1, 4, 16])
@pytest.mark.parametrize("window, rel", [("hann", 1e-6), ("rectangular", 1e-12)])
def test_sine_at_a_bin_frequency_peaks_at_its_amplitude_with_and_without_padding_hand_value(
        pad, window, rel):
    # 2.5 sin(2 pi 50 t + 0.4) on an offset of 0.7: the peak is 2.5 at 50 Hz on every grid
    # (np.hanning is symmetric, periodic only to O(1/N): its mirror image leaks ~1e-7 here)
    f, amplitude = spectrum(T, 0.7 + 2.5 * np.sin(2 * np.pi * 50.0 * T + 0.4), pad=pad,
                            window=window)
    assert f[1] == pytest.approx(1.0 / pad)
    assert f[np.argmax(amplitude)] == pytest.approx(50.0)
    assert amplitude.max() == pytest.approx(2.5, rel=rel)


def test_padded_spectrum_holds_the_unpadded_one_on_every_padth_bin_limiting_case():
    x = np.sin(2 * np.pi * 33.3 * T) + 0.2 * np.cos(2 * np.pi * 210.7 * T)
    _, plain = spectrum(T, x)
    _, padded = spectrum(T, x, pad=8)
    np.testing.assert_allclose(padded[::8], plain, rtol=1e-9, atol=1e-12)


def test_power_spectrum_puts_half_the_squared_amplitude_in_the_bin_and_sums_to_the_variance():
    # Parseval: the bins sum to the variance, A^2 / 2 for a sine of amplitude A (hand value)
    x = 0.7 + 2.5 * np.sin(2 * np.pi * 50.0 * T + 0.4) + 0.5 * np.cos(2 * np.pi * 500.0 * T)
    f, power = power_spectrum(T, x)
    assert power[f == 50.0].item() == pytest.approx(2.5**2 / 2, rel=1e-12)
    assert power[f == 500.0].item() == pytest.approx(0.5**2, rel=1e-9)  # Nyquist: no mirror
    assert power.sum() == pytest.approx(np.var(x), rel=1e-12)


@pytest.mark.parametrize("options, message", [({"pad": 0}, "pad must be a whole number"),
                                              ({"pad": 1.5}, "pad must be a whole number"),
                                              ({"window": "hamming"}, "window must be one of")])
def test_bad_options_are_refused_naming_them(options, message):
    with pytest.raises(ValueError, match=message):
        spectrum(T, np.sin(T), **options)


def test_a_window_needs_its_fewest_samples_and_none_needs_two():
    t = np.arange(4) / FS
    with pytest.raises(ValueError, match="at least 8 samples"):
        spectrum(t, np.sin(t))
    f, amplitude = spectrum(t[:2], np.array([1.0, -1.0]), window="rectangular")
    assert amplitude.tolist() == pytest.approx([0.0, 1.0])  # a zigzag of amplitude 1 at Nyquist
    with pytest.raises(ValueError, match="at least 2 samples"):
        power_spectrum(t[:1], np.ones(1))
