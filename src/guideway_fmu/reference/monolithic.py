"""Monolithic reference: a whole scenario's equations integrated in one process.

The reference that co-simulation results are measured against. Each component's FMU is found in
the component registry (``components/registry.py``) by its model identifier, and its physics is
the same continuous-time model the FMU steps (``physics/dynamics.py``), built from the FMU's
start values overridden by the scenario's parameters. The models are assembled along the
scenario's connections: one state vector (every model's states, in the order of the system's
components), every input fed by the output it is connected to or held at its start value, and
``solve_ivp`` (LSODA at rtol 1e-10 by default; RK45 where a model is not smooth, see
``ContinuousModel.smooth``) integrates the lot. Inputs that serve only the
coupling (tangents, interface laws) are not among the models' inputs, and step settings (the
contact's interpolate_inputs) are not among their parameters: the equations are those of the
physics, not of the FMUs' steps.

An output that bears a state's name is that state, so a connection from it cuts any loop (the
carriage's y feeds the contact, whose force feeds the carriage); a loop of feedthrough outputs
alone is an algebraic loop and refused. Tolerances: atol = rtol x each state's nominal scale
(``ContinuousModel.state_scales``). Outputs are evaluated on the solution at the output times:
every output of every model. ``benchmarks/monolithic_integrators.py`` compares SciPy's methods.
"""
from __future__ import annotations

import graphlib
import time
from dataclasses import dataclass

import numpy as np
from fmpy import read_model_description
from scipy.integrate import solve_ivp

from ..components import registry
from ..cosim.system import typed


@dataclass
class Reference:
    """A reference run: ``columns`` maps "<instance>.<variable>" to values at ``time`` [s].

    ``wall_time`` [s] is that of the whole call (assembling the system, integrating, evaluating
    the outputs: what a co-simulation's run is compared with), ``nfev`` the right-hand side
    evaluations.
    """

    time: np.ndarray
    columns: dict[str, np.ndarray]
    units: dict[str, str]
    wall_time: float
    nfev: int
    method: str
    rtol: float


def check(system) -> None:
    """Raise ValueError naming the component if the reference cannot model ``system``."""
    _Assembly(system)


def simulate(system, times=None, rtol: float = 1e-10, method: str | None = None,
             columns=None, start_offset: float = 0.0) -> Reference:
    """Integrate ``system`` (a checked ``cosim.system.System``) from experiment.start.

    ``times`` [s], increasing and not before the start, are the output times; by default the
    macro-step grid start, start + step, ..., stop. ``method`` is a ``solve_ivp`` method; by
    default LSODA, or RK45 when a model's derivatives jump (``ContinuousModel.smooth``).
    ``columns`` ("<instance>.<variable>") limits the outputs evaluated to those (and what they
    need): a fit that reads one channel skips the rest. ``start_offset`` moves every state's
    start by that fraction of its nominal scale (a disturbed start, to probe predictability).
    Raises ValueError naming the component for a component or a wiring that the reference
    cannot model, RuntimeError when the integration fails.
    """
    exp = system.experiment
    if times is None:
        times = exp.start + exp.step * np.arange(int(round((exp.stop - exp.start) / exp.step)) + 1)
    times = np.asarray(times, dtype=float)
    if times.ndim != 1 or times.size < 2 or np.any(np.diff(times) <= 0) or times[0] < exp.start:
        raise ValueError(f"times must increase, from the start time {exp.start} s on, got {times!r}")
    t0 = time.perf_counter()
    model = _Assembly(system)
    if method is None:
        smooth = all(b.model.smooth for b in model.blocks.values())
        method = "LSODA" if smooth else "RK45"
    y0 = model.initial_state(exp.start) + start_offset * model.atol(1.0)
    sol = solve_ivp(model.rhs, (exp.start, times[-1]), y0, method=method, t_eval=times,
                    rtol=rtol, atol=model.atol(rtol))
    if not sol.success:
        raise RuntimeError(f"{system.name}: {method} failed at rtol {rtol}: {sol.message}")
    out = model.outputs(sol.t, sol.y, None if columns is None else
                        {name.split(".", 1)[0] for name in columns})
    if columns is not None:
        out = {name: out[name] for name in columns}
    units = {k: system.unit(*k.split(".", 1)) for k in out}
    return Reference(sol.t, out, units, time.perf_counter() - t0, int(sol.nfev), method, rtol)


# -- assembling the system ---------------------------------------------------------------------
class _Block:
    """One component: its continuous-time model, where its states sit in the state vector and
    where each of its inputs comes from: ("state", index), ("output", block, name) or
    ("constant", value)."""

    def __init__(self, system, name: str):
        comp = system.components[name]
        md = read_model_description(str(comp.fmu))
        ids = (md.coSimulation.modelIdentifier if md.coSimulation else None, md.modelName)
        known = registry.components()
        kind = next((i for i in ids if i in known), None)
        self.name, self.kind = name, kind
        if kind is None:
            raise ValueError(f"component {name!r}: FMU {comp.fmu.name} (model identifier "
                             f"{ids[0]!r}) cannot be modelled by the monolithic reference; it "
                             f"knows {', '.join(known)}")
        variables = {v.name: v for v in md.modelVariables}
        values = {n: typed(v, v.start) for n, v in variables.items()
                  if v.causality in ("parameter", "input") and v.start is not None}
        values.update({n: typed(variables[n], v) for n, v in comp.parameters.items()})
        params = {n: values[n] for n, v in variables.items() if v.causality == "parameter"}
        try:
            self.model = known[kind].continuous_model(params)
        except (TypeError, ValueError, NotImplementedError) as exc:
            raise self.error(f"cannot be modelled: {exc}") from exc
        self.values = values
        self.offset, self.size = 0, len(self.model.states)
        self.sources: list[tuple[str, tuple]] = []

    def error(self, message: str) -> ValueError:
        return ValueError(f"component {self.name!r} ({self.kind}): {message}")


