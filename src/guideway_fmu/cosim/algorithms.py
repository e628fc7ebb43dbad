"""How macro steps are taken: Jacobi, Gauss-Seidel and the stabilised coupling for stiff loops.

Each is an :class:`Algorithm`: ``step(t, h) -> (accepted, next_h)`` over a :class:`Bus` that
moves values between FMU instances (master.py), plus class-level hooks for what it needs from the
system beyond its connections (further links, parameters to set at initialisation, variables to
exchange). Subclassing with a ``name`` registers an algorithm in :data:`ALGORITHMS`, the one list
that the scenario check, the command line and the master read. Inputs are held over each step
(FMI 2.0).

* Jacobi: every instance takes its inputs from the outputs at t, then all step. This is what
  libcosim's fixed-step algorithm and fmpy's SSP runner do.
* Gauss-Seidel: instances step one after the other in the order of :func:`order`, each taking
  its inputs from the latest outputs (those of instances already stepped are at t + h).
* Stabilised: Gauss-Seidel plus, for each declared tangent (system.py), the stiff component's
  tangent stiffness/damping dF/dx, dF/dv (an output of the FMU, or a central finite difference
  of its feedthrough output over its input, taken by the master) passed to the consumer, which
  then integrates F ~ F0 + K (x - x0) + C (v - v0) over the step instead of a held F0. A tangent
  may also pass an interface model (``model``: more outputs, such as the contact's force law
  with its films' rates, to consumer inputs) and set parameters the coupling needs
  (``settings``, such as the contact's interpolate_inputs: under Gauss-Seidel its inputs are the
  body's state at the end of the step). With the law the body integrates the contact's own
  frozen-film force within the step, which is what keeps lift-off and re-contact of a row (where
  the tangent is useless) accurate.
  For a linear spring-mass split over two FMUs that is the exact coupling: stable for any h
  (the explicit schemes need omega h < 4 zeta, never stable without damping). For a nonlinear
  force the defect d = |F1 - F0 - K0 dx - C0 dv| at the end of the step is the local error of
  the linearisation (O(h^2)); with ``tolerance`` > 0 each step is accepted when
  r = d / max(|F1 - F0|, |K0 dx|, 0.01 max|F|) <= tolerance (max|F| the largest force so far:
  where a contact opens, F'' is unbounded and the force change alone would make the step
  vanish), else every instance is rolled back (get/set FMU state) and the step retried shorter;
  the next step is h * clip(0.9 sqrt(tolerance / r), 0.2, 2). An FMU that discards a step is
  retried the same way (next step DISCARD_SHRINK h).
"""
from __future__ import annotations

import graphlib
import math
from abc import ABC, abstractmethod
from typing import TYPE_CHECKING

from fmpy.fmi1 import FMICallException

from .fmu_instance import FATAL

if TYPE_CHECKING:
    from .system import System

#: name -> algorithm class; filled by subclassing :class:`Algorithm` with a ``name``
ALGORITHMS: dict[str, type["Algorithm"]] = {}

# Step-size control of the stabilised coupling (module doc)
SAFETY = 0.9  # next h = h * SAFETY sqrt(tolerance / r): aim a little below the tolerance
SHRINK_LIMIT = 0.2  # never shrink by more than this factor in one step ...
GROW_LIMIT = 2.0  # ... nor grow by more than this one
DISCARD_SHRINK = 0.25  # factor of the retry after an FMU discarded (or failed) a step
DEFECT_FLOOR = 0.01  # the defect is measured against at least 1 % of the largest force seen


def order(system: "System") -> list[str]:
    """Gauss-Seidel order: sources before consumers. A loop is cut at a feedthrough output:
    the instance whose connected output is a state (no feedthrough from its inputs) steps
    first, so the one that feeds through sees the others' outputs at the end of the step."""
    feeds = {name: set() for name in system.components}
    edges = sorted({(c.source, c.target) for c in system.connections if c.source != c.target},
                   key=lambda e: any(system.feedthrough[c.source].get(c.output, True)
                                     for c in system.connections if (c.source, c.target) == e))
    for source, target in edges:  # state edges first; an edge that would close a loop is cut
        feeds[target].add(source)
        try:
            graphlib.TopologicalSorter(feeds).prepare()
        except graphlib.CycleError:
            feeds[target].discard(source)
    return list(graphlib.TopologicalSorter(feeds).static_order())


