"""One point of a sweep: the co-simulation with the point's parameters, reduced. What a Dask
worker runs (it imports this module, so workers need guideway_fmu installed)."""
from __future__ import annotations

import time

from ..cosim import master
from ..cosim.system import System
from .reduce import Output
from .sweep_file import nested


def run_point(system: System, point: dict, outputs: tuple[Output, ...]) -> dict:
    """Simulate ``system`` with ``point`` ({"<instance>.<parameter>": value}) set, re-checked by
    the scenario check; returns {"outputs": {column: value}, "wall_time_s": s}. A failing run
    raises (SimulationError, ScenarioError, ValueError of a reduction)."""
    start = time.perf_counter()
    result = master.simulate(system.with_changes(parameters=nested(point)))
    values = {o.column: o.of(result.recording) for o in outputs}
    return {"outputs": values, "wall_time_s": time.perf_counter() - start}
