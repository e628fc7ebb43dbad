"""Common machinery of the guideway FMUs (pythonfmu slaves).

The rule: an FMU that logs an error returns a status other than fmi2OK from the FMI call that
met it; it never hands out NaN, nor stale values under fmi2OK. Every error is logged naming the
variable or the input that caused it, and printed on stderr (pythonfmu drops messages when
logging is off). pythonfmu 0.7 (its C++ wrapper: PySlaveInstance.cpp, fmi2.cpp) gives a Python
slave two statuses besides fmi2OK: ``do_step`` returning False is fmi2Discard (reported with
fmi2Terminated), and an exception raised in any call is fmi2Error in our Linux binaries
(fmu_build/error_patch.py; pythonfmu as shipped, and so our Windows binaries, report fmi2Fatal
and release the instance, after which FMI allows no call into the FMU). Getters and
``exit_initialization_mode`` have no other way to fail. Hence:

* setters only store values; parameters and inputs are checked when they are used;
* ``doStep`` with a bad parameter or input, or a model that fails over the step, returns
  fmi2Discard and leaves the state at the last successful communication point. FMI lets a host
  read the outputs there after a discarded step: until a step succeeds again (or an FMU state is
  set), a getter that cannot evaluate returns the outputs last evaluated;
* ``exit_initialization_mode`` sets the internal state from the parameters and inputs, and
  raises when it cannot;
* output getters evaluate the model from the current inputs (direct feedthrough), and raise
  when that fails or gives an output that is not finite, unless a discarded step came before
  (above); in Initialization Mode they first set the internal state from the present parameters
  and inputs, as leaving it will, so a host that records the initial outputs records what the
  first step starts from.

The modelDescription written by :meth:`to_xml` adds what pythonfmu leaves out: units with base
units for every Real variable, and ModelStructure with Outputs and InitialUnknowns listing the
inputs each output depends on. An instance starts its parameters and inputs at the start values
of the modelDescription.xml it is extracted with (pythonfmu alone starts them at the class's
defaults, whatever the XML says), so a copy of the FMU with other start values written into its
XML (``export-ssp``'s baked parameters) starts at those.
"""
from __future__ import annotations

import copy
import math
import sys
from pathlib import Path
from xml.etree import ElementTree
from xml.etree.ElementTree import Element, SubElement

from ..physics.dynamics import ContinuousModel
from .runtime import (Boolean, DefaultExperiment, Fmi2Causality, Fmi2Initial, Fmi2Slave,
                      Fmi2Status, Fmi2Variability, Integer, Real, String)
from .units import BASE_UNITS


#: the refusals the FMI layer words (fmu_build/native writes the native edition's from these):
#: a String parameter's value outside its choices, a step size, outputs that are not finite
CHOICE = "parameter {name} must be one of {choices}, got {value!r}"
STEP_SIZE = "communication step size must be > 0, got {step_size!r}"
NOT_FINITE = "outputs {outputs!r} are not finite at the present inputs"