class Algorithm(ABC):
    """How macro steps are taken; a subclass with a ``name`` is registered in ALGORITHMS."""

    name = ""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "name" in cls.__dict__:  # a subclass that keeps its parent's name replaces nothing
            ALGORITHMS[cls.name] = cls

    def __init__(self, bus, system: "System"):
        self.bus = bus

    @classmethod
    def links(cls, system: "System") -> dict:
        """Further feeds {(instance, output or bus key): (instance, input)} besides the
        connections, written to the inputs before each step."""
        return {}

    @classmethod
    def settings(cls, system: "System") -> dict:
        """{instance: {parameter: value}} to set at initialisation, after the scenario's."""
        return {}

    @classmethod
    def exchanged(cls, system: "System") -> set:
        """Further (instance, output) to read after every step of their instance."""
        return set()

    @abstractmethod
    def step(self, t: float, h: float) -> tuple[bool, float]:
        """Advance every instance from t by h [s]; (accepted, next step [s])."""


class Jacobi(Algorithm):
    name = "jacobi"

    def __init__(self, bus, system: "System"):
        super().__init__(bus, system)
        self.names = list(system.components)

    def step(self, t: float, h: float):
        bus = self.bus
        for n in self.names:
            bus.write_inputs(n)
        for n in self.names:
            bus.do_step(n, t, h)
        for n in self.names:
            bus.read_outputs(n)
        return True, h


class GaussSeidel(Algorithm):
    name = "gauss-seidel"

    def __init__(self, bus, system: "System"):
        super().__init__(bus, system)
        self.names = order(system)

    def step(self, t: float, h: float):
        bus = self.bus
        for n in self.names:
            bus.write_inputs(n)
            bus.do_step(n, t, h)
            bus.read_outputs(n)
        return True, h


class Stabilised(GaussSeidel):
    name = "stabilised"

    @classmethod
    def links(cls, system):
        return tangent_links(system.tangents)

    @classmethod
    def settings(cls, system):
        return tangent_settings(system.tangents)

    @classmethod
    def exchanged(cls, system):
        return ({src for src in tangent_links(system.tangents) if src[1] in system.variables[src[0]]}
                | {(t.instance, t.force) for t in system.tangents})

    def __init__(self, bus, system: "System"):
        super().__init__(bus, system)
        exp = system.experiment
        self.tangents = [Tangent(bus, t) for t in system.tangents]
        # with no tangent there is no error estimate: steps shrink on failures, regrow to `step`
        self.tolerance, self.min_step = exp.tolerance, exp.min_step
        self.max_step = exp.max_step if self.tangents else exp.step
        self.rollback = exp.tolerance > 0 and bus.can_roll_back()
        self.differences = [tg.put_differences for tg in self.tangents if tg.differenced]

    def step(self, t: float, h: float):
        if not self.rollback:  # no defect to measure: the slopes the FMUs lack, and the step
            for put in self.differences:
                put()
            return super().step(t, h)
        bus = self.bus
        saved = bus.save()
        try:
            before = [tg.linearise() for tg in self.tangents]
            try:
                super().step(t, h)
            except FMICallException as exc:
                if h <= self.min_step or exc.status == FATAL:
                    raise
                bus.restore(saved)
                return False, max(DISCARD_SHRINK * h, self.min_step)
            ratio = max((tg.defect(*b) for tg, b in zip(self.tangents, before)), default=0.0)
            grow = (min(GROW_LIMIT, max(SHRINK_LIMIT, SAFETY * math.sqrt(self.tolerance / ratio)))
                    if ratio > 0 else GROW_LIMIT)
            next_h = min(self.max_step, max(self.min_step, h * grow))
            if ratio <= self.tolerance or h <= self.min_step:
                return True, next_h
            bus.restore(saved)
            return False, next_h
        finally:
            bus.free(saved)


