"""The co-simulation master: instantiate a system's FMUs, step them with an algorithm, record.

``simulate(system)`` is the whole run; :class:`Execution` steps a system on demand
(instantiate, initialise, advance to a time, close): the one stepping loop, behind ``simulate``
and the packed FMU of a whole system (packed_fmu.py). The pieces follow libcosim's split: the
:class:`Bus` moves values between instances (execution), algorithms.py decides how steps are
taken, and observers (observers.py: the recorder, the progress bar, any the caller adds) are notified at
the start, after every accepted step and at the end. The master talks to FMUs only through FMI (fmpy), so it runs
FMUs this project did not build (Real, Integer, Boolean and Enumeration connections).
"""
from __future__ import annotations

import gc
import math
import signal
import sys
import time
from contextlib import nullcontext
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np
from fmpy.fmi1 import FMICallException

from .algorithms import ALGORITHMS, Algorithm, order
from .fmu_instance import ERROR, FATAL, FmuInstance, remove_unpacked
from .interrupts import GRACE_PERIOD, StopRequested, StopRequests
from .observers import Observer, ProgressBar
from .recording import Recorder, Recording, RecordingError
from .system import System
from .watchdog import Watchdog


@dataclass
class Result:
    """What a run produced; ``error`` is set (and the recording partial) when it failed."""

    system: str
    algorithm: str
    recording: Recording
    parameters: dict
    steps: int = 0
    rejected: int = 0
    wall_time: float = 0.0  # s, the stepping loop
    fmi_time: float = 0.0  # s, inside FMI calls during the loop
    error: str | None = None
    stored: dict | None = None  # what the results file holds (Recorder.stored), if one was written

    def summary(self) -> dict:
        return {"scenario": self.system, "algorithm": self.algorithm,
                "parameters": self.parameters, "steps": self.steps, "rejected": self.rejected,
                "wall_time_s": self.wall_time, "fmi_call_time_s": self.fmi_time,
                "master_overhead_s": self.wall_time - self.fmi_time,
                "time_span_s": [float(self.recording.time[0]), float(self.recording.time[-1])]
                if len(self.recording.time) else [], "results": self.stored, "error": self.error}


class SimulationError(RuntimeError):
    """A run that stopped; ``result`` holds what was recorded until then, ``signal`` the signal
    (SIGINT, SIGTERM) that stopped it, None when an FMU failed."""

    def __init__(self, message: str, result: Result, signal: int | None = None):
        super().__init__(message)
        self.result, self.signal = result, signal


class NonFiniteOutput(FMICallException):
    """An FMU returned NaN or an infinite value with status OK (an error for the master: it would
    reach the other FMUs and the results silently)."""

    def __init__(self, instance: str, variable: str, value):
        super().__init__(f"fmi2Get {variable}", ERROR)
        self.instance, self.variable, self.value = instance, variable, value

    def __str__(self) -> str:
        return f"output {self.variable} is {self.value} (with status OK)"


class Bus:
    """The instances of a system and the latest value of every exchanged or recorded variable,
    ``values[(instance, variable)]``; batched reads and writes, one FMI call per type.

    ``exchanged`` variables are read after every step of their instance, ``observed`` ones
    (recorded only) when :meth:`observe` is called, before a sample is recorded. ``links`` are
    further (source key -> (instance, input)) feeds that an algorithm adds (``Algorithm.links``),
    written together with the connections.
    """

    def __init__(self, system: System, instances: dict[str, FmuInstance], exchanged: set,
                 observed: set, links: dict | None = None):
        self.system, self.instances, self.values = system, instances, {}
        self._sources = {(c.target, c.input): (c.source, c.output) for c in system.connections}
        feeds = {**self._sources, **{target: src for src, target in (links or {}).items()}}
        self._reads, self._observe, self._writes = {}, {}, {}
        for name, inst in instances.items():
            self._reads[name] = self._readers(inst, exchanged)
            self._observe[name] = self._readers(inst, observed - exchanged)
            inputs = sorted(i for t, i in feeds if t == name)
            self._writes[name] = [(inst.writer(group), [feeds[(name, i)] for i in group])
                                  for group in by_type(inst, inputs)]
        self._observe_all = [g for groups in self._observe.values() for g in groups]

    @staticmethod
    def _readers(inst: FmuInstance, keys: set):
        mine = sorted(v for i, v in keys if i == inst.name)
        return [(inst.reader(group), [(inst.name, v) for v in group])
                for group in by_type(inst, mine)]

    def _read(self, groups) -> None:
        values = self.values
        for read, keys in groups:
            new = read()
            total = sum(new)
            if total - total != 0:  # NaN or infinite among them (or a sum that overflowed)
                for key, value in zip(keys, new):
                    if value - value != 0:  # Strings are never read here
                        raise NonFiniteOutput(*key, value)
            values.update(zip(keys, new))

    def read_outputs(self, name: str) -> None:
        """Read the exchanged variables of the instance ``name`` after its step; an
        FMICallException raised here carries ``after_step`` = True (it concerns the values at
        the step's end)."""
        try:
            self._read(self._reads[name])
        except FMICallException as exc:
            exc.after_step = True
            raise

    def observe(self, name: str | None = None) -> None:
        """Read the observed-only variables of the instance ``name`` (default: of every one)."""
        self._read(self._observe_all if name is None else self._observe[name])

    def write_inputs(self, name: str) -> None:
        values = self.values
        for write, sources in self._writes[name]:
            write([values[s] for s in sources])

    def do_step(self, name: str, t: float, h: float) -> None:
        self.instances[name].do_step(t, h)

    def connected_inputs(self):
        return self._sources.items()

    def source_of(self, instance: str, variable: str):
        return self._sources.get((instance, variable))

    def writer(self, instance: str, variable: str):
        return self.instances[instance].writer([variable])

    def can_roll_back(self) -> bool:
        return all(i.can_get_set_state for i in self.instances.values())

    def save(self):
        return {n: i.get_state() for n, i in self.instances.items()}, dict(self.values)

    def restore(self, saved) -> None:
        states, values = saved
        for n, s in states.items():
            self.instances[n].set_state(s)
        self.values = values.copy()

    def free(self, saved) -> None:
        for n, s in saved[0].items():
            self.instances[n].free_state(s)

    def fmi_time(self) -> float:
        return sum(i.fmi_time for i in self.instances.values())


