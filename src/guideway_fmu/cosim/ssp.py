"""SSP 1.0 export of a system description, for libcosim (OSP) and fmpy's SSP runner.

The package is a zip holding

* ``SystemStructure.ssd``: one ``ssd:System`` with an ``ssd:Component`` per instance
  (``source="resources/<file>.fmu"``) whose Connectors are its outputs, parameters,
  calculated parameters and *connected* inputs (typed ``ssc:Real/Integer/Boolean/String``, a
  Real with its unit), whose ``parameters`` are an inline ``ssv:ParameterSet``; the
  ``system.connections`` (tangents are a notion of our stabilised master, not of SSP);
  ``ssd:Units``, each unit of a connector once with its SI base units (from the FMUs'
  UnitDefinitions); ``ssd:DefaultExperiment`` with start and stop time [s] and the OSP
  annotation with the macro step [s];
* ``resources/<file>.fmu``: the FMUs. Baked (the default): an instance with parameters gets a
  copy of its FMU whose modelDescription.xml start values are those parameters, every other
  entry copied unchanged; instances of one FMU file with equal parameters share one copy, and
  where they differ each variant is ``resources/<file stem>_<first instance>.fmu``. Unbaked:
  each FMU file once, as it is, however many instances share it.

Why bake by default: the parameter bindings are the SSP way of giving parameters, but a runner
may ignore them without a word (fmpy does), and then the package runs another system, unloaded
instead of loaded. A baked package gives the scenario's answer in any runner that starts its
FMUs from their start values (what FMI requires of an FMU), bindings or not; the bindings stay,
with the same values, for the tools that apply them. Our FMUs start from the start values of the
modelDescription.xml beside their extracted ``resources/`` (components/base.py); the export
instantiates every baked copy and refuses one that does not start at its baked values (a
third-party FMU with built-in start values, or one of ours built before they read them).
``bake=False`` (``export-ssp --no-bake``) packs the FMU files unchanged. Either way, every
instance with parameters is initialised with them and its outputs read before anything is
written: a parameter the FMU refuses (an error status, or an error it logs) is refused with the
FMU's own message.

It describes a fixed-step run with ``experiment.step`` whatever ``experiment.algorithm`` says;
tangents, step-size control, recording and plots are not exported.

What the tools do with it (measured with libcosimpy 0.0.6 and fmpy 0.3.32) and how their steps
compare with our master's "jacobi" (algorithms.py: every instance takes its inputs from the
outputs read after the previous step, then all step t -> t + h; outputs read after a step are
those of the inputs held during it, so a feedthrough output lags its input by one step):

libcosim (``CosimExecution.from_ssp_file``)
    Applies the inline parameter bindings (one it cannot apply only logs a warning). Needs the
    macro step from ``ssd:DefaultExperiment/ssd:Annotations/ssc:Annotation[@type=
    "com.opensimulationplatform"]/osp:Algorithm/osp:FixedStepAlgorithm/@baseStepSize`` (or a step
    passed to ``from_ssp_file``); it matches the literal prefixes ``ssd: ssc: ssv: osp:``, which
    this writer therefore uses. It runs the pythonfmu FMUs in the host interpreter, as fmpy
    does: nothing to preload from Python.
    Steps: the same Jacobi scheme; the same trajectories to ~1e-13 relative (its clock counts
    integer nanoseconds, so the FMUs see t differing by ~1e-19 s). Initialisation: it copies
    outputs to inputs in initialization mode, as many rounds as there are FMUs (our master: one
    pass, sources first); its sample at the start time of an output fed through from an input
    is the value computed in initialization mode, so it differs when the source's outputs change
    at exitInitializationMode (ContactEHL sets its films there: friction fed by it at t = start).
fmpy (``fmpy.ssp.simulation.simulate_ssp``)
    Ignores the bindings, the default experiment and the annotation: pass start/stop/step, and
    for an unbaked package ``parameter_set(system)`` (it cannot set String variables: only a
    baked package gives them to fmpy). It extracts each FMU whole, so our baked FMUs find their
    modelDescription.xml (``fmpy.simulate_fmu`` extracts only ``resources/`` and ``binaries/``:
    a baked FMU run there alone starts from its class's defaults). An input connector without a
    connection is silently fed by the source of the input connector listed before it (or
    fails): every connector of kind input must be connected, which is why only connected inputs
    are exported.
    No initialisation of inputs: they keep their start values (or the parameter set's) through
    initialization mode, and every connected input is 0.0 in the first step. After that the same
    Jacobi scheme; the row labelled t holds the values read after the step t -> t + h, and t
    advances by adding h as our master does (the last row is that of ``while t < stop``, one
    more than stop / h when the sum falls short). Where zero inputs in the first step change
    nothing (a system at rest at the start, as in tests/test_ssp.py) its rows equal our master's
    samples one step later exactly.
"""
from __future__ import annotations