def _slope_key(spec, output, input_name):
    """Bus key of a tangent: the FMU's output, or a master-side finite difference."""
    return (spec.instance, output if output != "fd" else f"d{spec.force}/d{input_name}")


def tangent_links(tangents) -> dict:
    """{bus key of each stiffness/damping/model output: consumer input} for the Bus (master.py)."""
    links = {}
    for t in tangents:
        links[_slope_key(t, t.stiffness, t.position)] = t.to_stiffness
        if t.velocity:
            links[_slope_key(t, t.damping, t.velocity)] = t.to_damping
        links.update({(t.instance, out): target for out, target in t.model})
    return links


def tangent_settings(tangents) -> dict:
    """{instance: {parameter: value}} that the stabilised coupling sets at initialisation."""
    settings = {}
    for t in tangents:
        settings.setdefault(t.instance, {}).update(t.settings)
    return settings


class Tangent:
    """One declared tangent bound to a bus: makes dF/dx (and dF/dv) available for the
    consumer's inputs (finite differences stored on the bus) and measures the linearisation
    defect of a step."""

    def __init__(self, bus, spec):
        self.bus, self.spec = bus, spec
        inst = spec.instance
        self.force = (inst, spec.force)
        self.x = bus.source_of(inst, spec.position)
        self.v = bus.source_of(inst, spec.velocity) if spec.velocity else None
        self.k_key = _slope_key(spec, spec.stiffness, spec.position)
        self.c_key = _slope_key(spec, spec.damping, spec.velocity) if spec.velocity else None
        self.largest = 0.0  # largest |force| seen: the absolute scale of the defect
        self.k = self._slope(spec.stiffness, spec.position)
        self.c = self._slope(spec.damping, spec.velocity) if spec.velocity else None
        self.differenced = self.k is not None or self.c is not None

    def _slope(self, output, input_name):
        """None for an FMU output (already on the bus), else the finite difference."""
        bus, inst = self.bus, self.spec.instance
        if output != "fd":
            return None
        inst_obj = bus.instances[inst]
        read_f, io = inst_obj.reader([self.spec.force]), inst_obj.reader([input_name])
        write = inst_obj.writer([input_name])

        def central_difference():
            x = io()[0]
            dx = 1e-6 * abs(x) + 1e-12
            write([x + dx])
            f_plus = read_f()[0]
            write([x - dx])
            f_minus = read_f()[0]
            write([x])
            return (f_plus - f_minus) / (2 * dx)
        return central_difference

    def put_differences(self) -> None:
        """Put the finite-difference K, C on the bus for the consumer (the FMU's own slopes are
        there already)."""
        vals = self.bus.values
        if self.k is not None:
            vals[self.k_key] = self.k()
        if self.c is not None:
            vals[self.c_key] = self.c()

    def linearise(self):
        """Put K, C on the bus for the consumer; returns what :meth:`defect` needs."""
        self.put_differences()
        vals = self.bus.values
        k = vals[self.k_key]
        c = vals[self.c_key] if self.c_key else 0.0
        return (vals[self.force], k, c, vals[self.x] if self.x else 0.0,
                vals[self.v] if self.v else 0.0)

    def defect(self, f0, k, c, x0, v0) -> float:
        """Linearisation defect of the step relative to the force change (module doc)."""
        vals = self.bus.values
        f1 = vals[self.force]
        dx = vals[self.x] - x0 if self.x else 0.0
        dv = vals[self.v] - v0 if self.v else 0.0
        predicted = k * dx + c * dv
        self.largest = max(self.largest, abs(f0), abs(f1))
        scale = max(abs(f1 - f0), abs(predicted), DEFECT_FLOOR * self.largest)
        d = abs(f1 - f0 - predicted)
        return d / scale if scale > 0 else (0.0 if d == 0 else math.inf)

