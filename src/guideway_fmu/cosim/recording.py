"""Recorded signals of a run, written as CSV with a units sidecar."""
from __future__ import annotations

import csv
import json
from array import array
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .observers import Observer


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


class Recorder(Observer):
    """Collects rows of values at the start, at accepted communication points at most one per
    ``interval`` [s], and at the stop time."""

    def __init__(self, names: list[str], units: dict[str, str], interval: float = 0.0):
        self.names, self.units, self.interval = names, units, interval
        self._keys = [tuple(n.split(".", 1)) for n in names]
        self._time = array("d")  # flat arrays: nothing for the garbage collector to traverse
        self._rows = array("d")
        self._next = -np.inf
        self._last = np.inf

    def started(self, system, bus):
        exp = system.experiment
        self._last = exp.stop - 1e-9 * exp.step  # a step ending beyond this is the last
        self._sample(exp.start, bus)

    def stepped(self, t, bus):
        if t >= self._next or t >= self._last:
            self._sample(t, bus)

    def _sample(self, t: float, bus) -> None:
        bus.observe()
        values = bus.values
        self._time.append(t)
        self._rows.extend([values[k] for k in self._keys])
        self._next = t + self.interval * (1 - 1e-9)

    def recording(self) -> Recording:
        data = np.array(self._rows, dtype=float).reshape(len(self._time), len(self.names))
        return Recording(np.array(self._time), {n: data[:, i] for i, n in enumerate(self.names)},
                         {n: self.units[n] for n in self.names})