import os
import re
import tempfile
import zipfile
from pathlib import Path

import numpy as np
from xml.etree import ElementTree as ET

from fmpy import read_model_description
from fmpy.ssp.ssd import Parameter, ParameterSet

from ..fmi.archive import check_entries, with_start_values, xml_value
from .fmu_instance import FMICallException, FmuInstance
from .system import System

SSD = "http://ssp-standard.org/SSP1/SystemStructureDescription"
SSC = "http://ssp-standard.org/SSP1/SystemStructureCommon"
SSV = "http://ssp-standard.org/SSP1/SystemStructureParameterValues"
OSP = "http://opensimulationplatform.com/SSP/OSPAnnotations"
NAMESPACES = {"ssd": SSD, "ssc": SSC, "ssv": SSV, "osp": OSP}
for _prefix, _uri in NAMESPACES.items():
    ET.register_namespace(_prefix, _uri)

_KINDS = ("input", "output", "parameter", "calculatedParameter")  # FMI causality = SSP kind
_TYPES = {"Real": "Real", "Integer": "Integer", "Boolean": "Boolean", "String": "String",
          "Enumeration": "Integer"}  # FMI 2 enumerations are integers; libcosim rejects ssc:Enumeration


def export_ssp(system: System, out: str | Path, bake: bool = True) -> Path:
    """Write ``system`` as an SSP 1.0 package to ``out`` (a new ``.ssp`` zip); returns its path.
    ``bake``: the FMUs carry the parameters as start values (module doc).

    Raises FileNotFoundError naming the file if ``out``'s folder or an FMU file does not exist,
    ValueError if two different FMU files share a file name, ``out`` is one of the scenario's
    FMUs or its description (writing it would destroy what it packs), an FMU has an unsafe
    archive entry (archive.check_entries), two FMUs define one unit differently, a baked
    FMU does not start at its baked values, or an FMU refuses its instance's parameters.
    """
    out = Path(out)
    packed_files(system, out, "package")
    entries = _entries(system, bake)
    ssd = ET.tostring(_ssd(system, entries), encoding="UTF-8", xml_declaration=True)
    with tempfile.TemporaryDirectory(prefix="guideway_fmu_ssp_") as tmp:
        files = {}
        for inst, (entry, values) in entries.items():
            comp = system.components[inst]
            if entry not in files:
                files[entry] = (_baked(inst, comp.fmu, Path(tmp) / entry, values,
                                       system.experiment) if values else comp.fmu)
            if comp.parameters and not values:  # unbaked: the runner sets them
                instance = FmuInstance(comp.fmu, inst)
                try:
                    _initialises(instance, inst, comp.fmu, system.experiment, comp.parameters)
                finally:
                    instance.close()
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
            zf.writestr("SystemStructure.ssd", ssd)
            for entry, path in files.items():
                zf.write(path, f"resources/{entry}")
    return out


def explicit_coupling_warning(system: System) -> str | None:
    """The paragraph ``export-ssp`` prints for a system with tangents (a stiff loop our master
    couples with the stabilised algorithm, which the package does not carry), else None."""
    if not system.tangents:
        return None
    loops = ", ".join(f"{t.instance}.{t.force} on {t.instance}.{t.position}"
                      for t in system.tangents)
    return (f"warning: {system.name} couples a stiff loop ({loops}) that our master steps with "
            "the stabilised coupling of its tangents, which an SSP package cannot carry. An SSP "
            "host (libcosim, fmpy) couples the loop explicitly, each output held over the step, "
            "and this loop does not stay stable that way: the run diverges or an FMU stops it "
            "within milliseconds (docs/hosts.md). To run the system in another host as our "
            "master does, export it as one FMU instead: guideway-fmu export-fmu SCENARIO OUT.fmu.")


