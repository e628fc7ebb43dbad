"""How the discrepancy workflow scores a model against the samples: the Bayesian information
criterion of a least-squares fit."""
from __future__ import annotations

import numpy as np

#: least mean square a BIC takes [unit of the residual squared]: a fit exact to the last bit
#: keeps a finite score
LEAST_MEAN_SQUARE = 1e-300


def bic(rss: float, samples: int, parameters: int) -> float:
    """BIC [-] of a least-squares fit with Gaussian errors: n ln(RSS / n) + k ln n for the
    residual sum of squares ``rss`` over n = ``samples`` and k = ``parameters`` fitted numbers
    (the constant terms dropped: only differences between models on the same samples count;
    lower is better)."""
    return float(samples * np.log(max(rss / samples, LEAST_MEAN_SQUARE))
                 + parameters * np.log(samples))