class _Assembly:
    """The wired system: state layout, right-hand side, initial state and outputs."""

    def __init__(self, system):
        self.blocks = {name: _Block(system, name) for name in system.components}
        feeds = {(c.target, c.input): (c.source, c.output) for c in system.connections}
        n = 0
        for b in self.blocks.values():
            b.offset, n = n, n + b.size
        self.n = n
        after: dict[str, set] = {name: set() for name in self.blocks}  # block -> blocks it reads
        state_edges = []
        for b in self.blocks.values():
            for name in b.model.inputs:
                src = feeds.get((b.name, name))
                if src is None:
                    b.sources.append((name, ("constant", float(b.values.get(name, 0.0)))))
                    continue
                a = self.blocks[src[0]]
                if src[1] in a.model.states:
                    b.sources.append((name, ("state", a.offset + a.model.states.index(src[1]))))
                    state_edges.append((a.name, b.name))
                else:
                    b.sources.append((name, ("output", a.name, src[1])))
                    after[b.name].add(a.name)
        try:
            self.order = list(graphlib.TopologicalSorter(after).static_order())
        except graphlib.CycleError as exc:
            raise ValueError(f"the monolithic reference cannot solve the algebraic loop "
                             f"{' -> '.join(exc.args[1])}: no output in it is a state") from None
        self.after = after
        # blocks whose outputs the derivatives need, and the initialisation order
        upstream = set(self._upstream([b.name for b in self.blocks.values() if b.size]))
        read = {name: set() for name in self.blocks}  # outputs the derivatives read, by block
        for b in self.blocks.values():
            for _, src in b.sources:
                if src[0] == "output":
                    read[src[1]].add(src[2])
        self.rhs_blocks = [(self.blocks[name], tuple(sorted(read[name])) if name in upstream else None)
                           for name in self.order if name in upstream or self.blocks[name].size]
        init: dict[str, set] = {name: set() for name in self.blocks}  # states first: the
        edges = state_edges + [(a, b) for b, deps in after.items() for a in sorted(deps)]
        for a, b in edges:  # carriage's y before the films it sets; feedthrough where no loop
            init[b].add(a)
            try:
                graphlib.TopologicalSorter(init).prepare()
            except graphlib.CycleError:
                init[b].discard(a)
        self.init_order = list(graphlib.TopologicalSorter(init).static_order())

    def _upstream(self, names) -> list[str]:
        """The blocks whose outputs ``names`` read, directly or not, in evaluation order."""
        need, todo = set(), list(names)
        while todo:
            for a in self.after[todo.pop()]:
                if a not in need:
                    need.add(a)
                    todo.append(a)
        return [name for name in self.order if name in need]

    @staticmethod
    def _inputs(b: _Block, x, outputs) -> dict:
        return {name: x[src[1]] if src[0] == "state" else src[1] if src[0] == "constant"
                else outputs[src[1]][src[2]] for name, src in b.sources}

    def _outputs(self, t: float, x, names) -> dict:
        outputs = {}
        for name in names:
            b = self.blocks[name]
            outputs[name] = b.model.outputs(t, x[b.offset: b.offset + b.size],
                                            self._inputs(b, x, outputs))
        return outputs

    def initial_state(self, start: float) -> np.ndarray:
        """The state at the start time [s], each model's from its inputs there."""
        x = np.zeros(self.n)
        for name in self.init_order:
            b = self.blocks[name]
            if b.size:
                outputs = self._outputs(start, x, self._upstream([name]))
                x[b.offset: b.offset + b.size] = b.model.initial_state(
                    start, self._inputs(b, x, outputs))
        return x

    def atol(self, rtol: float) -> np.ndarray:
        """rtol x each state's nominal scale."""
        scales = [s for b in self.blocks.values() for s in b.model.state_scales()]
        return rtol * np.asarray(scales, dtype=float)

    def rhs(self, t: float, x) -> list:
        """d(state)/dt at the time t [s]."""
        x = x.tolist()
        outputs, rates = {}, [0.0] * self.n
        for b, wanted in self.rhs_blocks:
            state, inputs = x[b.offset: b.offset + b.size], self._inputs(b, x, outputs)
            if not b.size:
                outputs[b.name] = b.model.outputs(t, state, inputs, wanted)
            elif wanted:
                rates[b.offset: b.offset + b.size], outputs[b.name] = b.model.evaluate(t, state, inputs)
            else:
                rates[b.offset: b.offset + b.size] = b.model.derivatives(t, state, inputs)
        return rates

    def outputs(self, t: np.ndarray, states: np.ndarray, blocks=None) -> dict[str, np.ndarray]:
        """Every output of every model (or of the ``blocks`` named, evaluated with what they
        read) at the times t [s], in the system's order."""
        names = self.order if blocks is None else [
            n for n in self.order if n in set(blocks) | set(self._upstream(list(blocks)))]
        rows = [self._outputs(float(ti), states[:, i].tolist(), names)
                for i, ti in enumerate(t)]
        return {f"{name}.{k}": np.array([row[name][k] for row in rows], dtype=float)
                for name in names for k in rows[0][name]}
