"""The shared machinery of the continuous-time models (physics/dynamics.py)."""
import pytest

from guideway_fmu.physics.dynamics import MAX_SUBSTEPS, substeps


def test_substeps_hand_values_and_the_bound():
    assert substeps(10 / 3, "x") == 4  # rounded up
    assert substeps(0.0, "x") == 1  # nothing limits the step: one
    assert substeps(MAX_SUBSTEPS, "x") == MAX_SUBSTEPS
    for count in (MAX_SUBSTEPS + 0.5, float("inf"), float("nan")):
        with pytest.raises(ValueError, match="substeps of the body"):
            substeps(count, "the body")
