"""A fixed-step Gauss-Seidel master over FMU instances, and its recording as CSV."""
from __future__ import annotations

import csv
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from fmpy.fmi1 import FMICallException

from .fmu_instance import FmuInstance


@dataclass(frozen=True)
class Connection:
    """Output ``source.variable`` feeds input ``target.variable``."""

    source: str
    output: str
    target: str
    input: str


@dataclass
class Recording:
    """Recorded signals: ``time`` [s] and one column per ``<instance>.<variable>``."""

    time: np.ndarray
    columns: dict[str, np.ndarray]
    units: dict[str, str]

    def write_csv(self, path: str | Path) -> Path:
        """Write the CSV and, beside it, ``<name>.units.json`` with every column's unit."""
        path = Path(path)
        names = list(self.columns)
        with path.open("w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["time", *names])
            writer.writerows(np.column_stack([self.time, *self.columns.values()]).tolist())
        units = {"time": "s", **self.units}
        path.with_suffix(".units.json").write_text(json.dumps(units, indent=1))
        return path


def _propagate(instances: dict[str, FmuInstance], connections, target: str | None = None):
    for c in connections:
        if target is None or c.target == target:
            instances[c.target].set(c.input, instances[c.source].get(c.output))


def run(instances: dict[str, FmuInstance], connections: list[Connection], order: list[str],
        start: float, stop: float, step: float, record: list[str]) -> Recording:
    """Step the initialised ``instances`` from ``start`` to ``stop`` with the macro step ``step``.

    Each macro step visits the instances in ``order``; an instance's inputs are taken from the
    latest outputs of its sources (Gauss-Seidel). ``record`` names ``<instance>.<variable>``.
    """
    if not step > 0 or not stop > start:
        raise ValueError(f"need stop > start and step > 0, got start={start}, stop={stop}, step={step}")
    signals = [tuple(name.split(".", 1)) for name in record]
    for inst, var in signals:
        instances[inst].variable(var)
    n = int(round((stop - start) / step))
    time = start + step * np.arange(n + 1)
    data = np.empty((n + 1, len(signals)))

    def sample(i):
        _propagate(instances, connections)
        data[i] = [instances[inst].get(var) for inst, var in signals]

    sample(0)
    for i in range(n):
        for name in order:
            _propagate(instances, connections, target=name)
            try:
                instances[name].fmu.doStep(currentCommunicationPoint=time[i],
                                           communicationStepSize=step)
            except FMICallException as exc:
                raise RuntimeError(f"FMU instance {name!r} failed its step at t = {time[i]:.9g} s "
                                   f"(see its log above): {exc}") from exc
        sample(i + 1)
    return Recording(time, {f"{a}.{b}": data[:, k] for k, (a, b) in enumerate(signals)},
                     {f"{a}.{b}": instances[a].unit(b) for a, b in signals})
