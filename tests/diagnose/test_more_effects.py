"""Two effects at once (diagnose/more_effects.py): a named effect's extension over the baseline
by hand, and records hiding two effects from the second generator (guideway_synthetic/
second_truth.py, written independently of the candidates) named in turn, in diagnosis.json as
missing_effects."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from guideway_fmu.diagnose import decide, report
from guideway_fmu.diagnose.candidates import BASELINE, UnmodeledMass, extension, with_fixed
from guideway_synthetic import second_truth


@pytest.fixture(scope="module")
def mass_record(tmp_path_factory):
    folder = tmp_path_factory.mktemp("mass") / "run"
    second_truth.draw(folder, "unmodeled_mass", "drive", 64100, n_samples=4000)
    return decide.decide(folder)


def test_extension_of_an_added_mass_is_its_inertia_and_the_baseline_has_none_hand_calculation(
        mass_record):
    ctx, fit_mask = mass_record.ctx, mass_record.fit_mask
    fitted = UnmodeledMass().fit(ctx, fit_mask)
    # the mass candidate's columns are the Coulomb column and a: beyond the baseline's form
    # (level, offset) it adds extra_mass * a, exactly
    np.testing.assert_allclose(extension(ctx, fitted),
                               fitted.parameters["extra_mass"] * ctx.motion.a, rtol=0,
                               atol=1e-9 * np.ptp(ctx.y))
    np.testing.assert_allclose(extension(ctx, BASELINE.fit(ctx, fit_mask)), 0.0,
                               atol=1e-9 * np.ptp(ctx.y))


def test_a_fit_beside_a_known_part_keeps_it_out_of_its_own_extension(mass_record):
    ctx, fit_mask = mass_record.ctx, mass_record.fit_mask
    known = 0.1 * np.ptp(ctx.y) * np.sin(np.arange(ctx.y.size))
    beside = BASELINE.fit(with_fixed(ctx, ctx.fixed + known), fit_mask)
    np.testing.assert_array_equal(beside.known, ctx.fixed + known)
    np.testing.assert_allclose(extension(ctx, beside), 0.0, atol=1e-9 * np.ptp(ctx.y))
    alone = BASELINE.fit(ctx, fit_mask)
    assert beside.parameters["coulomb"] != alone.parameters["coulomb"]  # refitted beside it


@pytest.mark.parametrize("first, also, record_class, seed", [
    ("presliding_hysteresis", "unmodeled_mass", "drive", 64001),
    ("lubrication", "position_dependent_friction", "friction_along", 64002),
    ("preload_loss", "presliding_hysteresis", "velocity_only", 64003),
])
def test_two_hidden_effects_are_named_in_turn_and_the_gap_shrinks_second_generator(
        tmp_path, first, also, record_class, seed):
    truth = second_truth.draw(tmp_path / "run", first, record_class, seed, also=also,
                              n_samples=4000)
    named = decide.decide(tmp_path / "run")
    effects = [step.effect for step in named.steps]
    assert set(effects[:2]) == {truth.expected, truth.expected_also}
    assert named.effect == effects[0]
    gaps = [step.gap_after for step in named.steps]
    # each step closes a part of the gap (the generator's noise is the independent yardstick:
    # its RMS over the range, which the joint models come within 1.3 to 8 times of on these)
    noise = truth.noise_rms / np.ptp(named.ctx.y[named.held])
    assert named.gap_base > gaps[0] > gaps[1] and gaps[0] - gaps[1] > 0.25 * gaps[0]
    assert gaps[1] < 10.0 * noise
    for step in named.steps[1:]:
        for key, (low, high) in step.intervals.items():
            assert low <= step.fit.parameters[key] <= high
    record = report.diagnosis_record(named, SimpleNamespace(gaps=lambda _: (0.1, 0.05)))
    assert [e["effect"] for e in record["missing_effects"]] == effects
    assert record["missing_effect"] == effects[0]
    assert record["missing_effects"][1]["gap_after"] == round(gaps[1], 8)


def test_a_second_effect_must_differ_from_the_first_in_the_generator(tmp_path):
    with pytest.raises(ValueError, match="also 'lubrication': a second effect must be another"):
        second_truth.draw(tmp_path / "run", "lubrication", "drive", 1, also="lubrication")
