"""The workflow's scoring (diagnose/scoring.py) against hand calculations."""
import math

import pytest

from guideway_fmu.diagnose.scoring import LEAST_MEAN_SQUARE, bic


def test_bic_is_n_log_mean_square_plus_k_log_n_hand_calculation():
    # RSS 8 over 4 samples, 2 parameters: 4 ln 2 + 2 ln 4 = 8 ln 2
    assert bic(8.0, 4, 2) == pytest.approx(8.0 * math.log(2.0), rel=1e-15)
    # one parameter more pays ln n: it must cut the RSS by the factor n^(1/n) to break even
    assert bic(8.0 / 4.0 ** 0.25, 4, 3) == pytest.approx(bic(8.0, 4, 2), rel=1e-14)


def test_exact_fit_scores_the_least_mean_square_not_minus_infinity():
    assert bic(0.0, 10, 1) == pytest.approx(10 * math.log(LEAST_MEAN_SQUARE) + math.log(10),
                                            rel=1e-15)