def packed_files(system: System, out: Path, made: str) -> dict[str, Path]:
    """The FMU files of ``system`` by file name, checked for packing them into ``out``, the
    ``made`` (package, FMU) to write: FileNotFoundError naming the file if ``out``'s folder or an
    FMU does not exist; ValueError if ``out`` is one of the FMUs or the scenario file (the same
    file by any path: a link, a hard link; writing it would destroy what it packs), two
    different FMU files share a name, or an FMU has an unsafe archive entry
    (archive.check_entries)."""
    if not out.parent.is_dir():
        raise FileNotFoundError(f"cannot write {out}: folder {out.parent} does not exist")
    inputs = [(comp.fmu, f"{comp.name}'s FMU") for comp in system.components.values()]
    if system.path is not None:
        inputs.append((Path(system.path), "the scenario file"))
    for path, what in inputs if out.exists() else ():
        if path.exists() and os.path.samefile(out, path):
            raise ValueError(f"cannot write {out}: it is {what}, which the {made} is made from")
    sources: dict[str, Path] = {}
    for comp in system.components.values():
        if not comp.fmu.is_file():
            raise FileNotFoundError(f"{comp.name}: FMU file {comp.fmu} does not exist")
        other = sources.setdefault(comp.fmu.name, comp.fmu)
        if other.resolve() != comp.fmu.resolve():
            raise ValueError(f"{comp.name}: FMU files {other} and {comp.fmu} share the name "
                             f"{comp.fmu.name} and cannot both be packed")
    for path in sources.values():
        check_entries(path)
    return sources


def _entries(system: System, bake: bool) -> dict[str, tuple[str, dict]]:
    """Instance -> (the file name of its FMU under resources/, the parameters baked into it)."""
    keys = {inst: tuple(sorted(comp.parameters.items())) if bake else ()
            for inst, comp in system.components.items()}
    variants: dict[str, dict[tuple, str]] = {}  # FMU file name -> {parameters: first instance}
    for inst, comp in system.components.items():
        variants.setdefault(comp.fmu.name, {}).setdefault(keys[inst], inst)
    entries, owners = {}, {}
    for inst, comp in system.components.items():
        key = keys[inst]
        first = variants[comp.fmu.name][key]
        if len(variants[comp.fmu.name]) == 1:
            entry = comp.fmu.name
        elif re.fullmatch(r"[A-Za-z0-9_.-]+", first):
            entry = f"{comp.fmu.stem}_{first}.fmu"
        else:
            raise ValueError(f"{first}: its parameters differ from those of another instance of "
                             f"{comp.fmu.name}, so it needs a copy named after it, and an instance "
                             "name in a file name may hold only letters, digits and _ . -")
        if owners.setdefault(entry, (comp.fmu.name, key)) != (comp.fmu.name, key):
            raise ValueError(f"{inst}: its FMU would be resources/{entry}, which another FMU "
                             "already is: rename the instance or the FMU file")
        entries[inst] = entry, dict(key)
    return entries


def _baked(inst: str, fmu: Path, out: Path, values: dict, experiment) -> Path:
    """A copy of ``fmu`` at ``out`` starting at ``values``, checked by instantiating it as
    ``inst`` and reading them back (an FMU that ignores its modelDescription's start values
    would otherwise run the package with others, silently), then initialising it."""
    with_start_values(fmu, out, values)
    try:
        instance = FmuInstance(out, inst)
    except Exception as exc:  # noqa: BLE001 - fmpy raises many kinds for an FMU it cannot load
        raise ValueError(f"{inst}: {fmu} with its start values baked in does not instantiate "
                         f"({exc}): export without baking ('bake' False) and give the parameters to the runner") from exc
    try:
        for name, value in values.items():
            started = instance.get(name)
            if started != value:
                raise ValueError(
                    f"{inst}: {fmu} starts {name} at {started!r} whatever the start value in its "
                    f"modelDescription.xml ({value!r} baked): it cannot carry the scenario's "
                    "parameters. Rebuild it (guideway-fmu build) if it is one of ours built "
                    "before our FMUs read their start values, or export without baking ('bake' False) and "
                    "give the parameters to the runner")
        _initialises(instance, inst, fmu, experiment)
    finally:
        instance.close()
    return out


def _initialises(instance: FmuInstance, inst: str, fmu: Path, experiment,
                 parameters: dict | None = None) -> None:
    """Initialise ``instance`` for ``experiment`` with ``parameters`` set and read its outputs;
    ValueError with the FMU's messages if it fails or logs an error (ours refuse a bad
    parameter so: pythonfmu can fail no initialisation call without ending the process)."""
    try:
        instance.initialise(experiment.start, parameters, experiment.stop)
        for name, v in instance.variables.items():
            if v.causality == "output":
                instance.get(name)
    except FMICallException as exc:  # the FMU's own messages say why; the call's name if none
        failed = "; ".join(_own_errors(instance)) or f"{exc}; it logged no error"
    else:
        failed = "; ".join(_own_errors(instance))
    if failed:
        raise ValueError(f"{inst}: {fmu} refuses the instance's parameters: {failed}")


