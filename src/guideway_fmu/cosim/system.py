"""System description: components (FMUs), connections, tangents, experiment, recording, plots.

Read from a TOML scenario (:func:`load`), or built in code (:class:`Builder`), and checked
against each FMU's modelDescription before anything is instantiated; every error names the file,
the table and the key. :func:`dump` writes a system back as TOML that :func:`load` reads to an
equal system: the one scenario writer. The format (tables and keys, all SI units)::

    name = "..."                    # optional, defaults to the file stem
    description = "..."             # optional

    [experiment]
    start = 0.0                     # s
    stop = 0.2                      # s
    step = 2e-6                     # s, macro step (the initial one for adaptive algorithms)
    algorithm = "stabilised"        # a name of cosim/algorithms.py ALGORITHMS: "jacobi",
                                    #   "gauss-seidel" or "stabilised"
    tolerance = 0.0                 # stabilised only: > 0 turns on step-size control (module doc
    min_step = 1e-8                 #   of stabilised.py); min_step/max_step bound the step [s]
    max_step = 1e-4
    step_timeout = 60.0             # optional, s of wall time: an FMI call of any FMU (its
                                    #   instantiation, initialisation, a step, ...) that takes
                                    #   longer ends the run (cosim/watchdog.py); default: no limit

    [components.Contact]            # one table per instance; the key is the instance name:
                                    #   not empty, no '.', no control character, no white
                                    #   space at either end
    fmu = "../../fmus/ContactEHL.fmu"   # relative to this file, or looked up in --fmus
    parameters = { preload = 9200.0 }   # parameters (or inputs' start values) by name

    [[connections]]
    from = "Carriage.y"                 # <instance>.<output>
    to = "Contact.y"                # <instance>.<input>

    [[tangents]]                    # stiff loops: the stabilised algorithm only
    force = "Contact.F_contact"     # feedthrough output of the stiff component
    position = "Contact.y"          # the input it depends on (stiffness = dforce/dposition)
    stiffness = "Contact.K_contact" # an output, or "fd" for a finite difference by the master
    to_stiffness = "Carriage.K_contact" # the consumer's input that takes the stiffness
    velocity = "Contact.y_dot"      # optional: the same for the damping dforce/dvelocity
    damping = "Contact.C_contact"
    to_damping = "Carriage.C_contact"
    model = { law_force_1um = "Carriage.law_force_1um" }   # optional: further outputs of the force's
                                    #   instance (an interface model of the force over the step,
                                    #   such as its law) -> consumer inputs
    settings = { interpolate_inputs = true }   # optional: parameters of the force's instance
                                    #   that this coupling needs, set at initialisation

    [record]
    variables = ["Contact.F_upper"] # optional; default: every output of every component
    interval = 1e-5                 # optional, s: record every macro step not closer than this

    [plots]                         # optional; each a list of <instance>.<variable>
    time = ["Carriage.y"]               # time histories
    spectrum = ["Carriage.y"]           # FFT amplitude spectra
    film = ["Contact.h_upper"]      # film thickness histories (in micrometres)
    envelope = ["Contact.F_upper"]  # running max/min over `window`
    skip = 0.01                     # s of transient left out of the spectra
    window = 1e-3                   # s, envelope window
    f_max = 20000.0                 # Hz, upper end of the spectrum plots

The clock's resolution: ``step`` (and, with ``tolerance`` > 0, ``min_step``) must be at least
STEP_RESOLUTION (2^20) float spacings at the experiment's largest time, max(|start|, |stop|),
so that t + h advances with each step's length represented to about 1e-6 of itself; a smaller
one would make no progress (t + h == t) or steps of arbitrary length.
"""
from __future__ import annotations

import math
import os
import tomllib
from dataclasses import dataclass, field, fields
from pathlib import Path

import tomli_w
from fmpy import read_model_description

PLOT_KINDS = ("time", "spectrum", "film", "envelope")
PLOT_OPTIONS = ("skip", "f_max", "window")  # s, Hz, s: see cosim/plots.py
STEP_RESOLUTION = 2**20  # float spacings at the largest time a step spans at least (module doc)


class ScenarioError(ValueError):
    """A scenario that cannot be used; the message names the file, table and key."""


