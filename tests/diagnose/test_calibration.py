"""The stated confidence read from the calibration table (diagnose/calibration.py): bins and
Laplace's rule, by hand."""
from __future__ import annotations

import pytest

from guideway_fmu.diagnose import calibration


@pytest.mark.parametrize("effect, gap, weight, label", [
    ("lubrication", 5.0, 1.0, "effect gap>=4 weight>=0.99"),
    ("none", 1.0, 0.0, "none gap<1.3 weight<0.5"),
    ("unknown", 1.3, 0.7, "unknown gap>=1.3 weight>=0.5"),
    ("presliding_hysteresis", 3.9, 0.99, "effect gap>=2 weight>=0.99")])
def test_evidence_bins(effect, gap, weight, label):
    assert calibration.bin_of(effect, gap, weight) == label


def test_a_bin_states_laplaces_rule_and_an_empty_one_a_half(monkeypatch):
    monkeypatch.setattr(calibration, "table", lambda: {"bins": {"none gap<1.3 weight<0.5": [18, 20]}})
    assert calibration.confidence("none", 1.0, 0.0) == pytest.approx(19 / 22)
    assert calibration.confidence("unknown", 1.0, 0.0) == 0.5


def test_counts_of_rows_by_hand():
    rows = [{"named": "none", "expected": "none", "gap_ratio": 1.0, "weight": 0.0},
            {"named": "none", "expected": "lubrication", "gap_ratio": 1.1, "weight": 0.2},
            {"named": "lubrication", "expected": "lubrication", "gap_ratio": 9.0, "weight": 1.0}]
    assert calibration.count(rows) == {"effect gap>=4 weight>=0.99": [1, 1],
                                       "none gap<1.3 weight<0.5": [1, 2]}
