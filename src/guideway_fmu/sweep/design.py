"""Designs of experiments: the points of a sweep, each a dict ``{"<instance>.<parameter>": value}``.

Pure functions of the sweep file's values, so the same file gives the same points (and point
ids) on every run, which ``--resume`` relies on.
"""
from __future__ import annotations

import hashlib
import itertools
import json

import numpy as np


def factorial(levels: dict[str, list]) -> list[dict]:
    """Every combination of the listed values (full factorial), the last parameter varying
    fastest: prod(len(values)) points."""
    names = list(levels)
    return [dict(zip(names, combination)) for combination in itertools.product(*levels.values())]


def latin_hypercube(ranges: dict[str, tuple[float, float]], samples: int, seed: int) -> list[dict]:
    """``samples`` points of a Latin hypercube (scipy.stats.qmc.LatinHypercube, seeded) scaled to
    ``ranges`` {name: (low, high)}: along every parameter each of ``samples`` equal bins of
    [low, high) holds exactly one point."""
    from scipy.stats import qmc  # here: scipy.stats takes long to import
    unit = qmc.LatinHypercube(len(ranges), seed=seed).random(samples)
    low, high = np.array(list(ranges.values()), dtype=float).T
    scaled = qmc.scale(unit, low, high)
    return [{name: float(value) for name, value in zip(ranges, row)} for row in scaled]


def point_id(scenario: str, experiment: dict, point: dict) -> str:
    """A point's id: 16 hex digits of the SHA-256 of the scenario's name, its experiment and the
    point's values, so a changed stop time or scenario never counts as an already finished point."""
    text = json.dumps({"scenario": scenario, "experiment": experiment, "point": point},
                      sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]