@dataclass(frozen=True)
class Component:
    """An FMU instance: its name, FMU file and the parameter values to apply."""

    name: str
    fmu: Path
    parameters: dict


@dataclass(frozen=True)
class Connection:
    """Output ``source.output`` feeds input ``target.input``."""

    source: str
    output: str
    target: str
    input: str


@dataclass(frozen=True)
class Tangent:
    """The linearisation of a stiff feedthrough output that the stabilised algorithm passes on.

    ``stiffness``/``damping`` are output names of the force's instance, or "fd" for a central
    finite difference of ``force`` over ``position``/``velocity`` taken by the master. ``model``
    pairs further outputs of that instance with the consumer inputs they feed, ``settings`` its
    parameters with the values the coupling needs; both only under the stabilised algorithm.
    """

    instance: str
    force: str
    position: str
    stiffness: str
    to_stiffness: tuple[str, str]
    velocity: str | None = None
    damping: str | None = None
    to_damping: tuple[str, str] | None = None
    model: tuple[tuple[str, tuple[str, str]], ...] = ()
    settings: tuple[tuple[str, object], ...] = ()


@dataclass(frozen=True)
class Experiment:
    start: float = 0.0
    stop: float = 1.0
    step: float = 1e-3
    algorithm: str = "gauss-seidel"
    tolerance: float = 0.0
    min_step: float = 1e-9
    max_step: float = math.inf
    step_timeout: float = math.inf  # s of wall time per FMI call


@dataclass(frozen=True)
class System:
    """A checked system description; ``variables`` maps instance -> {name: ScalarVariable}."""

    name: str
    path: Path | None
    components: dict[str, Component]
    connections: tuple[Connection, ...]
    experiment: Experiment
    tangents: tuple[Tangent, ...] = ()
    record: tuple[str, ...] = ()
    record_interval: float = 0.0
    plots: dict = field(default_factory=dict)
    description: str = ""
    variables: dict = field(default_factory=dict, repr=False)
    feedthrough: dict = field(default_factory=dict, repr=False)  # instance -> {output: bool}

    def unit(self, instance: str, variable: str) -> str:
        return self.variables[instance][variable].unit or ""

    def variable_description(self, instance: str, variable: str) -> str:
        """The FMU's description of the variable ("" if it gives none)."""
        return self.variables[instance][variable].description or ""

    def with_changes(self, fmus: dict[str, Path] | None = None,
                     parameters: dict[str, dict] | None = None, **experiment) -> "System":
        """A copy with some FMU files replaced (instance -> path), some parameters set
        (instance -> {parameter: value}) and experiment fields changed; the copy is checked as
        a loaded scenario is (an unknown instance or field is an error naming it)."""
        unknown = sorted(set(parameters or {}) - set(self.components))
        if unknown:
            raise ScenarioError(f"{self.path or self.name}: no component {unknown[0]!r} to set "
                                f"parameters of; the components are {sorted(self.components)}")
        comps = {n: Component(n, Path((fmus or {}).get(n, c.fmu)),
                              {**c.parameters, **(parameters or {}).get(n, {})})
                 for n, c in self.components.items()}
        exp = Experiment(**{**self.experiment.__dict__, **experiment})
        return check(System(self.name, self.path, comps, self.connections, exp, self.tangents,
                            self.record, self.record_interval, self.plots, self.description),
                     str(self.path or self.name))


# -- building and writing --------------------------------------------------------------------
def _ref(text: str, what: str) -> tuple[str, str]:
    instance, dot, variable = text.partition(".")
    if not (instance and dot and variable):
        raise ScenarioError(f"{what} must be '<instance>.<variable>', got {text!r}")
    return instance, variable


