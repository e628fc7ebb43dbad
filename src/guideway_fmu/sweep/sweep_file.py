"""The sweep file (TOML): which scenario, which points, which reduced outputs (docs/sweep.md).

Every error names the sweep file, the table and the key, and what is wrong; a parameter value
is checked by the scenario check itself (``System.with_changes``), whose message is quoted.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from .. import scenarios
from ..cosim import master
from ..cosim.system import (Experiment, ScenarioError, System, TomlTable, load as load_scenario,
                            read_toml)
from . import design
from .reduce import REDUCTIONS, Output

KINDS = ("factorial", "points", "latin-hypercube")


@dataclass(frozen=True)
class Sweep:
    """A checked sweep: the scenario (experiment overrides applied), the swept parameters
    ("<instance>.<parameter>"), the points in design order with their ids, the outputs."""

    path: Path
    system: System
    kind: str
    parameters: tuple[str, ...]
    points: tuple[dict, ...]
    ids: tuple[str, ...]
    outputs: tuple[Output, ...]


def nested(point: dict) -> dict[str, dict]:
    """{"<instance>.<parameter>": value} -> {instance: {parameter: value}} (System.with_changes)."""
    out: dict[str, dict] = {}
    for name, value in point.items():
        instance, _, parameter = name.partition(".")
        out.setdefault(instance, {})[parameter] = value
    return out


def load(path: str | Path, fmu_dir: str | Path | None = None, edition: str = "python") -> Sweep:
    """Read and check a sweep file. Its ``scenario`` is a path relative to the file or a shipped
    scenario's name; FMUs as for ``guideway-fmu run`` (``fmu_dir``, or the FMU cache's set of
    ``edition`` for a shipped one)."""
    path = Path(path)
    src = str(path)
    top = TomlTable(src, "top level", read_toml(path, "the sweep file"))
    top.unknown(("scenario", "description", "experiment", "design", "outputs"))
    system = _scenario(top, path, fmu_dir, edition)
    table = TomlTable(src, "design", top.get("design", dict, required=True))
    kind = table.get("kind", str, required=True)
    if kind not in KINDS:
        raise table.error("kind", f"must be one of {', '.join(KINDS)}, got {kind!r}")
    points = {"factorial": _factorial, "points": _explicit,
              "latin-hypercube": _latin_hypercube}[kind](table, system)
    experiment = system.experiment.__dict__
    ids = tuple(design.point_id(system.name, experiment, p) for p in points)
    if len(set(ids)) < len(ids):
        raise table.error("points" if kind == "points" else kind, "lists the same point twice")
    outputs = _outputs(top, system)
    return Sweep(path, system, kind, tuple(points[0]), tuple(points), ids, outputs)


def _scenario(top: TomlTable, path: Path, fmu_dir, edition: str) -> System:
    name = top.get("scenario", str, required=True)
    beside = path.parent / name
    try:
        scenario = beside if beside.is_file() else scenarios.find(name)
    except ValueError as exc:
        raise top.error("scenario", str(exc)) from None
    system = load_scenario(scenario, scenarios.fmu_folder(scenario, fmu_dir, edition))
    table = TomlTable(top.source, "experiment", top.get("experiment", dict, {}))
    table.unknown(Experiment.__dataclass_fields__)
    changes = {k: table.get(k, type(getattr(system.experiment, k))) for k in table.data}
    try:
        return system.with_changes(**changes)
    except ScenarioError as exc:
        raise table.error(", ".join(changes), f"the scenario refuses it: {exc}") from None


def _check_value(system: System, table: TomlTable, name: str, value) -> None:
    """The scenario check on ``name`` = ``value`` alone; its message quoted under ``name``."""
    instance, dot, parameter = name.partition(".")
    if not (instance and dot and parameter):
        raise table.error(name, "must be '<instance>.<parameter>'")
    try:
        system.with_changes(parameters={instance: {parameter: value}})
    except ScenarioError as exc:
        raise table.error(name, f"the scenario refuses it: {exc}") from None


def _factorial(table: TomlTable, system: System) -> list[dict]:
    table.unknown(("kind", "values"))
    values = TomlTable(table.source, "design.values", table.get("values", dict, required=True))
    if not values.data:
        raise table.error("values", "names no parameter")
    for name in values.data:
        levels = values.get(name, list)
        if not levels:
            raise values.error(name, "lists no value")
        for value in levels:
            _check_value(system, values, name, value)
    return design.factorial(values.data)


def _explicit(table: TomlTable, system: System) -> list[dict]:
    table.unknown(("kind", "points"))
    points = table.get("points", list, required=True)
    if not points:
        raise table.error("points", "lists no point")
    for i, point in enumerate(points):
        row = TomlTable(table.source, f"design.points #{i + 1}", point)
        if set(row.data) != set(points[0]):
            raise table.error("points", f"point #{i + 1} names {sorted(row.data)}, point #1 "
                              f"{sorted(points[0])}: every point sets the same parameters")
        for name, value in row.data.items():
            _check_value(system, row, name, value)
    return [dict(p) for p in points]


def _latin_hypercube(table: TomlTable, system: System) -> list[dict]:
    table.unknown(("kind", "samples", "seed", "ranges"))
    samples = table.get("samples", int, required=True)
    if samples < 1:
        raise table.error("samples", f"must be >= 1, got {samples}")
    ranges = TomlTable(table.source, "design.ranges", table.get("ranges", dict, required=True))
    if not ranges.data:
        raise table.error("ranges", "names no parameter")
    for name in ranges.data:
        bounds = ranges.get(name, list)
        if not (len(bounds) == 2 and all(isinstance(b, (int, float)) and not isinstance(b, bool)
                                         and math.isfinite(b) for b in bounds)
                and bounds[0] < bounds[1]):
            raise ranges.error(name, f"must be [low, high] with finite low < high, got {bounds!r}")
        for value in bounds:
            _check_value(system, ranges, name, float(value))
    return design.latin_hypercube(ranges.data, samples, table.get("seed", int, 0))


def _outputs(top: TomlTable, system: System) -> tuple[Output, ...]:
    outputs, span = [], system.experiment.stop - system.experiment.start
    entries = top.get("outputs", list, required=True)
    if not entries:
        raise top.error("outputs", "lists no output")
    for i, entry in enumerate(entries):
        t = TomlTable(top.source, f"outputs #{i + 1}", entry)
        t.unknown(("variable", "reduce", "settle"))
        instance, variable = t.ref("variable")
        kind = t.get("reduce", str, required=True)
        if kind not in REDUCTIONS:
            raise t.error("reduce", f"must be one of {', '.join(REDUCTIONS)}, got {kind!r}")
        settle = t.get("settle", float, 0.0)
        if not 0 <= settle < span:
            raise t.error("settle", f"must be >= 0 s and shorter than the run ({span:g} s), "
                          f"got {settle}")
        name = f"{instance}.{variable}"
        recorded = master.recorded(system)
        if name not in recorded:
            raise t.error("variable", f"{name} is not recorded by the scenario {system.name} "
                          f"(recorded: {', '.join(recorded)})")
        output = Output(name, kind, settle)
        if any(o.column == output.column for o in outputs):
            raise t.error("reduce", f"{output.column} is asked for twice")
        outputs.append(output)
    return tuple(outputs)