#: how pythonfmu's wrapper logs that the slave's Python call raised: after the slave's own
#: message, which says why, it adds nothing
WRAPPER_LINE = "Fatal py exception encountered"


def _own_errors(instance: FmuInstance) -> list[str]:
    """The errors ``instance`` logged, each once, without pythonfmu's wrapper line."""
    return [e for e in dict.fromkeys(instance.errors()) if not e.startswith(WRAPPER_LINE)]


def parameter_set(system: System) -> ParameterSet:
    """The components' parameters as the ``parameter_set`` of fmpy's ``simulate_ssp``.

    fmpy 0.3.32 takes an ``fmpy.ssp.ssd.ParameterSet`` (not a dict) whose parameter names are
    ``<instance>.<variable>``, and applies a parameter to every instance whose name the
    parameter's name starts with. Raises ValueError for what it would get wrong: String
    parameters (it cannot set them) and a parameter name that starts with another instance's.
    """
    params = []
    for inst, comp in system.components.items():
        for name, value in comp.parameters.items():
            full, kind = f"{inst}.{name}", system.variables[inst][name].type
            if kind == "String":
                raise ValueError(f"{full}: fmpy's simulate_ssp cannot set String variables")
            others = [i for i in system.components if i != inst and full.startswith(i)]
            if others:
                raise ValueError(f"{full}: fmpy would also apply it to {others[0]}: rename one instance")
            params.append(Parameter(name=full, type=_TYPES[kind], value=value))
    return ParameterSet(name="parameters", parameters=params)


def _ssd(system: System, entries: dict[str, tuple[str, dict]]) -> ET.Element:
    root = ET.Element(f"{{{SSD}}}SystemStructureDescription", version="1.0", name=system.name)
    sys_el = ET.SubElement(root, f"{{{SSD}}}System", name=system.name)
    if system.description:
        sys_el.set("description", system.description)
    elements = ET.SubElement(sys_el, f"{{{SSD}}}Elements")
    connected = {(c.target, c.input) for c in system.connections}
    units: dict[str, dict] = {}  # unit -> {instance with a connector in it: None}
    for inst, comp in system.components.items():
        el = ET.SubElement(elements, f"{{{SSD}}}Component", name=inst,
                           source=f"resources/{entries[inst][0]}", type="application/x-fmu-sharedlibrary")
        connectors = ET.SubElement(el, f"{{{SSD}}}Connectors")
        for v in system.variables[inst].values():
            if v.causality in _KINDS and (v.causality != "input" or (inst, v.name) in connected):
                c = ET.SubElement(connectors, f"{{{SSD}}}Connector", name=v.name, kind=v.causality)
                typed = ET.SubElement(c, f"{{{SSC}}}{_TYPES[v.type]}")
                if v.type == "Real" and system.unit(inst, v.name):
                    typed.set("unit", system.unit(inst, v.name))
                    units.setdefault(system.unit(inst, v.name), {})[inst] = None
        if comp.parameters:
            binding = ET.SubElement(ET.SubElement(el, f"{{{SSD}}}ParameterBindings"),
                                    f"{{{SSD}}}ParameterBinding")
            pset = ET.SubElement(ET.SubElement(binding, f"{{{SSD}}}ParameterValues"),
                                 f"{{{SSV}}}ParameterSet", version="1.0", name=f"{inst}-parameters")
            parameters = ET.SubElement(pset, f"{{{SSV}}}Parameters")
            for name, value in comp.parameters.items():
                kind = _TYPES[system.variables[inst][name].type]
                p = ET.SubElement(parameters, f"{{{SSV}}}Parameter", name=name)
                ET.SubElement(p, f"{{{SSV}}}{kind}", value=xml_value(kind, value))
    if system.connections:
        connections = ET.SubElement(sys_el, f"{{{SSD}}}Connections")
        for c in system.connections:
            ET.SubElement(connections, f"{{{SSD}}}Connection", startElement=c.source,
                          startConnector=c.output, endElement=c.target, endConnector=c.input)
    if units:
        declared = ET.SubElement(root, f"{{{SSD}}}Units")
        for name, base in base_units(system, units).items():
            ET.SubElement(ET.SubElement(declared, f"{{{SSC}}}Unit", name=name), f"{{{SSC}}}BaseUnit", base)
    exp = system.experiment
    default = ET.SubElement(root, f"{{{SSD}}}DefaultExperiment", startTime=repr(exp.start),
                            stopTime=repr(exp.stop))
    osp = ET.SubElement(ET.SubElement(default, f"{{{SSD}}}Annotations"), f"{{{SSC}}}Annotation",
                        type="com.opensimulationplatform")
    ET.SubElement(ET.SubElement(osp, f"{{{OSP}}}Algorithm"), f"{{{OSP}}}FixedStepAlgorithm",
                  baseStepSize=repr(exp.step))
    ET.indent(root)
    return root


