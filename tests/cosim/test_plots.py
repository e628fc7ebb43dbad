"""Spectra, envelopes and PNG output of cosim.plots, checked against signals known by hand."""
import numpy as np
import pytest

from guideway_fmu.cosim.recording import Recording
from guideway_fmu.numerics.spectrum import peak_indices, spectrum
from guideway_fmu.cosim.plots import (envelope, oscillates, plot_all, plot_defaults, plot_film,
                                      plot_spectra, plot_time)

FS = 20_000.0  # sampling rate [Hz]


def _peak(freq, amplitude, near):
    """(frequency, height) of the highest bin within 50 Hz of ``near`` [Hz]."""
    band = np.flatnonzero(np.abs(freq - near) <= 50)
    i = band[np.argmax(amplitude[band])]
    return freq[i], amplitude[i]


def test_spectrum_recovers_a_sum_of_sines():
    t = np.arange(4000) / FS  # 0.2 s, bins of 5 Hz
    x = 3.0 + 2.0 * np.sin(2 * np.pi * 150 * t) + 0.5 * np.cos(2 * np.pi * 3200 * t + 0.7)
    freq, amplitude = spectrum(t, x)
    assert freq[1] == pytest.approx(5.0) and freq[-1] == pytest.approx(FS / 2)
    for f, a in [(150, 2.0), (3200, 0.5)]:
        f_peak, a_peak = _peak(freq, amplitude, f)
        assert abs(f_peak - f) <= 5.0
        assert a_peak == pytest.approx(a, rel=0.02)
    assert amplitude[freq < 100].max() < 0.02  # mean (3.0) removed
    assert amplitude[(freq > 400) & (freq < 3000)].max() < 1e-3  # nothing between the sines


def test_skip_discards_the_transient():
    t = np.arange(6000) / FS  # 0.3 s
    transient = 5.0 * np.sin(2 * np.pi * 400 * t) * (t < 0.1)
    x = np.sin(2 * np.pi * 1000 * t) + transient
    freq, amplitude = spectrum(t, x, skip=0.1)
    assert freq[1] == pytest.approx(FS / 4000)  # 0.2 s left
    assert _peak(freq, amplitude, 1000)[1] == pytest.approx(1.0, rel=0.02)
    assert _peak(freq, amplitude, 400)[1] < 0.01
    freq, amplitude = spectrum(t, x)
    assert _peak(freq, amplitude, 400)[1] > 0.5


def test_peaks_are_the_highest_local_maxima():
    t = np.arange(4000) / FS
    x = 0.2 * np.sin(2 * np.pi * 500 * t) + np.sin(2 * np.pi * 2000 * t) + 0.5 * np.sin(2 * np.pi * 7000 * t)
    freq, amplitude = spectrum(t, x)
    assert freq[peak_indices(amplitude, 3)].tolist() == [2000.0, 7000.0, 500.0]


def test_spectrum_rejects_non_uniform_or_short_signals():
    t = np.arange(100) / FS
    t[50] += 0.3 / FS
    with pytest.raises(ValueError, match="uniform"):
        spectrum(t, np.sin(t))
    t = np.arange(20) / FS
    with pytest.raises(ValueError, match="at least 8 samples"):
        spectrum(t, np.sin(t), skip=15 / FS)


def test_envelope_follows_the_modulation():
    t = np.arange(10_000) / 1e5  # 0.1 s at 100 kHz
    modulation = 1.0 + 0.5 * np.cos(2 * np.pi * 10 * t)
    lower, upper = envelope(t, modulation * np.sin(2 * np.pi * 1000 * t), window=1e-3)
    inside = (t > 1e-3) & (t < t[-1] - 1e-3)  # edge windows are cut in half
    assert np.max(np.abs(upper - modulation)[inside]) < 0.03 * modulation.max()
    assert np.max(np.abs(lower + modulation)[inside]) < 0.03 * modulation.max()


def _recording(time):
    force = 1e3 * (1 + 0.2 * np.sin(2 * np.pi * 50 * time)) * np.sin(2 * np.pi * 2000 * time)
    return Recording(time, {"contact.F": force, "contact.h": 1e-6 * (1 + 0.1 * np.cos(2 * np.pi * 300 * time))},
                     {"contact.F": "N", "contact.h": "m"})


