"""The memory of ``guideway-fmu diagnose`` on a long record stays bounded (issue 21): a record
of 1e6 rows took 7.55 GB of peak RSS; benchmarks/diagnose_memory.py writes the figures."""
from __future__ import annotations

import numpy as np
import pytest

from guideway_synthetic import truth
from guideway_synthetic.trials import diagnose_in_child

# minutes: a million samples decided and co-simulated. Not serial: the peak is the child's own
# (os.wait4), which other processes do not change, and it takes one core like any test
pytestmark = pytest.mark.slow

BOUND = 2e9  # bytes of peak resident set size at 1e6 rows


def test_a_million_rows_are_diagnosed_within_two_gigabytes(tmp_path, fmu_dir):
    info = truth.make_run(tmp_path / "run", "presliding_hysteresis", np.random.default_rng(3),
                          n_samples=1_000_000)
    diagnosis, peak = diagnose_in_child(tmp_path / "run", tmp_path / "out", fmu_dir)
    assert peak < BOUND, f"peak RSS {peak / 1e9:.2f} GB"
    assert diagnosis["missing_effect"] == info.expected
