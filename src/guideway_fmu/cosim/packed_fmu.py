"""The slave of a packed FMU (export_fmu.py): a scenario's system inside one FMI 2.0 CS FMU.

The FMU's package carries the scenario (``packed/system.toml``, FMUs by file name) and its
FMUs (``packed/*.fmu``). Its variables, all named ``<instance>.<variable>`` with the inner
FMU's type, unit and description:

* parameters: every parameter of every instance (variability fixed: applied when
  initialisation ends), starting at the scenario's value, else at the inner FMU's start;
* inputs: the inputs that neither a connection nor the coupling algorithm feeds (tangent
  links), starting at the scenario's value, else at the inner FMU's start;
* outputs: every numeric output of every instance, no direct feedthrough (an input set at a
  communication point acts over the next step; the outputs are those at the point).

Life cycle: instantiation extracts and instantiates the inner FMUs (each into its own
``guideway-fmu-*`` temporary folder, fmu_instance.py); leaving initialisation initialises them
with the parameters and inputs as set; each ``doStep(t, H)`` holds the inputs over the interval
while our master (master.Execution: the scenario's algorithm, step and step-size control) steps
the system to t + H, ending its last inner step there; terminate (or freeing the instance)
terminates and frees the inner instances and deletes their folders. A non-finite input, an inner
FMU that fails or refuses a parameter: fmi2Discard with a logged message naming it (pythonfmu
can return no other failure status without ending the process's instances). Its FMU state
(:class:`Snapshot`) holds its inner instances' states: it can get and set it where they all can
(export_fmu.py declares it so).
"""
from __future__ import annotations

import math
import re
import sys
import weakref
from pathlib import Path
from xml.etree.ElementTree import Element, SubElement

import numpy as np
from fmpy.fmi1 import FMICallException

from ..components.runtime import (Boolean, DefaultExperiment, Fmi2Causality, Fmi2Initial,
                                  Fmi2Slave, Fmi2Status, Fmi2Variability, Integer, Real, String)
from .algorithms import ALGORITHMS
from .interrupts import StopRequests
from .fmu_instance import FATAL
from .master import Execution, Result, SimulationError, by_type, failure
from .recording import Recording
from .ssp import base_units
from .system import load, typed

DATA = "packed"  # the package's folder holding the scenario and its FMUs
#: never entered, so no signal stops the inner master: the host's signals are the host's
NEVER = StopRequests()
SCENARIO = "system.toml"
_TYPES = {"Real": Real, "Integer": Integer, "Enumeration": Integer, "Boolean": Boolean,
          "String": String}


def data_folder(resources: str) -> Path:
    """The folder of the scenario and FMUs in the package this module was copied into, under
    the instance's ``resources`` (not beside this module's file: a module stays imported from
    the folder of the first instance, which its host may have deleted since)."""
    return Path(resources) / __name__.split(".", 1)[0] / DATA


def model_identifier(name: str) -> str:
    """A C identifier from a scenario's name (the packed FMU's modelName and binary's name)."""
    ident = re.sub(r"\W", "_", name, flags=re.ASCII)
    return ident if re.match(r"[A-Za-z_]", ident) else f"_{ident}"


def fed_inputs(system) -> set[tuple[str, str]]:
    """(instance, input) that a connection or the algorithm's links feed."""
    links = ALGORITHMS[system.experiment.algorithm].links(system)
    return {(c.target, c.input) for c in system.connections} | set(links.values())