def _assert_png(path):
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000


def test_plot_all_writes_pngs(tmp_path):
    rec = _recording(np.arange(2000) / FS)
    plots = {"time": ["contact.F", "contact.h"], "spectrum": ["contact.F"], "film": ["contact.h"],
             "envelope": ["contact.F"]}
    paths = plot_all(rec, plots, tmp_path / "out", skip=0.01, f_max=5000, window=5e-4)
    assert [p.name for p in paths] == ["time.png", "spectrum.png", "film.png", "envelope.png"]
    for path in paths:
        _assert_png(path)


def test_spectrum_plot_resamples_a_non_uniform_recording(tmp_path):
    time = np.cumsum(np.r_[0.0, np.full(999, 1 / FS), np.full(1000, 0.5 / FS)])
    _assert_png(plot_spectra(_recording(time), ["contact.F"], tmp_path / "s.png"))


def test_film_needs_metres(tmp_path):
    with pytest.raises(ValueError, match="contact.F.*must be in m"):
        plot_film(_recording(np.arange(100) / FS), ["contact.F"], tmp_path / "f.png")


def test_unknown_name_raises_key_error_listing_the_columns(tmp_path):
    rec = _recording(np.arange(100) / FS)
    with pytest.raises(ValueError, match="contact.x.*available: contact.F, contact.h"):
        plot_time(rec, ["contact.F", "contact.x"], tmp_path / "t.png")
    with pytest.raises(ValueError, match="contact.x"):
        plot_all(rec, {"time": ["contact.F"], "film": ["contact.x"]}, tmp_path)
    assert not (tmp_path / "time.png").exists()  # checked before anything is written


def test_axis_labels_name_the_quantity_from_the_fmu_and_its_unit(fmu_dir):
    from guideway_fmu import scenarios
    from guideway_fmu.cosim import master, system
    from guideway_fmu.cosim.plots import axis_label
    scenario = system.load(scenarios.find("soleimanian2020_9000N_4500Hz"), fmu_dir)
    rec = master.simulate(scenario.with_changes(stop=1e-4)).recording
    assert axis_label(rec, "Contact.F_upper").replace("\n", " ") == "load of one roller in an upper groove [N]"
    assert axis_label(rec, "Contact.h_upper", "µm").endswith("[µm]")
    assert axis_label(_recording(np.linspace(0, 1, 9)), "contact.F") == "contact.F [N]"  # no description


def test_oscillates_tells_a_swinging_signal_from_a_constant_a_ramp_and_a_step():
    t = np.arange(2000) / FS
    assert oscillates(t, np.sin(2 * np.pi * 100 * t))  # 20 periods
    assert oscillates(t, 5.0 + 3.0 * t + 1e-3 * np.sin(2 * np.pi * 100 * t))  # about a trend
    assert not oscillates(t, np.full(t.size, 2.5))
    assert not oscillates(t, 3.0 * t - 1.0)
    assert not oscillates(t, np.where(t < 0.05, 0.0, 1.0))
    assert not oscillates(t, 1.0 + 1e-12 * np.sin(2 * np.pi * 100 * t))  # round-off only
    assert not oscillates(t, np.sin(2 * np.pi * 10 * t))  # two periods: too few crossings


def test_default_plots_draw_each_instance_and_spectra_of_what_oscillates(tmp_path):
    t = np.arange(400) / FS
    rec = Recording(t, {"Body.y": 1e-6 * np.sin(2 * np.pi * 500 * t),
                        "Body.F": np.full(t.size, 3.0), "Drive/1.u": 0.1 * t},
                    {"Body.y": "m", "Body.F": "N", "Drive/1.u": "m/s"})
    paths = plot_defaults(rec, tmp_path / "plots")
    assert [p.name for p in paths] == ["time_Body.png", "spectrum_Body.png", "time_Drive_1.png"]
    for p in paths:
        assert p.read_bytes()[:4] == b"\x89PNG"