class GuidewaySlave(Fmi2Slave):
    """Base class: typed variable registration, checking, lazy outputs and full state save."""

    author = "guideway-fmu"
    license = "MIT"
    version = "0.1.0"
    #: attribute names of internal state saved by get/set FMU state, besides the variables
    internal_state: tuple[str, ...] = ()
    #: "guideway": a subsystem of the roller guide; "diagnosis": a rig model or a candidate
    #: effect of the discrepancy workflow
    role = "guideway"
    #: why the component has no continuous-time model, where it has none (said by the reference)
    without_time_model = "it has none"
    #: what a host runs when the user gives no experiment: one 0.2 s feed cycle of the paper's
    #: rig at the 4 us step of its scenarios (components of other rigs state theirs)
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.2, step_size=4e-6)

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self._units: dict[str, str] = {}
        self._non_negative: list[str] = []
        self._inputs: list[str] = []
        self._input_refs: dict[int, str] = {}  # value reference -> name, Real inputs
        self._output_refs: dict[int, str] = {}  # value reference -> name, outputs
        self._depends: dict[str, tuple[str, ...]] = {}
        self._choices: dict[str, tuple[str, ...]] = {}  # String parameter -> its values
        self._outputs: dict[str, float] | None = None
        self._last_valid: dict[str, float] = {}
        self._model = None
        self._inputs_checked = False  # since the last input or parameter was set
        self._initialising = False
        self._discarded = False  # the last step was discarded (and no state set since)
        self._printed: str | None = None  # the error last printed, until a call succeeds
        self._described = _described_starts(self.resources)

    # -- registration -------------------------------------------------------------------
    def parameter(self, name: str, start, unit: str | None, description: str,
                  choices: tuple[str, ...] | None = None) -> None:
        """A tunable parameter: Real (with ``unit``), Boolean (bool start), Integer (int start) or
        String (str start); the modelDescription's start value replaces ``start`` where there is one.
        ``choices``: a String parameter that names a law takes one of these values (checked
        before the model is built; the native edition translates each law)."""
        start = self._start(name, start)
        if choices is not None:
            self._choices[name] = tuple(choices)
        setattr(self, name, start)
        kind = (String if isinstance(start, str) else Boolean if isinstance(start, bool)
                else Integer if isinstance(start, int) else Real)
        self.register_variable(kind(
            name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.tunable,
            description=description, getter=lambda: getattr(self, name),
            setter=lambda v: self._set(name, v, parameter=True)))
        if kind is Real:
            self._units[name] = unit

    def input(self, name: str, start: float, unit: str, description: str,
              non_negative: bool = False) -> None:
        """A Real input; ``non_negative`` inputs are refused below zero; the modelDescription's
        start value replaces ``start`` where there is one."""
        setattr(self, name, self._start(name, float(start)))
        self._inputs.append(name)
        if non_negative:
            self._non_negative.append(name)
        variable = Real(
            name, causality=Fmi2Causality.input, variability=Fmi2Variability.continuous,
            description=description, getter=lambda: getattr(self, name),
            setter=lambda v: self._set(name, v))
        self.register_variable(variable)
        self._input_refs[variable.value_reference] = name
        self._units[name] = unit

    def output(self, name: str, unit: str, description: str, depends: tuple[str, ...] = ()) -> None:
        """An output computed by :meth:`evaluate`; ``depends`` names the inputs it feeds through."""
        variable = Real(
            name, causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
            initial=Fmi2Initial.calculated, description=description,
            getter=lambda: self._output(name))
        self.register_variable(variable)
        self._output_refs[variable.value_reference] = name
        self._units[name] = unit
        self._depends[name] = tuple(depends)

    def _start(self, name: str, default):
        """The start value of ``name`` in the modelDescription (schema-valid XML text: xs:double,
        xs:int, xs:boolean or a string), of the type of ``default``; ``default`` without one."""
        text = self._described.get(name)
        if text is None or isinstance(default, str):
            return default if text is None else text
        if isinstance(default, bool):
            return text in ("true", "1")
        return type(default)(text)

    def _set(self, name, value, parameter=False):
        setattr(self, name, value)
        self._changed(parameter)

    def _changed(self, parameter=False) -> None:
        """Inputs (or a ``parameter``) were set: outputs, the input check (and the model) are stale."""
        self._outputs = None
        self._inputs_checked = False
        if parameter:
            self._model = None

    def parameter_values(self) -> dict:
        """The current parameters by name: the keywords of the physics' ``from_parameters``."""
        return {name: getattr(self, name) for name in self._variables_of(Fmi2Causality.parameter)}

    # -- to be provided by the components -----------------------------------------------
    @classmethod
    def continuous_model(cls, parameters: dict) -> ContinuousModel:
        """The component's physics as a continuous-time model (physics/dynamics.py) from its
        parameter values by name, validated (raise ValueError naming the parameter): what the
        FMU evaluates and steps and what the monolithic reference integrates."""
        raise NotImplementedError(f"{cls.__name__} has no continuous-time model: "
                                  f"{cls.without_time_model}")

    def build_model(self):
        """Build and validate the physics from the parameters (raise ValueError)."""
        return self.continuous_model(self.parameter_values())

    def check_inputs(self) -> None:
        """Raise ValueError naming the first input that is non-finite or out of range."""
        for name in self._inputs:
            value = getattr(self, name)
            if not math.isfinite(value):
                raise ValueError(f"input {name} must be finite, got {value!r}")
            if name in self._non_negative and value < 0.0:
                raise ValueError(f"input {name} must be >= 0, got {value!r}")

    def model_inputs(self) -> dict[str, float]:
        """The present values of the inputs the continuous-time model reads."""
        return {name: getattr(self, name) for name in self.model().inputs}

    def evaluate(self) -> dict[str, float]:
        """Outputs from the current inputs (a stateless model; stateful components override)."""
        return self.model().outputs(0.0, (), self.model_inputs())

    def advance(self, t: float, h: float) -> None:
        """Integrate the internal state from t to t + h [s] (stateless components: nothing)."""

    def initialise(self) -> None:
        """Set the internal state from parameters and inputs when initialization mode ends."""

    # -- FMI calls ----------------------------------------------------------------------
    def choices(self, name: str) -> tuple[str, ...] | None:
        """The values the String parameter ``name`` chooses among, None when it is free text."""
        return self._choices.get(name)

    def model(self):
        if self._model is None:
            for name, choices in self._choices.items():
                if getattr(self, name) not in choices:
                    raise ValueError(CHOICE.format(name=name, choices=choices,
                                                   value=getattr(self, name)))
            self._model = self.build_model()
        return self._model

    def _checked(self, action):
        """``action()`` with the model built and the inputs checked."""
        self.model()
        if not self._inputs_checked:  # once per set of inputs: a step and its outputs share it
            self.check_inputs()
            self._inputs_checked = True
        return action()

    def _report(self, exc: Exception) -> None:
        """Log the failure ``exc`` (the project's errors name what failed; others their type)."""
        self._error(str(exc) if isinstance(exc, (ValueError, RuntimeError))
                    else f"{type(exc).__name__}: {exc}")

    def _error(self, message: str) -> None:
        """Log ``message`` as an error (every failing call says why), and print it on stderr:
        pythonfmu 0.7 drops every message when the host instantiated the FMU with logging off,
        and the cause must reach the user, once (leaving initialisation, the outputs and the step
        meet a bad parameter in turn): not again until a call succeeds."""
        self.log(f"{self.instance_name}: {message}", Fmi2Status.error)
        if message != self._printed:
            self._printed = message
            print(f"{type(self).__name__} {self.instance_name}: {message}", file=sys.stderr)

    def enter_initialization_mode(self):
        self._initialising = True

    def exit_initialization_mode(self):
        self._initialising = False
        self._outputs = None
        try:
            self._checked(self.initialise)
        except Exception as exc:
            self._report(exc)
            raise  # fmi2Error (module doc)
        self._printed = None

    def do_step(self, current_time: float, step_size: float) -> bool:
        self._outputs = None
        try:
            if not (math.isfinite(step_size) and step_size > 0.0):
                raise ValueError(STEP_SIZE.format(step_size=step_size))
            self._checked(lambda: self.advance(current_time, step_size))
        except Exception as exc:  # noqa: BLE001 - a failed step is discarded, not an error
            self._report(exc)
            self._discarded = True
            return False  # fmi2Discard
        self._discarded, self._printed = False, None
        return True

    # pythonfmu's get_real and set_real, which its C side calls by name, pass each variable
    # through its getter or setter; a batch of outputs alone (or of Real inputs alone), what a
    # master exchanges every step, is served here from one evaluation (one invalidation).
    def get_real(self, vrs):
        try:
            names = [self._output_refs[vr] for vr in vrs]
        except KeyError:
            return super().get_real(vrs)
        values = self._evaluated()
        return [float(values.get(name, 0.0)) for name in names]

    def set_real(self, vrs, values):
        try:
            names = [self._input_refs[vr] for vr in vrs]
        except KeyError:
            return super().set_real(vrs, values)
        for name, value in zip(names, values):
            setattr(self, name, value)
        self._changed()

    def _output(self, name: str) -> float:
        return float(self._evaluated().get(name, 0.0))

    def _evaluated(self) -> dict[str, float]:
        """The outputs by name, evaluated from the present inputs; after a discarded step, where
        they cannot be, those last evaluated (module doc). Raises otherwise."""
        if self._outputs is None:
            try:
                self._outputs = self._last_valid = self._checked(self._evaluate)
                self._printed = None
            except Exception as exc:
                if not (self._discarded and self._last_valid):
                    self._report(exc)
                    raise  # fmi2Error (module doc)
                self._outputs = self._last_valid  # the outputs at the last successful time
        return self._outputs

    def _evaluate(self) -> dict[str, float]:
        """:meth:`evaluate`, in Initialization Mode from the state initialisation will set;
        ValueError naming the outputs that are not finite."""
        if self._initialising:  # the outputs as initialization will leave them
            self.initialise()
        values = self.evaluate()
        # a finite sum has finite terms; only an overflowing or non-finite one needs a look
        if math.isfinite(sum(values.values())) or all(math.isfinite(v) for v in values.values()):
            return values
        bad = {k: v for k, v in values.items() if not math.isfinite(v)}
        raise ValueError(NOT_FINITE.format(outputs=bad))

    # -- FMU state ----------------------------------------------------------------------
    def _get_fmu_state(self):
        state = {name: getattr(self, name) for name in self._variables_of(
            Fmi2Causality.parameter, Fmi2Causality.input)}
        state["__internal__"] = copy.deepcopy({k: getattr(self, k) for k in self.internal_state})
        state["__last_valid__"] = dict(self._last_valid)
        return state

    def _set_fmu_state(self, state):
        for name, value in state.items():
            if name == "__internal__":
                for k, v in value.items():
                    setattr(self, k, copy.deepcopy(v))
            elif name == "__last_valid__":
                self._last_valid = dict(value)
            else:
                setattr(self, name, value)
        self._discarded = False
        self._changed(parameter=True)

    # -- modelDescription ---------------------------------------------------------------
    def _variables_of(self, *causalities):
        return [v.name for v in self.vars.values() if v.causality in causalities]

    def to_xml(self, model_options=dict()) -> Element:
        root = super().to_xml(model_options)
        index = {v.name: i + 1 for i, v in enumerate(self.vars.values())}
        for node in root.find("ModelVariables"):
            real = node.find("Real")
            if real is not None:
                real.set("unit", self._units[node.get("name")])
        units = Element("UnitDefinitions")
        for name in sorted(set(self._units.values())):
            SubElement(SubElement(units, "Unit", name=name), "BaseUnit",
                       {k: str(e) for k, e in BASE_UNITS[name].items()})
        root.insert(list(root).index(root.find("CoSimulation")) + 1, units)
        root.remove(root.find("ModelStructure"))
        structure = SubElement(root, "ModelStructure")
        for section in ("Outputs", "InitialUnknowns"):
            node = SubElement(structure, section)
            for name, deps in self._depends.items():
                SubElement(node, "Unknown", index=str(index[name]),
                           dependencies=" ".join(str(index[d]) for d in deps))
        return root


def _described_starts(resources: str | None) -> dict[str, str]:
    """Start values (XML text) by variable name of the modelDescription.xml beside the FMU's
    ``resources`` folder; none when the class is instantiated outside an extracted FMU (as the
    build does)."""
    if resources is None or Path(resources).name != "resources":
        return {}
    xml = Path(resources).parent / "modelDescription.xml"
    if not xml.is_file():
        return {}
    return {v.get("name"): typed.get("start") for v in ElementTree.parse(xml).getroot().iter("ScalarVariable")
            for typed in v if typed.get("start") is not None}
