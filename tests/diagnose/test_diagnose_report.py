"""The report's wording of how the motion was obtained (report.describe), case by case, against
the derivation the signals module returns."""
from __future__ import annotations

import numpy as np

from guideway_fmu.diagnose import report
from guideway_fmu.diagnose.signals import Derivation, derive_motion


def test_measured_channel_is_said_to_be_measured():
    assert report.describe("feed_velocity", Derivation()) == "measured"
    assert report.describe("normal_force", None) == "not recorded"


def test_derived_acceleration_names_source_filter_window_and_limit():
    d = Derivation("feed_position", 2, 9, 7, 1e-3, True, noise_limit=0.01, recorded_unused=True)
    text = report.describe("feed_acceleration", d)
    assert text.startswith("derived from feed_position: second derivative")
    assert "order 7, 9 samples (0.009 s)" in text and "within 0.01 m/s2 RMS" in text
    assert "the recorded feed_acceleration is not used" in text


def test_integrated_position_and_uneven_grid_are_said():
    assert report.describe("feed_position", Derivation("feed_velocity", -1)).startswith(
        "integrated from feed_velocity")
    text = report.describe("feed_velocity", Derivation("feed_position", 1, 11, 3, 2e-3, False))
    assert "first derivative" in text and "cubic, 11 samples" in text and "cubic splines" in text


def test_gain_and_dequantising_are_said():
    assert "scaled by 1.05" in report.describe("feed_acceleration", Derivation(gain=1.05))
    assert "count steps are taken out" in report.describe(
        "feed_position", Derivation(window=9, order=7, step=1e-3, dequantised=True))


def test_standstill_wording_follows_the_rest_band():
    assert "position lies within 5e-07 m" in report.describe_standstill(1e-3, 5e-7)
    assert report.describe_standstill(1e-3, None).startswith("|feed_velocity| <= 0.001 m/s (1% of")


def test_every_derivation_of_a_velocity_only_record_is_worded():
    t = np.arange(2000) * 1e-3
    motion = derive_motion(t, {"feed_velocity": np.sin(2 * np.pi * t)}, None)
    words = {name: report.describe(name, d) for name, d in motion.how.items()}
    assert set(words) == {"feed_velocity", "feed_position", "feed_acceleration"}
    assert words["feed_acceleration"].startswith("derived from feed_velocity")


def test_the_three_kinds_of_answer_are_said_apart():
    mass = [{"parameter": "moving_mass", "stated": 30.0, "fitted": 6.1, "interval": [5.9, 6.3]}]
    assert report.answer_kind({"missing_effect": "lubrication", "baseline_corrections": []}) == \
        "a missing effect"
    assert report.answer_kind({"missing_effect": "none", "baseline_corrections": []}) == \
        "no discrepancy beyond the noise"
    assert report.answer_kind({"missing_effect": "none", "baseline_corrections": mass}) == \
        "a baseline parameter is wrong"
    assert report.answer_kind({"missing_effect": "presliding_hysteresis",
                               "baseline_corrections": mass}) == (
        "a baseline parameter is wrong, and a missing effect after its correction")


def test_the_separating_experiment_is_said_with_both_predictions():
    experiment = {"between": ["preload_loss", "unmodeled_mass"], "record": "the rig under 920 N more",
                  "predictions": {"preload_loss": {"displacement_change": 2.0e-7,
                                                   "natural_frequency": 6000.0},
                                  "unmodeled_mass": {"displacement_change": 1.8e-7,
                                                     "natural_frequency": 6010.0}},
                  "displacement_apart_in_noise": 20.0, "frequency_apart": 10.0 / 6010.0}
    said = report.separating_words(experiment)
    assert said.startswith("record the rig under 920 N more")
    assert "preload_loss: displacement 0.2 um" in said and "6010 Hz" in said
    assert "0.166 % in frequency and 20 noise floors in displacement" in said
    assert report.separating_words(None) == "-"
