"""The candidate registry: one class per effect, read by the decision, the report and the truth
generator; each names a friction FMU the component registry builds and a law of physics."""
from __future__ import annotations

from types import SimpleNamespace

import pytest

from guideway_fmu.components import registry
from guideway_fmu.diagnose import candidates, truth
from guideway_fmu.physics import friction_effects, roller_friction


def test_every_candidate_names_a_built_fmu_and_a_physics_law():
    built = set(registry.names())
    laws = [f for module in (friction_effects, roller_friction) for f in vars(module).values()
            if callable(f)]
    for effect, cls in candidates.CANDIDATES.items():
        assert cls.fmu_name in built, effect
        assert any(cls.law is f for f in laws), effect
        assert cls.signal, effect


def test_running_distance_effects_are_read_from_the_registry():
    assert set(candidates.RUNNING_DISTANCE_EFFECTS) == {"preload_loss", "ball_to_ball_contact"}


@pytest.mark.parametrize("guide, expected", [("ball", True), ("roller", False), (None, False)])
def test_ball_to_ball_applies_to_ball_guides_only(guide, expected):
    run = SimpleNamespace(sections={"guideway": {"type": guide}} if guide else {})
    effects = [c.effect for c in candidates.candidates_for(run)]
    assert ("ball_to_ball_contact" in effects) is expected
    assert effects[:5] == ["lubrication", "presliding_hysteresis", "position_dependent_friction",
                           "unmodeled_mass", "preload_loss"]


def test_truth_expects_every_registered_effect_it_can_hide_by_name():
    for effect, answer in truth.EXPECTED.items():
        assert answer == (effect if effect in candidates.CANDIDATES or effect == "none"
                          else "unknown")
    assert set(candidates.CANDIDATES) <= set(truth.EXPECTED)


def test_a_new_candidate_registers_by_being_defined():
    try:
        class Squeal(candidates.Candidate):
            effect, signal, fmu_name = "squeal", "speed", "FrictionStribeck"
            running_distance = True

        assert candidates.CANDIDATES["squeal"] is Squeal
        run = SimpleNamespace(sections={})
        assert any(isinstance(c, Squeal) for c in candidates.candidates_for(run))
    finally:
        candidates.CANDIDATES.pop("squeal", None)