def by_type(inst: FmuInstance, names) -> list[list[str]]:
    """``names`` of ``inst``'s variables in groups of one type, Strings left out (one batched
    FMI call per group)."""
    groups = {}
    for n in names:
        groups.setdefault(inst.variable(n).type, []).append(n)
    return [g for t, g in groups.items() if t != "String"]


def recorded(system: System) -> list[str]:
    """The "<instance>.<variable>" a run of ``system`` records: its [record] list, by default
    every numeric output."""
    if system.record:
        return list(system.record)
    return [f"{i}.{v}" for i, vs in system.variables.items()
            for v, var in vs.items() if var.causality == "output" and var.type != "String"]


class Execution:
    """A system's FMUs instantiated (sources first), initialised, connected on a :class:`Bus` and
    stepped by the experiment's algorithm on demand: the one stepping loop, behind
    :func:`simulate` and the packed FMU (packed_fmu.py). ``observed``: further (instance,
    variable) that :meth:`Bus.observe` reads, or, ``with_outputs``, that are read with the
    exchanged outputs after every step (one FMI call fewer per instance and step where every step
    is observed); ``t`` [s] is where the instances are, ``steps``/``rejected`` count into
    ``result``."""

    def __init__(self, system: System, result: Result, observed: set = frozenset(),
                 with_outputs: bool = False):
        self.system, self.result, self.observed = system, result, set(observed)
        self.with_outputs = with_outputs
        self.algorithm_class = ALGORITHMS[system.experiment.algorithm]
        self.instances: dict[str, FmuInstance] = {}
        self.instantiating: tuple[str, float] | None = None  # (instance, perf_counter() [s])
        self.bus: Bus | None = None
        self.algorithm: Algorithm | None = None
        self.t, self.h = system.experiment.start, system.experiment.step

    def instantiate(self, stops: StopRequests) -> None:
        """Instantiate every FMU (SimulationError naming the instance and file if one fails, the
        result's error set)."""
        for name in order(self.system):
            comp = self.system.components[name]
            self.instantiating = (name, time.perf_counter())
            try:
                self.instances[name] = FmuInstance(comp.fmu, name)
            except Exception as exc:  # noqa: BLE001 - fmpy raises a bare Exception here
                self.result.error = (f"{self.system.name}: cannot instantiate {name} from "
                                     f"{comp.fmu}: {exc}")
                raise SimulationError(self.result.error, self.result) from exc
            finally:
                self.instantiating = None
            stops.check(None)

    def busy(self) -> tuple[str, str, float] | None:
        """(instance, FMI function, perf_counter() at its call [s]) of the FMI call in
        progress, None between calls (for the watchdog, from another thread)."""
        pending = self.instantiating
        if pending is not None:
            return pending[0], "fmi2Instantiate", pending[1]
        for name, inst in list(self.instances.items()):
            call = inst.busy
            if call is not None:
                return name, *call
        return None

    def stuck(self, name: str, function: str) -> str:
        """'FMU instance ... did not return from ...': the call ``function`` of ``name``, with
        the step it came in or after."""
        inst = self.instances.get(name)
        t = None if inst is None else inst.time
        where = ("the step at" if function == "fmi2DoStep" else
                 f"{function} during initialisation" if t is None else
                 f"{function} after the step at")
        return (f"FMU instance {name!r} did not return from {where}"
                + ("" if t is None else f" t = {t:.9g} s"))

    def initialise(self, stops: StopRequests, values: dict | None = None) -> None:
        """Initialise every instance with the scenario's parameters, then ``values`` ({instance:
        {parameter or input: value}}), then the algorithm's settings; outputs on the bus."""
        system = self.system
        cls = self.algorithm_class
        exchanged = {(c.source, c.output) for c in system.connections} | cls.exchanged(system)
        if self.with_outputs:
            exchanged |= self.observed
        self.bus = Bus(system, self.instances, exchanged, self.observed, cls.links(system))
        settings = cls.settings(system)
        _initialise(system, self.bus, {n: {**(values or {}).get(n, {}), **settings.get(n, {})}
                                       for n in self.instances}, stops)
        self.algorithm = cls(self.bus, system)

    def advance(self, until: float, stops: StopRequests, watchers=()) -> None:
        """Step from ``t`` to ``until`` [s] (a step that would pass it shortened to end there, one
        that ends there to round-off taken as it is, ``t`` then set to ``until``), notifying
        ``watchers`` after every accepted step; inputs set from outside are held. An
        FMICallException leaves with ``time`` [s]: that of the values concerned (the end of the
        step for an output read after it, the step's start else)."""
        exp, algorithm, bus, result = self.system.experiment, self.algorithm, self.bus, self.result
        eps = 1e-9 * exp.step
        t, h = self.t, self.h
        try:
            while t < until - eps:
                stops.check(t)
                h_try = h if t + h <= until + eps else until - t  # h itself when it ends there
                try:
                    accepted, h_next = algorithm.step(t, h_try)
                except FMICallException as exc:
                    exc.time = t + h_try if getattr(exc, "after_step", False) else t
                    raise
                if not accepted:
                    result.rejected += 1
                    h = h_next
                    continue
                result.steps += 1
                t = until if until - (t + h_try) <= eps else t + h_try
                h = h_next if exp.tolerance > 0 else exp.step
                try:
                    for w in watchers:
                        w.stepped(t, bus)
                except FMICallException as exc:  # a recorded-only output at t
                    exc.time = t
                    raise
        finally:
            self.t, self.h = t, h

    def close(self) -> FMICallException | None:
        """Terminate and free every instance and delete its extracted files; returns the first
        failed terminate (FmuInstance.close), after which no instance is called if it was
        fmi2Fatal."""
        first = None
        for inst in self.instances.values():
            if first is not None and first.status == FATAL:
                inst.fatal = True
            failed = inst.close()
            first = first or failed
        return first