_BASE = ("kg", "m", "s", "A", "K", "mol", "cd", "rad", "factor", "offset")


def base_units(system: System, used: dict[str, dict]) -> dict[str, dict[str, str]]:
    """The SSD's units: each of ``used`` (unit -> the instances with a connector in it) with the
    attributes of its SI base unit, as each of those FMUs defines it (every unit an FMU uses is
    among its UnitDefinitions: fmpy's validation refused it at loading otherwise). Raises
    ValueError naming both FMUs and the unit if two define it differently."""
    defined: dict[Path, dict] = {}
    bases = {}
    for unit, instances in used.items():
        for inst in instances:
            fmu = system.components[inst].fmu
            if fmu not in defined:
                defined[fmu] = _unit_definitions(fmu)
            first, where = bases.setdefault(unit, (defined[fmu][unit], fmu))
            if first != defined[fmu][unit]:
                raise ValueError(f"unit {unit!r} has the base unit {first} in {where} but "
                                 f"{defined[fmu][unit]} in {fmu}: an SSD defines a unit once")
    return {unit: base for unit, (base, _) in bases.items()}


def _unit_definitions(fmu: Path) -> dict[str, dict[str, str]]:
    """An FMU's UnitDefinitions: unit -> the attributes of its base unit other than the
    defaults (exponents 0, factor 1, offset 0); none for a unit without a base unit, which SSP
    (where a unit needs one) then reads as a number without dimension."""
    units = {}
    for unit in read_model_description(str(fmu)).unitDefinitions:
        base = unit.baseUnit
        units[unit.name] = {} if base is None else {
            k: xml_value("Real" if k in ("factor", "offset") else "Integer", getattr(base, k))
            for k in _BASE if getattr(base, k) != (1.0 if k == "factor" else 0)}
    return units


def run_libcosim(package, names, steps):
    """Run an exported package in libcosim (libcosimpy, an optional dependency) for ``steps``
    macro steps; time [s] and the columns ``<instance>.<variable>`` (Real) at the steps + 1
    communication points."""
    from libcosimpy.CosimEnums import CosimVariableType
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    log_output_level(CosimLogLevel.WARNING)
    execution = CosimExecution.from_ssp_file(str(package))
    observer = CosimObserver.create_time_series()
    if not execution.add_observer(observer):
        raise RuntimeError(f"libcosim: cannot observe {package}")
    index = {s.name.decode(): s.index for s in execution.slave_infos()}
    refs = {}
    for name in names:
        inst, var = name.split(".", 1)
        refs[name] = index[inst], next(v.reference for v in execution.slave_variables(index[inst])
                                       if v.name.decode() == var)
        if not observer.start_time_series(*refs[name], CosimVariableType.REAL):
            raise RuntimeError(f"libcosim: cannot record {name}")
    if not execution.step(steps):
        raise RuntimeError(f"libcosim: {package} failed to step")
    columns = {}
    for name, (i, ref) in refs.items():
        # libcosimpy 0.0.6 drops as many samples as it finds step numbers 0: read step 0 alone
        _, _, first = observer.time_series_real_samples(i, ref, from_step=0, sample_count=2)
        times, _, rest = observer.time_series_real_samples(i, ref, from_step=1, sample_count=steps)
        if len(first) != 1 or len(rest) != steps:
            raise RuntimeError(f"libcosim: {package} recorded {len(first) + len(rest)} samples of "
                               f"{name}, expected {steps + 1} (did a step fail?)")
        columns[name] = np.array([first[0], *rest])
    return np.array([0, *times]) * 1e-9, columns