class PackedSystem(Fmi2Slave):
    """A scenario's connected system run by the master (module doc)."""

    author = "guideway-fmu"
    license = "MIT"
    version = "0.1.0"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.system = load(data_folder(self.resources) / SCENARIO)
        exp = self.system.experiment
        self.modelName = model_identifier(self.system.name)
        self.description = (f"The system of scenario {self.system.name} run by guideway-fmu's "
                            f"master ({exp.algorithm}, step {exp.step:g} s)")
        self.default_experiment = DefaultExperiment(exp.start, exp.stop, exp.step)
        self.values: dict[str, object] = {}  # "<instance>.<variable>" -> value
        self.inputs: list[tuple[str, str]] = []
        self.outputs: list[tuple[str, str]] = []
        self.parameters: list[tuple[str, str]] = []
        self.units: dict[str, str] = {}
        self.start, self.stop = exp.start, exp.stop
        fed = fed_inputs(self.system)
        for inst, variables in self.system.variables.items():
            given = self.system.components[inst].parameters
            for v in variables.values():
                key = (inst, v.name)
                if v.causality == "parameter" or v.causality == "input" and key not in fed:
                    start = given.get(v.name, None if v.start is None else typed(v, v.start))
                    self._register(key, v, start)
                    (self.parameters if v.causality == "parameter" else self.inputs).append(key)
                elif v.causality == "output" and v.type != "String":
                    self._register(key, v, typed(v, v.start or "0"))
                    self.outputs.append(key)
        self._input_names = [".".join(k) for k in self.inputs]
        self._outputs_of: dict[str, list] = {}  # instance -> [(bus key, name)] of its outputs
        for key in self.outputs:
            self._outputs_of.setdefault(key[0], []).append((key, ".".join(key)))
        self._stale: set[str] = set()  # instances whose outputs changed since last read
        self._write = None  # the batched writers of the inputs, made at the first change
        self._held: list = []  # the input values last written to the inner instances
        self.execution: Execution | None = None
        self._ready = False  # the inner system initialised
        if Path(self.resources or "").name == "resources":  # in an extracted FMU, not the build
            result = Result(self.system.name, exp.algorithm, Recording(np.array([]), {}, {}), {})
            self.execution = Execution(self.system, result, set(self.outputs))
            try:
                self.execution.instantiate(NEVER)
            except SimulationError:
                self.close()  # the instances made so far; pythonfmu then reports no instance
                raise

    def _register(self, key, v, start) -> None:
        name = ".".join(key)
        self.values[name] = start
        causality = Fmi2Causality[v.causality]
        options = ({"variability": Fmi2Variability.fixed} if v.causality == "parameter" else
                   {"variability": Fmi2Variability.continuous if v.type == "Real"
                    else Fmi2Variability.discrete})
        if v.causality == "output":
            options["initial"] = Fmi2Initial.calculated
        # no reference to self (a cycle would keep the instance, and its inner instances, alive
        # after fmi2FreeInstance until a garbage collection)
        me, values = weakref.ref(self), self.values
        getter = ((lambda: me()._output(key[0], name)) if v.causality == "output"
                  else lambda: values[name])
        self.register_variable(_TYPES[v.type](
            name, causality=causality, description=v.description, getter=getter,
            setter=None if v.causality == "output" else lambda x: values.__setitem__(name, x),
            **options))
        if v.type == "Real" and v.unit:
            self.units[name] = v.unit

    # -- FMI calls ------------------------------------------------------------------------
    def setup_experiment(self, start_time, stop_time, tolerance):
        self.start = start_time
        if stop_time is not None and stop_time > start_time:
            self.stop = stop_time

    def exit_initialization_mode(self):
        self._ready = self._guarded(self._initialise)

    def _initialise(self) -> None:
        """Initialise the inner instances with the experiment, parameters and inputs as set."""
        exp = self.system.experiment
        if (self.start, self.stop) != (exp.start, exp.stop):
            self.execution.system = self.system.with_changes(start=self.start, stop=self.stop)
            self.execution.t = self.start
        given: dict[str, dict] = {}
        for inst, var in self.parameters + self.inputs:
            value = self.values[f"{inst}.{var}"]
            if value is not None:
                given.setdefault(inst, {})[var] = value
        self.execution.initialise(NEVER, given)
        self._held = [given.get(i, {}).get(v) for i, v in self.inputs]

    def _writers(self) -> list:
        """(batched writer, names in self.values) per inner instance and type of the inputs."""
        instances = self.execution.instances
        return [(instances[inst].writer(group), [f"{inst}.{v}" for v in group])
                for inst in dict.fromkeys(i for i, _ in self.inputs)
                for group in by_type(instances[inst], [v for i, v in self.inputs if i == inst])]

    def do_step(self, current_time: float, step_size: float) -> bool:
        if not self._ready:
            self._error("the inner system is not initialised, failed fatally or was "
                        "terminated (see the messages before)")
            return False
        at = self.execution.t
        if abs(current_time - at) > 1e-9 * self.system.experiment.step:
            self._error(f"a step from t = {current_time!r} s, but the system is at t = {at!r} s")
            return False
        held = [self.values[n] for n in self._input_names]
        if held != self._held:  # (a NaN never equals itself: always checked)
            bad = next((n for n, x in zip(self._input_names, held)
                        if isinstance(x, float) and not math.isfinite(x)), None)
            if bad is not None:
                self._error(f"input {bad} must be finite, got {self.values[bad]!r}")
                return False
        if not (math.isfinite(step_size) and step_size > 0.0):
            self._error(f"communication step size must be > 0, got {step_size}")
            return False
        return self._guarded(lambda: self._advance(held, current_time + step_size))

    def _advance(self, held: list, until: float) -> None:
        """Hold the inputs at ``held`` (written to the inner instances if they changed) and step
        the system to ``until`` [s]."""
        if held != self._held:
            if self._write is None:
                self._write = self._writers()
            for write, names in self._write:
                write([self.values[n] for n in names])
            self._held = held
        self.execution.advance(until, NEVER)

    def _output(self, inst: str, name: str):
        """An output's value, the outputs of its instance read from it first if it stepped
        since; when that read fails (a non-finite value), the error logged and the last values
        kept (a getter that raised would be fmi2Fatal for every instance of the process)."""
        if inst in self._stale:
            self._stale.discard(inst)
            try:
                self.execution.bus.observe(inst)
            except FMICallException as exc:
                self._error(failure(self.system.name, self.execution.instances, exc))
            else:
                values = self.execution.bus.values
                for key, full in self._outputs_of[inst]:
                    self.values[full] = values[key]
        return self.values[name]

    def _guarded(self, action) -> bool:
        """``action()``, the outputs then to be read again; False with the failure logged if it
        fails."""
        if self.execution is None:
            self._error("no inner system: the instance was terminated")
            return False
        try:
            action()
            self._stale.update(self._outputs_of)
            return True
        except FMICallException as exc:
            self._error(failure(self.system.name, self.execution.instances, exc))
            if exc.status == FATAL:  # no further call into the inner instances
                self._ready = False
        except (SimulationError, ValueError, KeyError, TypeError) as exc:
            self._error(str(exc))
        return False

    def _error(self, message: str) -> None:
        """Log ``message`` as an error and print it on stderr (pythonfmu drops messages when
        logging is off)."""
        self.log(f"{self.instance_name}: {message}", Fmi2Status.error)
        print(f"{self.modelName} {self.instance_name}: {message}", file=sys.stderr)

    def terminate(self):
        self.close()

    def close(self) -> None:
        """Terminate and free the inner instances and delete their folders (once)."""
        if getattr(self, "execution", None) is not None:  # None: __init__ failed or closed
            self.execution.close()
            self.execution = None
            self._ready = False
            self._stale.clear()  # the outputs keep their last values

    def __del__(self):  # fmi2FreeInstance without fmi2Terminate (pythonfmu releases the instance)
        self.close()

    # -- FMU state ----------------------------------------------------------------------------
    def _get_fmu_state(self) -> "Snapshot":
        return Snapshot(self)

    def _set_fmu_state(self, state: "Snapshot") -> None:
        state.restore(self)

    # -- modelDescription -------------------------------------------------------------------
    def to_xml(self, model_options=dict()) -> Element:
        root = super().to_xml(model_options)
        for node in root.find("ModelVariables"):
            if node.get("name") in self.units:
                node.find("Real").set("unit", self.units[node.get("name")])
        used = {}
        for name, unit in self.units.items():
            used.setdefault(unit, {})[name.split(".", 1)[0]] = None
        units = Element("UnitDefinitions")
        for unit, base in sorted(base_units(self.system, used).items()):
            SubElement(SubElement(units, "Unit", name=unit), "BaseUnit", base)
        root.insert(list(root).index(root.find("CoSimulation")) + 1, units)
        root.remove(root.find("ModelStructure"))
        structure = SubElement(root, "ModelStructure")
        index = {v.name: i + 1 for i, v in enumerate(self.vars.values())}
        for section in ("Outputs", "InitialUnknowns"):
            node = SubElement(structure, section)
            for inst, var in self.outputs:  # initially: on every parameter and input
                SubElement(node, "Unknown", index=str(index[f"{inst}.{var}"]),
                           **({"dependencies": ""} if section == "Outputs" else {}))
        return root


