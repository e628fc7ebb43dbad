"""The shared machinery of the continuous-time models (physics/dynamics.py)."""
import pytest

from guideway_fmu.physics.dynamics import MAX_SUBSTEPS, substeps


def test_substeps_hand_values_and_the_bound():
    assert substeps(1.0, 0.3, "x") == 4  # ceil(3.33)
    assert substeps(1.0, 2.0, "x") == 1
    assert substeps(1.0, 1.0 / MAX_SUBSTEPS, "x") == MAX_SUBSTEPS
    for largest in (0.5 / MAX_SUBSTEPS, 0.0, -1.0, float("nan")):
        with pytest.raises(ValueError, match="substeps of the body"):
            substeps(1.0, largest, "the body")