class Builder:
    """A system built in code, the inverse of reading a TOML file::

        b = Builder("rig", "what it shows").experiment(stop=0.2, step=2e-6)
        b.component("Feed", "fmus/FeedKinematics.fmu", profile="biharmonic")
        b.connect("Feed.u", "Contact.u")
        system = b.system()          # checked against the FMUs
        dump(b.system(check=False), "rig.toml")

    Methods return the builder, so calls chain. Keys and meanings are those of the TOML format
    (module doc). FMU paths are taken as given: :meth:`system` checks them from the working
    directory, :func:`dump` writes a relative one as the path from the scenario file.
    """

    def __init__(self, name: str, description: str = ""):
        self.name, self.description = name, description
        self._experiment = Experiment()
        self._components: dict[str, Component] = {}
        self._connections: list[Connection] = []
        self._tangents: list[Tangent] = []
        self._record: tuple[str, ...] = ()
        self._interval = 0.0
        self._plots: dict = {}

    def experiment(self, **values) -> "Builder":
        """Set fields of the experiment (start, stop, step, algorithm, tolerance, ...)."""
        self._experiment = Experiment(**{**self._experiment.__dict__, **values})
        return self

    def component(self, name: str, fmu, **parameters) -> "Builder":
        """Add the instance ``name`` of the FMU file ``fmu`` with parameter (or input start)
        values (numpy scalars become Python ones)."""
        plain = {k: v.item() if hasattr(v, "item") else v for k, v in parameters.items()}
        self._components[name] = Component(name, Path(fmu), plain)
        return self

    def connect(self, source: str, target: str) -> "Builder":
        """Feed the input ``target`` ("<instance>.<input>") from the output ``source``."""
        self._connections.append(Connection(*_ref(source, "from"), *_ref(target, "to")))
        return self

    def tangent(self, force: str, position: str, stiffness: str, to_stiffness: str,
                velocity: str | None = None, damping: str | None = None,
                to_damping: str | None = None, model: dict | None = None,
                settings: dict | None = None) -> "Builder":
        """Declare a stiff loop for the stabilised coupling (keys as in [[tangents]])."""
        instance, force_name = _ref(force, "force")

        def own(text):  # an output or input of the force's instance, or "fd"
            return text if text in (None, "fd") else _ref(text, "tangent variable")[1]

        self._tangents.append(Tangent(
            instance, force_name, own(position), own(stiffness), _ref(to_stiffness, "to_stiffness"),
            own(velocity), own(damping), to_damping and _ref(to_damping, "to_damping"),
            tuple((out, _ref(target, "model")) for out, target in (model or {}).items()),
            tuple((settings or {}).items())))
        return self

    def record(self, variables=(), interval: float = 0.0) -> "Builder":
        """Record these "<instance>.<variable>" (default: every output) every ``interval`` [s]."""
        self._record, self._interval = tuple(variables), interval
        return self

    def plots(self, **entries) -> "Builder":
        """Plot lists by kind (time, spectrum, film, envelope) and their options."""
        self._plots.update(entries)
        return self

    def system(self, path: str | Path | None = None, check_fmus: bool = True) -> System:
        """The system; checked against the FMUs unless ``check_fmus`` is False."""
        system = System(self.name, None if path is None else Path(path), dict(self._components),
                        tuple(self._connections), self._experiment, tuple(self._tangents),
                        self._record, self._interval, dict(self._plots), self.description)
        return check(system, str(path or self.name)) if check_fmus else system


def dump(system: System, path: str | Path, header: str = "") -> Path:
    """Write ``system`` as a TOML scenario at ``path`` that :func:`load` reads back to an equal
    system. An absolute FMU path is written relative to the file's folder, a relative one as it
    is (:func:`load` reads it relative to the file). ``header``: comment lines."""
    path = Path(path)
    default = Experiment()
    data = {"name": system.name}
    if system.description:
        data["description"] = system.description
    data["experiment"] = {f.name: getattr(system.experiment, f.name) for f in fields(Experiment)
                          if getattr(system.experiment, f.name) != getattr(default, f.name)}
    data["components"] = {
        name: {"fmu": _relative(Path(c.fmu), path.parent),
               **({"parameters": dict(c.parameters)} if c.parameters else {})}
        for name, c in system.components.items()}
    if system.connections:
        data["connections"] = [{"from": f"{c.source}.{c.output}", "to": f"{c.target}.{c.input}"}
                               for c in system.connections]
    if system.tangents:
        data["tangents"] = [_tangent_table(t) for t in system.tangents]
    record = {"variables": list(system.record)} if system.record else {}
    if system.record_interval:
        record["interval"] = system.record_interval
    if record:
        data["record"] = record
    if system.plots:
        data["plots"] = dict(system.plots)
    text = "".join(f"# {line}\n" for line in header.splitlines()) + tomli_w.dumps(data)
    path.write_text(text)
    return path


