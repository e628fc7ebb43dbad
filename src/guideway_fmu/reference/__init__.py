"""The monolithic reference of any scenario of registered FMUs (monolithic.py) and the
comparison of a co-simulation with it (verify.py), pointwise or by statistics as the
reference's predictability allows (criterion.py, statistics.py)."""
from .monolithic import Reference, simulate

__all__ = ["Reference", "simulate"]