def simulate(system: System, progress: bool = False, observers: tuple[Observer, ...] = (),
             results: str | Path | None = None,
             before_exit: Callable[[Result], None] | None = None) -> Result:
    """Run ``system`` from start to stop; raises SimulationError (with the partial result) when
    an FMI call fails (a step that cannot be retried, instantiation, initialisation, reading an
    output, terminating), the results cannot be written, or SIGINT/SIGTERM came (the run stops
    between steps, interrupts.py). ``observers`` are notified besides the recorder (and the progress bar
    when ``progress``). With ``results`` the recording streams to that CSV file as it is taken
    (recording.py). An FMI call that outlasts the experiment's ``step_timeout`` (watchdog.py),
    or that keeps the run from stopping GRACE_PERIOD after a signal (interrupts.py), ends the
    process after ``before_exit`` got the partial result."""
    exp = system.experiment
    record = recorded(system)
    recorder = Recorder(record, {r: system.unit(*r.split(".", 1)) for r in record},
                        system.record_interval, results,
                        {r: system.variable_description(*r.split(".", 1)) for r in record})
    watchers = [recorder, *([ProgressBar()] if progress else []), *observers]
    result = Result(system.name, exp.algorithm, Recording(*_empty(record)), {})
    execution = Execution(system, result, {tuple(r.split(".", 1)) for r in record},
                          with_outputs=exp.tolerance == 0 and system.record_interval <= exp.step)
    instances = execution.instances

    def abandon(why: str) -> None:  # in another thread, stuck in an FMU; the process then ends
        result.error = (f"{system.name}: {why}; the process ends without terminating or freeing "
                        "the FMU instances")
        recorder.close()
        result.recording, result.stored = recorder.recording(), recorder.stored()
        remove_unpacked()
        if before_exit is not None:
            try:
                before_exit(result)
            except OSError as exc:  # a full disk: the message still goes out
                result.error += f"\n{exc}"
        print(result.error, file=sys.stderr)

    def expired(name: str, function: str) -> None:
        abandon(f"{execution.stuck(name, function)} within the step timeout of "
                f"{exp.step_timeout:g} s")

    def unstopped(signum: int) -> None:
        call = execution.busy()
        abandon(f"interrupted by {signal.Signals(signum).name}, and "
                f"{execution.stuck(*call[:2]) if call else 'the run did not stop'} within the "
                f"grace period of {GRACE_PERIOD:g} s")

    error = signum = cause = None
    watchdog = (Watchdog(execution.busy, exp.step_timeout, expired)
                if exp.step_timeout < math.inf else nullcontext())
    with StopRequests(unstopped) as stops, watchdog:  # also while the instances are closed
        try:
            execution.instantiate(stops)
            execution.initialise(stops)
            result.parameters = {n: _parameters(inst) for n, inst in instances.items()}
            try:
                for w in watchers:
                    w.started(system, execution.bus)
            except FMICallException as exc:
                exc.time = exp.start
                raise
            _run(execution, watchers, stops)
        except FMICallException as exc:
            error, cause = failure(system.name, instances, exc), exc
        except StopRequested as exc:
            error, signum = f"{system.name}: {exc} {_when(exc)}", exc.signal
        except SimulationError as exc:  # an instance that could not be created
            error, cause = str(exc), exc.__cause__
        except RecordingError:
            pass  # recorder.error, below
        finally:
            unterminated = execution.close()
            recorder.close()
            result.recording, result.stored = recorder.recording(), recorder.stored()
    if error is None and unterminated is not None:  # a run that went well until fmi2Terminate
        unterminated.time = execution.t
        error, cause = failure(system.name, instances, unterminated), unterminated
    if recorder.error is not None:  # rows that could not be written, whatever else failed
        error = "\n".join(filter(None, [error, f"{system.name}: {recorder.error}"]))
        cause = cause or recorder.error
    if error is not None:
        result.error = error
        raise SimulationError(error, result, signum) from cause
    return result