def _relative(fmu: Path, folder: Path) -> str:
    return (Path(os.path.relpath(fmu, folder.resolve())) if fmu.is_absolute() else fmu).as_posix()


def _tangent_table(t: Tangent) -> dict:
    def own(name):
        return name if name == "fd" else f"{t.instance}.{name}"

    table = {"force": own(t.force), "position": own(t.position), "stiffness": own(t.stiffness),
             "to_stiffness": ".".join(t.to_stiffness)}
    if t.velocity:
        table.update(velocity=own(t.velocity), damping=own(t.damping),
                     to_damping=".".join(t.to_damping))
    if t.model:
        table["model"] = {out: ".".join(target) for out, target in t.model}
    if t.settings:
        table["settings"] = dict(t.settings)
    return table


# -- reading -------------------------------------------------------------------------------
class TomlTable:
    """A TOML table that knows where it came from, for error messages naming the file, the
    table and the key (scenarios here, sweep files in sweep/sweep_file.py)."""

    def __init__(self, source: str, name: str, data):
        if not isinstance(data, dict):
            raise ScenarioError(f"{source}: [{name}] must be a table, got {type(data).__name__}")
        self.source, self.name, self.data = source, name, data

    def error(self, key: str, message: str) -> ScenarioError:
        return ScenarioError(f"{self.source}: [{self.name}] key '{key}': {message}")

    def get(self, key: str, kind, default=None, required: bool = False):
        if key not in self.data:
            if required:
                raise self.error(key, "is missing")
            return default
        value = self.data[key]
        kinds = (int, float) if kind is float else kind
        if isinstance(value, bool) and kind is not bool or not isinstance(value, kinds):
            raise self.error(key, f"must be {getattr(kind, '__name__', kind)}, got {value!r}")
        return float(value) if kind is float else value

    def ref(self, key: str, required: bool = True) -> tuple[str, str] | None:
        """A ``<instance>.<variable>`` reference."""
        value = self.get(key, str, required=required)
        if value is None:
            return None
        inst, dot, var = value.partition(".")
        if not (inst and dot and var):
            raise self.error(key, f"must be '<instance>.<variable>', got {value!r}")
        return inst, var

    def unknown(self, allowed) -> None:
        extra = sorted(set(self.data) - set(allowed))
        if extra:
            raise self.error(extra[0], f"is not a known key (known: {', '.join(sorted(allowed))})")


def typed(variable, value):
    """A start value (a string) or a scenario's value as the Python type of ``variable`` (an
    fmpy ScalarVariable)."""
    if variable.type == "Real":
        return float(value)
    if variable.type in ("Integer", "Enumeration"):
        return int(value)
    if variable.type == "Boolean":
        return value if isinstance(value, bool) else value in ("true", "1")
    return value


def read_toml(path: str | Path, what: str) -> dict:
    """The TOML file ``path`` (``what`` it is, for the message); a ScenarioError naming the file
    when it cannot be read or parsed."""
    path = Path(path)
    try:
        return tomllib.loads(path.read_text())
    except FileNotFoundError as exc:
        raise ScenarioError(f"{path}: cannot read: no such {what} file") from exc
    except OSError as exc:
        raise ScenarioError(f"{path}: cannot read {what}: {exc.strerror or exc}") from exc
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(f"{path}: not valid TOML: {exc}") from exc


