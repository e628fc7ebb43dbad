"""Recorded signals of a run, written as CSV with a units sidecar."""
from __future__ import annotations

import csv
import json
from array import array
from dataclasses import dataclass
from pathlib import Path

import numpy as np


@dataclass
class Recording:
    """Recorded signals: ``time`` [s] and one column per ``<instance>.<variable>``."""

    time: np.ndarray
    columns: dict[str, np.ndarray]
    units: dict[str, str]

    def write_csv(self, path: str | Path) -> Path:
        """Write the CSV (header ``time,<instance>.<variable>,...``) and, beside it,
        ``<name>.units.json`` mapping every column to its unit."""
        path = Path(path)
        names = list(self.columns)
        with path.open("w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["time", *names])
            writer.writerows(np.column_stack([self.time, *self.columns.values()]).tolist())
        path.with_suffix(".units.json").write_text(json.dumps({"time": "s", **self.units}, indent=1))
        return path


class Recorder:
    """Collects rows of values at accepted communication points, at most one per ``interval``."""

    def __init__(self, names: list[str], units: dict[str, str], interval: float = 0.0):
        self.names, self.units, self.interval = names, units, interval
        self._time = array("d")  # flat arrays: nothing for the garbage collector to traverse
        self._rows = array("d")
        self._next = -np.inf

    def due(self, t: float) -> bool:
        return t >= self._next

    def sample(self, t: float, row: list[float], force: bool = False) -> None:
        if force or t >= self._next:
            self._time.append(t)
            self._rows.extend(row)
            self._next = t + self.interval * (1 - 1e-9)

    def recording(self) -> Recording:
        data = np.array(self._rows, dtype=float).reshape(len(self._time), len(self.names))
        return Recording(np.array(self._time), {n: data[:, i] for i, n in enumerate(self.names)},
                         {n: self.units[n] for n in self.names})
