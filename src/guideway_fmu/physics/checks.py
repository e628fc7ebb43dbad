"""Argument checks shared by the physics functions.

Every check raises ``ValueError`` whose message starts with the name of the offending
quantity, so that a component can pass the message on to the FMU log unchanged.
"""
from __future__ import annotations

import numpy as np


def finite(name: str, value):
    """Return ``value`` as a float array after checking that every entry is finite."""
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return arr


def positive(name: str, value):
    """Return ``value`` after checking that it is finite and > 0."""
    arr = finite(name, value)
    if not np.all(arr > 0.0):
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return arr


def non_negative(name: str, value):
    """Return ``value`` after checking that it is finite and >= 0."""
    arr = finite(name, value)
    if not np.all(arr >= 0.0):
        raise ValueError(f"{name} must be >= 0, got {value!r}")
    return arr


def positive_integer(name: str, value):
    """Return ``value`` after checking that it is a whole number > 0 (bools refused)."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value <= 0:
        raise ValueError(f"{name} must be a positive integer, got {value!r}")
    return value


def in_range(name: str, value, low: float, high: float):
    """Return ``value`` after checking that it is finite and within [low, high]."""
    arr = finite(name, value)
    if not np.all((arr >= low) & (arr <= high)):
        raise ValueError(f"{name} must lie in [{low}, {high}], got {value!r}")
    return arr


def check_fields(obj, rules: dict) -> None:
    """Check the dataclass ``obj`` field by field: ``rules`` maps a field name to a check."""
    for field, check in rules.items():
        check(f"{type(obj).__name__}.{field}", getattr(obj, field))