def load(path: str | Path, fmu_dir: str | Path | None = None) -> System:
    """Read and check a scenario TOML file.

    FMU paths are relative to the scenario file; with ``fmu_dir`` each FMU is instead taken by
    its file name from that folder.
    """
    path = Path(path)
    src = str(path)
    top = TomlTable(src, "top level", read_toml(path, "the scenario"))
    top.unknown(("name", "description", "experiment", "components", "connections", "tangents",
                 "record", "plots"))

    exp_t = TomlTable(src, "experiment", top.get("experiment", dict, required=True))
    exp_t.unknown(Experiment.__dataclass_fields__)
    d = Experiment()
    exp = Experiment(**{k: exp_t.get(k, type(getattr(d, k)), getattr(d, k))
                        for k in Experiment.__dataclass_fields__})

    comps = {}
    for name, table in TomlTable(src, "components", top.get("components", dict, required=True)).data.items():
        t = TomlTable(src, f"components.{name}", table)
        t.unknown(("fmu", "parameters"))
        fmu = Path(t.get("fmu", str, required=True))
        fmu = Path(fmu_dir) / fmu.name if fmu_dir is not None else path.parent / fmu
        params = TomlTable(src, f"components.{name}.parameters", t.get("parameters", dict, {})).data
        comps[name] = Component(name, fmu, dict(params))

    connections = []
    for i, table in enumerate(top.get("connections", list, [])):
        t = TomlTable(src, f"connections #{i + 1}", table)
        t.unknown(("from", "to"))
        (a, b), (c, e) = t.ref("from"), t.ref("to")
        connections.append(Connection(a, b, c, e))

    tangents = []
    for i, table in enumerate(top.get("tangents", list, [])):
        t = TomlTable(src, f"tangents #{i + 1}", table)
        t.unknown(Tangent.__dataclass_fields__.keys() - {"instance"})
        inst, force = t.ref("force")
        named = {}
        for key in ("position", "velocity"):
            r = t.ref(key, required=key == "position")
            if r is not None and r[0] != inst:
                raise t.error(key, f"must be an input of {inst}, the force's instance")
            named[key] = r[1] if r else None
        for key in ("stiffness", "damping"):
            value = t.get(key, str, required=key == "stiffness")
            if value is not None and value != "fd":
                r = t.ref(key)
                if r[0] != inst:
                    raise t.error(key, f"must be an output of {inst} or \"fd\"")
                value = r[1]
            named[key] = value
        to_k, to_c = t.ref("to_stiffness"), t.ref("to_damping", required=False)
        if (named["velocity"] is None) != (named["damping"] is None) or (named["damping"] is None) != (to_c is None):
            raise t.error("velocity", "velocity, damping and to_damping go together")
        model_t = TomlTable(src, f"tangents #{i + 1}.model", t.get("model", dict, {}))
        model = tuple((out, model_t.ref(out)) for out in model_t.data)
        settings = tuple(TomlTable(src, f"tangents #{i + 1}.settings", t.get("settings", dict, {})).data.items())
        tangents.append(Tangent(inst, force, named["position"], named["stiffness"], to_k,
                                named["velocity"], named["damping"], to_c, model, settings))

    rec_t = TomlTable(src, "record", top.get("record", dict, {}))
    rec_t.unknown(("variables", "interval"))
    record = rec_t.get("variables", list, [])
    for v in record:
        if not isinstance(v, str) or "." not in v:
            raise rec_t.error("variables", f"entries must be '<instance>.<variable>', got {v!r}")
    plots_t = TomlTable(src, "plots", top.get("plots", dict, {}))
    plots_t.unknown(PLOT_KINDS + PLOT_OPTIONS)
    plots = {k: plots_t.get(k, list, []) for k in PLOT_KINDS if k in plots_t.data}
    plots.update({k: plots_t.get(k, float) for k in PLOT_OPTIONS if k in plots_t.data})

    system = System(top.get("name", str, path.stem), path, comps, tuple(connections), exp,
                    tuple(tangents), tuple(record), rec_t.get("interval", float, 0.0), plots,
                    top.get("description", str, ""))
    return check(system, src)