def failure(system: str, instances: dict[str, FmuInstance], exc: FMICallException) -> str:
    """What failed, when, and the failing instance's log (every log when none is named); after
    fmi2Fatal every instance is marked so that closing makes no further call into it."""
    if exc.status == FATAL:  # no call into any instance after fmi2Fatal
        for inst in instances.values():
            inst.fatal = True
    failing = getattr(exc, "instance", None)
    logs = "\n".join(f"--- log of {n} ---\n{i.log_text()}" for n, i in instances.items()
                     if failing is None or n == failing)
    return f"{system}: FMU instance {failing!r} failed {_when(exc)}: {exc}\n{logs}"


def _when(exc) -> str:
    """Where the run was when ``exc`` came: the time it carries [s], else initialisation."""
    t = getattr(exc, "time", None)
    return "during initialisation" if t is None else f"at t = {t:.9g} s"


def _initialise(system: System, bus: Bus, settings: dict, stops: StopRequests) -> None:
    """Initialise every instance, sources first (inputs at start from their outputs), with the
    scenario's parameters and the algorithm's ``settings``."""
    exp = system.experiment
    for name in order(system):
        inst = bus.instances[name]
        inst.enter_initialisation(exp.start, {**system.components[name].parameters,
                                              **settings.get(name, {})}, exp.stop)
        _write_available(bus, name)
        inst.exit_initialisation()
        bus.read_outputs(name)
        stops.check(None)
    for name in bus.instances:
        bus.read_outputs(name)


def _write_available(bus: Bus, name: str) -> None:
    """Initial inputs whose sources are initialised already (others keep their start values)."""
    for (target, inp), src in bus.connected_inputs():
        if target == name and src in bus.values:
            bus.writer(name, inp)([bus.values[src]])


def _run(execution: Execution, watchers, stops: StopRequests) -> None:
    """Step from start to stop, timing the loop into the result; watchers finish either way."""
    result, bus = execution.result, execution.bus
    fmi0, wall0 = bus.fmi_time(), time.perf_counter()
    gc_was_on = gc.isenabled()
    gc.disable()  # the loop makes no reference cycles; full collections would cost ms each
    try:
        execution.advance(execution.system.experiment.stop, stops, watchers)
        stops.check(execution.t)  # a signal during the last step: the caller still wants to stop
    finally:
        if gc_was_on:
            gc.enable()
        result.wall_time = time.perf_counter() - wall0
        result.fmi_time = bus.fmi_time() - fmi0
        for w in watchers:
            w.finished(result)


def _parameters(inst: FmuInstance) -> dict:
    """Every parameter's value as the instance reports it after initialisation."""
    return {n: inst.get(n) for n, v in inst.variables.items() if v.causality == "parameter"}


def _empty(record):
    return np.array([]), {r: np.array([]) for r in record}, {r: "" for r in record}
