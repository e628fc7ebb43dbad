"""The candidate registry: one class per effect, read by the decision, the report and the truth
generator; each names a friction FMU the component registry builds and a law of physics."""
from __future__ import annotations

from types import SimpleNamespace

import pytest

from guideway_fmu.components import registry
from guideway_fmu.diagnose import candidates
from guideway_synthetic import truth
from guideway_fmu.physics.rigs import friction_laws
from guideway_fmu.physics.roller_guide import friction


def test_every_candidate_names_a_built_fmu_and_a_physics_law():
    built = set(registry.names())
    laws = [f for module in (friction_laws, friction) for f in vars(module).values()
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


@pytest.mark.parametrize("effect, cls", [("position_dependent_friction", candidates.PositionDependent),
                                         ("ball_to_ball_contact", candidates.BallToBall)])
def test_a_table_is_fitted_sparse_as_the_dense_least_squares_would(tmp_path, effect, cls):
    # the dense design of a table took 8 bytes x samples x nodes (3.2 GB at 1e6 x 400)
    import numpy as np
    from scipy import sparse

    from guideway_fmu.diagnose.decide import _splits, motion_of
    from guideway_fmu.diagnose.run_io import load_run
    truth.make_run(tmp_path / "run", effect, np.random.default_rng(7), n_samples=3000)
    run = load_run(tmp_path / "run")
    motion = motion_of(run)
    ctx = candidates.Context.of(run, motion)
    fit_mask = _splits(run, motion)[1][0][0]
    table = cls()
    for setting in table.settings(ctx)[:3]:
        columns = table.columns(ctx, setting)
        assert sparse.issparse(columns) and columns.nnz <= 2 * ctx.y.size
        _, coef, _ = table._evaluate(ctx, fit_mask, setting)
        dense = np.column_stack([columns.toarray(), np.ones(ctx.y.size)])[fit_mask]
        penalty = table.penalty(sparse.csr_matrix(dense[:, :-1]))
        rows = np.vstack([dense, np.column_stack([penalty, np.zeros(len(penalty))])])
        rhs = np.r_[(ctx.y - ctx.fixed)[fit_mask], np.zeros(len(penalty))]
        expected = np.linalg.lstsq(rows, rhs, rcond=None)[0]
        assert np.allclose(coef, expected, rtol=1e-7, atol=1e-9 * np.abs(expected).max())