# -- checking ------------------------------------------------------------------------------
def check(system: System, src: str) -> System:
    """Check the description against the FMUs' modelDescriptions; returns it with ``variables``."""
    exp = system.experiment

    def fail(table, key, message):
        return ScenarioError(f"{src}: [{table}] key '{key}': {message}")

    from .algorithms import ALGORITHMS  # the registry; algorithms.py reads systems
    if exp.algorithm not in ALGORITHMS:
        raise fail("experiment", "algorithm",
                   f"must be one of {', '.join(ALGORITHMS)}, got {exp.algorithm!r}")
    for key in ("start", "stop", "step", "tolerance", "min_step", "max_step", "step_timeout"):
        value = getattr(exp, key)
        if math.isnan(value) or (key not in ("max_step", "step_timeout")
                                 and not math.isfinite(value)):
            raise fail("experiment", key, f"must be finite, got {value!r}")
    if not exp.stop > exp.start:
        raise fail("experiment", "stop", f"must be greater than start ({exp.start}), got {exp.stop}")
    if not 0 < exp.step <= exp.stop - exp.start:
        raise fail("experiment", "step", f"must be > 0 and <= stop - start, got {exp.step}")
    if exp.tolerance < 0:
        raise fail("experiment", "tolerance", f"must be >= 0, got {exp.tolerance}")
    if not exp.step_timeout > 0:
        raise fail("experiment", "step_timeout", f"must be > 0 s, got {exp.step_timeout}")
    if not 0 < exp.min_step <= exp.max_step:
        raise fail("experiment", "min_step", f"must be > 0 and <= max_step, got {exp.min_step}")
    smallest = STEP_RESOLUTION * math.ulp(max(abs(exp.start), abs(exp.stop)))
    for key in ("step", "min_step") if exp.tolerance > 0 else ("step",):
        if getattr(exp, key) < smallest:
            raise fail("experiment", key, f"{getattr(exp, key)!r} s is too small for the clock "
                       f"up to t = {max(abs(exp.start), abs(exp.stop)):g} s: t + h would not "
                       f"advance with useful resolution; it must be >= {smallest:.3g} s "
                       f"({STEP_RESOLUTION} float spacings there)")
    if not system.components:
        raise fail("components", "-", "at least one component is needed")
    for name in system.components:
        problem = _instance_name_problem(name)
        if problem:
            raise fail("components", repr(name)[1:-1], f"an instance name {problem}")

    variables, feedthrough = {}, {}
    for name, comp in system.components.items():
        if not comp.fmu.is_file():
            raise fail(f"components.{name}", "fmu", f"FMU file {comp.fmu} does not exist")
        try:
            md = read_model_description(str(comp.fmu))
        except Exception as exc:  # noqa: BLE001 - fmpy raises many kinds for a broken FMU
            raise fail(f"components.{name}", "fmu", f"cannot read {comp.fmu}: {exc}") from exc
        if md.fmiVersion != "2.0" or md.coSimulation is None:
            raise fail(f"components.{name}", "fmu", f"{comp.fmu.name} is not an FMI 2.0 co-simulation FMU")
        cs = md.coSimulation
        if exp.tolerance > 0 and not cs.canGetAndSetFMUstate:
            raise fail("experiment", "tolerance", f"step-size control rolls every FMU back, and "
                       f"{name} ({comp.fmu.name}) cannot get and set its state "
                       "(canGetAndSetFMUstate = false): use tolerance = 0")
        if not cs.canHandleVariableCommunicationStepSize:
            _fixed_step(exp, name, comp.fmu.name, fail)
        variables[name] = {v.name: v for v in md.modelVariables}
        # ModelStructure: an output without a dependencies list depends on everything
        feedthrough[name] = {u.variable.name: u.dependencies is None or any(
            d.causality == "input" for d in u.dependencies) for u in md.outputs}
        for key, value in comp.parameters.items():
            v = variables[name].get(key)
            if v is None or v.causality not in ("parameter", "input"):
                raise fail(f"components.{name}.parameters", key,
                           f"{comp.fmu.name} has no parameter or input of that name")
            if not _fits(v.type, value):
                raise fail(f"components.{name}.parameters", key,
                           f"{v.type} variable cannot take {value!r}")

    def need(table, key, inst, var, causality):
        if inst not in variables:
            raise fail(table, key, f"no component named {inst!r}")
        v = variables[inst].get(var)
        if v is None:
            raise fail(table, key, f"{system.components[inst].fmu.name} has no variable {var!r}")
        if causality and v.causality not in causality:
            raise fail(table, key, f"{inst}.{var} is {_article(v.causality)}, not "
                                   f"{' or '.join(map(_article, causality))}")
        return v

    fed = {}  # (instance, input) -> what feeds it: a connection or a tangent's link

    def feed(table, key, target, source):
        if target in fed:
            raise fail(table, key, f"{target[0]}.{target[1]} is already fed by {fed[target]}")
        fed[target] = source

    for i, c in enumerate(system.connections):
        table = f"connections #{i + 1}"
        out = need(table, "from", c.source, c.output, ("output",))
        inp = need(table, "to", c.target, c.input, ("input",))
        if out.type == "String":
            raise fail(table, "from", f"{c.source}.{c.output} is a String: the master exchanges "
                       "numbers only (Real, Integer, Boolean, Enumeration)")
        if out.type != inp.type:
            raise fail(table, "to", f"type {inp.type} cannot take the {out.type} output {c.source}.{c.output}")
        feed(table, "to", (c.target, c.input), f"{c.source}.{c.output}")
    for i, t in enumerate(system.tangents):
        table = f"tangents #{i + 1}"
        need(table, "force", t.instance, t.force, ("output",))
        need(table, "position", t.instance, t.position, ("input",))
        if t.stiffness != "fd":
            need(table, "stiffness", t.instance, t.stiffness, ("output",))
        need(table, "to_stiffness", *t.to_stiffness, ("input",))
        feed(table, "to_stiffness", t.to_stiffness, f"{t.instance}.{t.stiffness}")
        if t.velocity:
            need(table, "velocity", t.instance, t.velocity, ("input",))
            if t.damping != "fd":
                need(table, "damping", t.instance, t.damping, ("output",))
            need(table, "to_damping", *t.to_damping, ("input",))
            feed(table, "to_damping", t.to_damping, f"{t.instance}.{t.damping}")
        for out, target in t.model:
            need(f"{table}.model", out, t.instance, out, ("output",))
            need(f"{table}.model", out, *target, ("input",))
            feed(f"{table}.model", out, target, f"{t.instance}.{out}")
        for key, value in t.settings:
            v = need(f"{table}.settings", key, t.instance, key, ("parameter",))
            if not _fits(v.type, value):
                raise fail(f"{table}.settings", key, f"{v.type} variable cannot take {value!r}")

    def numeric(table, key, name):
        inst, _, var = name.partition(".")
        if need(table, key, inst, var, None).type == "String":
            raise fail(table, key, f"{name} is a String: results hold numbers only")

    for v in system.record:
        numeric("record", "variables", v)
    for kind in PLOT_KINDS:
        for v in system.plots.get(kind, []):
            if not isinstance(v, str):
                raise fail("plots", kind, f"entries must be '<instance>.<variable>', got {v!r}")
            numeric("plots", kind, v)
    if system.record_interval < 0 or not math.isfinite(system.record_interval):
        raise fail("record", "interval", f"must be >= 0, got {system.record_interval}")
    object.__setattr__(system, "variables", variables)
    object.__setattr__(system, "feedthrough", feedthrough)
    return system