class Snapshot:
    """The state of a packed FMU instance (fmi2GetFMUstate): its inner instances' FMU states
    (once initialised), where its master is, its variables and the inputs last written. pythonfmu
    releases it at fmi2FreeFMUstate, which frees the inner states (unless the instance is gone,
    and its inner instances with them)."""

    def __init__(self, packed: PackedSystem):
        execution = packed.execution
        self.owner, self.execution = weakref.ref(packed), execution
        self.inner = execution.bus.save() if packed._ready else None
        self.t, self.h = (execution.t, execution.h) if execution is not None else (None, None)
        self.values, self.held, self.stale = dict(packed.values), list(packed._held), set(packed._stale)

    def restore(self, packed: PackedSystem) -> None:
        """Put ``packed`` back into this state (logged error if it is another instance's)."""
        execution = packed.execution
        if execution is not self.execution or (self.inner is None) == packed._ready:
            packed._error("fmi2SetFMUstate: the state is not one of this instance in its "
                          "present mode; nothing restored")
            return
        if self.inner is not None:
            execution.bus.restore(self.inner)
            execution.t, execution.h = self.t, self.h
        packed.values.update(self.values)
        packed._held, packed._stale = list(self.held), set(self.stale)

    def __del__(self):
        packed = self.owner()
        if self.inner is not None and packed is not None and packed.execution is self.execution:
            self.execution.bus.free(self.inner)
