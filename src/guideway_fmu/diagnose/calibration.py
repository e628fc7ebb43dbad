"""The confidence a horizontal diagnosis states: the share of right answers among never-seen
synthetic records that gave the same kind of answer on the same evidence.

The evidence of an answer is binned by its kind (a named effect, ``none``, ``unknown``), the gap
before any fit over the reported noise floor (GAP_EDGES) and the answer's raw weight, the BIC
weight of scoring.confidence (WEIGHT_EDGES). calibration.json, beside this module, holds for each
bin the records and the right answers among them, counted by
``benchmarks/diagnose_calibration.py --fit-seed`` on draws of both horizontal generators
(guideway_synthetic) from seeds no rule of the workflow was set on; the same script reports the
reliability of the result on other seeds (docs/diagnosis-calibration.md). A bin states
(right + 1) / (records + 2), Laplace's rule: a bin of few records stays near 1/2, an empty one
states 1/2. The raw weight alone is no probability: it is 0 for a ``none`` a candidate's score
contradicts and for most ``unknown`` answers, which are right nine times in ten.

The counts depend on the workflow's rules. The run that counts them writes
docs/diagnosis-calibration.md too, whose provenance covers the workflow's code and this table:
tests/test_docs_pages.py says when either changed since (rerun the command the page names).
calibration.json's "hash" is the code's hash as that run began, the previous table included.
"""
from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

FILE = Path(__file__).with_name("calibration.json")
GAP_EDGES = (1.3, 2.0, 4.0)  # gap before over the noise floor
WEIGHT_EDGES = (0.5, 0.99)  # raw BIC weight of the answer


def kind(effect: str) -> str:
    """The kind of an answer: ``none``, ``unknown`` or ``effect``."""
    return effect if effect in ("none", "unknown") else "effect"


def bin_of(effect: str, gap_ratio: float, weight: float) -> str:
    """The evidence bin of an answer, e.g. ``effect gap>=4 weight>=0.99``."""
    gap = sum(gap_ratio >= edge for edge in GAP_EDGES)
    held = sum(weight >= edge for edge in WEIGHT_EDGES)
    gap_label = f"gap>={GAP_EDGES[gap - 1]:g}" if gap else f"gap<{GAP_EDGES[0]:g}"
    weight_label = f"weight>={WEIGHT_EDGES[held - 1]:g}" if held else f"weight<{WEIGHT_EDGES[0]:g}"
    return f"{kind(effect)} {gap_label} {weight_label}"


@lru_cache(maxsize=1)
def table() -> dict:
    """calibration.json's content: {"hash": ..., "bins": {bin: [right, records]}}; empty bins
    where the file is missing."""
    if not FILE.exists():
        return {"hash": None, "bins": {}}
    return json.loads(FILE.read_text(encoding="utf-8"))


def confidence(effect: str, gap_ratio: float, weight: float) -> float:
    """The stated confidence [0, 1] of the answer ``effect`` on its evidence (module docstring)."""
    right, records = table()["bins"].get(bin_of(effect, gap_ratio, weight), (0, 0))
    return (right + 1.0) / (records + 2.0)


def count(rows) -> dict:
    """{bin: [right, records]} of ``rows`` (dicts: named, expected, gap_ratio, weight)."""
    bins: dict[str, list[int]] = {}
    for row in rows:
        tally = bins.setdefault(bin_of(row["named"], row["gap_ratio"], row["weight"]), [0, 0])
        tally[0] += int(row["named"] == row["expected"])
        tally[1] += 1
    return dict(sorted(bins.items()))


def write(bins: dict, digest: str, command: str) -> Path:
    """calibration.json with the counts ``bins``, the code's hash ``digest`` and the command."""
    FILE.write_text(json.dumps({"hash": digest, "command": command, "bins": bins}, indent=1)
                    + "\n", encoding="utf-8")
    table.cache_clear()
    return FILE