def _instance_name_problem(name: str) -> str | None:
    """What makes ``name`` unusable as an instance name (in ``<instance>.<variable>``
    references, results' column names, the SSD's and the packed FMU's variable names), or None."""
    if not name:
        return "must not be empty"
    if "." in name:
        return "must not contain '.', which ends the instance in '<instance>.<variable>'"
    if not name.isprintable():
        return "must not contain a control character"
    if name != name.strip():
        return "must not begin or end with white space"
    return None


def _article(word: str) -> str:
    return f"{'an' if word[0] in 'aeiou' else 'a'} {word}"


def _fixed_step(exp: Experiment, name: str, fmu: str, fail) -> None:
    """Refuse what an FMU that cannot change its communication step cannot run: step-size
    control, or a run whose length is not a whole number of steps (the last would be short)."""
    why = (f"{name} ({fmu}) cannot change its communication step size "
           "(canHandleVariableCommunicationStepSize = false)")
    if exp.tolerance > 0:
        raise fail("experiment", "tolerance", f"{why}: use tolerance = 0")
    steps = (exp.stop - exp.start) / exp.step
    if abs(steps - round(steps)) > 1e-9 * max(1.0, steps):
        whole = exp.start + max(1, round(steps)) * exp.step
        raise fail("experiment", "stop", f"{why}, and stop - start = {exp.stop - exp.start:g} s "
                   f"is not a whole number of steps of {exp.step:g} s: use stop = {whole:.12g}")


INT32 = (-2**31, 2**31 - 1)  # the range of an FMI 2 Integer (fmi2Integer is a C int)


def _fits(kind: str, value) -> bool:
    if kind == "Real":
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    if kind in ("Integer", "Enumeration"):
        return (isinstance(value, int) and not isinstance(value, bool)
                and INT32[0] <= value <= INT32[1])
    if kind == "Boolean":
        return isinstance(value, bool)
    return isinstance(value, str)
