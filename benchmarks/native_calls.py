"""The cost of FMI calls in the native edition of an FMU against its pythonfmu edition, measured
side by side in one run and written to docs/native.md.

These components' physics is a few lines per step, so what a master pays per FMU and macro step
is mostly the FMI calls themselves: the floor under every co-simulation of them, which the
native edition (no Python inside) lowers. For each component with a native edition, both
editions loaded through fmpy's FMU2Slave (instantiated, initialised with the inputs INPUTS
gives, else their start values):

(a) a master's step: setReal of every input, fmi2DoStep of STEP seconds, getReal of every
    output [us per sequence];
(b) getReal of every output alone, again and again after a step [us per call];
(c) once per FMU and edition, the first instance in the process: fmpy's FMU2Slave (the library
    loaded, its functions bound), then instantiation and initialisation (instantiate,
    setupExperiment, initialisation mode entered with the inputs set and left) [ms].

(a) and (b): the median over --repeats of the time per call of --iterations calls, the editions
interleaved so that the machine's load falls on both alike; ratios python/native.

    python benchmarks/native_calls.py [--repeats 5] [--iterations 20000] [--out docs/native.md]
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import fmpy
import pages
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

from guideway_fmu.components import registry
from guideway_fmu.fmu_build import build, cache, native
from guideway_fmu.fmu_build.native.build import build_native
from guideway_fmu.fmu_build.native.component import Unit
from guideway_fmu.fmu_build.native.source import TranslationError

EDITIONS = build.EDITIONS
PACKAGE_ROOT = Path(native.__file__).resolve().parents[3]  # the folder holding guideway_fmu/
STEP = 1e-5  # s
LOADED = {"F_upper": 500.0, "F_lower": 500.0, "u": 0.1}  # N, N, m/s: a preloaded carriage moving
INPUTS = {**{name: LOADED for name in ("FrictionCoulomb", "FrictionStribeck", "FrictionDahl",
                                        "FrictionPositionDependent", "FrictionBallToBall",
                                        "FrictionPreloadLoss")},
          "ContactDryHertz": {"u": 0.1}, "ContactEHL": {"u": 0.1}, "MillingForce": {"u_feed": 0.02}}


@dataclass
class Instance:
    """One initialised instance of an FMU, with what a master exchanges with it every step."""

    slave: FMU2Slave
    inputs: list[int]  # value references
    values: list[float]
    outputs: list[int]
    steps: int = 0  # taken so far, of STEP each

    def step(self) -> None:
        """One master step: set every input, step, get every output."""
        self.slave.setReal(self.inputs, self.values)
        self.slave.doStep(self.steps * STEP, STEP)
        self.slave.getReal(self.outputs)
        self.steps += 1

    def read(self) -> None:
        """Get every output."""
        self.slave.getReal(self.outputs)


def input_values(name: str, description) -> dict[int, float]:
    """The inputs of component ``name`` by value reference: INPUTS, else their start values;
    VerticalDynamics carries its weight on the contact (F_contact = mass gravity)."""
    variables = {v.name: v for v in description.modelVariables}
    chosen = {v.name: float(v.start) for v in variables.values() if v.causality == "input"}
    chosen.update(INPUTS.get(name, {}))
    if name == "VerticalDynamics":
        chosen["F_contact"] = float(variables["mass"].start) * float(variables["gravity"].start)
    return {variables[n].valueReference: value for n, value in chosen.items()}


def instantiate(name: str, fmu: Path, folder: Path) -> tuple[Instance, float, float]:
    """An initialised instance of ``fmu`` extracted into ``folder``; the seconds fmpy takes to
    load its library (FMU2Slave), and those from instantiate to leaving initialisation."""
    description = read_model_description(str(fmu))
    unzipped = extract(str(fmu), str(folder))
    inputs = input_values(name, description)
    begun = time.perf_counter()
    slave = FMU2Slave(guid=description.guid, unzipDirectory=unzipped, instanceName=name,
                      modelIdentifier=description.coSimulation.modelIdentifier)
    loaded = time.perf_counter()
    slave.instantiate()
    slave.setupExperiment(startTime=0.0)
    slave.enterInitializationMode()
    slave.setReal(list(inputs), list(inputs.values()))
    slave.exitInitializationMode()
    done = time.perf_counter()
    outputs = [o.variable.valueReference for o in description.outputs]
    return (Instance(slave, list(inputs), list(inputs.values()), outputs), loaded - begun,
            done - loaded)


def per_call(call: Callable[[], None], iterations: int) -> float:
    """Microseconds per call of ``iterations`` calls of ``call``."""
    begun = time.perf_counter()
    for _ in range(iterations):
        call()
    return (time.perf_counter() - begun) / iterations * 1e6


def measure(name: str, fmus: dict[str, Path], folder: Path, repeats: int,
            iterations: int) -> dict[str, dict[str, float]]:
    """Per edition: "step" and "read" [us, median of ``repeats``], "load" and "start" [ms]."""
    instances, starts = {}, {}
    for edition in EDITIONS:
        instances[edition], load, start = instantiate(name, fmus[edition], folder / edition)
        starts[edition] = {"load": load * 1e3, "start": start * 1e3}
    times = {(edition, what): [] for edition in EDITIONS for what in ("step", "read")}
    try:
        for _ in range(repeats):
            for edition, instance in instances.items():
                times[edition, "step"].append(per_call(instance.step, iterations))
                times[edition, "read"].append(per_call(instance.read, iterations))
    finally:
        for instance in instances.values():
            instance.slave.terminate()
            instance.slave.freeInstance()
    return {edition: {"step": statistics.median(times[edition, "step"]),
                      "read": statistics.median(times[edition, "read"]),
                      **starts[edition]} for edition in EDITIONS}


ABOUT = ("The native edition of a component is its Python definition (the component class and "
         "the physics it calls) translated to C by `fmu_build/native` and compiled: one FMI "
         "layer, `fmu_build/native/fmi2_slave.c`, written in C once for every native FMU, around "
         "the component's translated unit. No Python interpreter runs inside; the FMU declares "
         "the same modelDescription variables (names, value references, units, start values, "
         "output dependencies) as the pythonfmu edition, so a master swaps one for the other "
         "without changing a connection, and starts from the start values of its "
         "modelDescription as that edition does. The translator covers the subset the physics "
         "is written in: numbers, tuples, objects and dicts whose shape the component's start "
         "values fix, numpy arrays of known length, arrays of run-time length up to 256 numbers "
         "(a table a String parameter gives, a tooth count, the balls of a carriage or a feed "
         "unit; held in a scratch area on the heap, not on the host thread's stack), String "
         "parameters that choose a law (each law translated, chosen at run time), every call "
         "inlined, loops and branches, try/except, `raise` with the Python message word for "
         "word, math's domain and range errors; anything else it refuses, naming the file, line "
         "and construct. Library functions the physics calls that C's library lacks are written "
         "once in the C runtime, `fmu_build/native/gw_runtime.h`, each tested against the "
         "library: numpy's pairwise sum, interp and linalg.solve (LU with partial pivoting), "
         "SciPy's ellipk and ellipe (arithmetic-geometric mean), brentq (Brent's method, the "
         "function inlined where it is evaluated) and eigh's eigenvalues (Cholesky, cyclic "
         "Jacobi); no equation of the physics has a C copy. An iterative solve's answer agrees "
         "between the editions to its tolerance, not to the last bit (their iterates round "
         "differently). Build the "
         "FMUs with `guideway-fmu build --edition native` (`--cross` adds win64 and darwin64 "
         "binaries, cross-compiled with zig).")


def status(name: str) -> str:
    """Whether component ``name`` has a native edition, and if not, why."""
    if name in native.COMPONENTS:
        return "native"
    if name in native.PYTHON_ONLY:
        return f"Python only: {native.PYTHON_ONLY[name]}"
    try:
        Unit(registry.component(name)).text  # noqa: B018 - translated to find the refusal
    except (TranslationError, ValueError) as exc:
        reason = str(exc).replace(f"{PACKAGE_ROOT}/", "").replace("|", "\\|")
        return f"not yet: {reason}"
    return "translates, but not yet tested against the Python edition"


STARTS = ("Once per FMU and edition, the first instance of each in the process, in milliseconds: "
          "loading, fmpy's `FMU2Slave` (the library opened, its functions bound in Python), "
          "then instantiation and initialisation (instantiate, setupExperiment, initialisation "
          "mode entered and left with the inputs set), for the pythonfmu edition the import of "
          "the FMU's own copy of the package included.")


def page(results: dict[str, dict[str, dict[str, float]]], args, command: str) -> str:
    how = (f"Both editions in one process through fmpy {fmpy.__version__}'s `FMU2Slave`, "
           "interleaved; every figure includes fmpy's Python side of each call (ctypes arrays, "
           f"status check). Step: setReal of every input, fmi2DoStep of {STEP:g} s, getReal of "
           "every output; getReal: every output read again after a step (both editions evaluate "
           "the outputs once per step and serve later reads from memory). Median over "
           f"{args.repeats} repeats of {args.iterations} calls, in microseconds. The host's "
           "share is the same in both editions: a master that calls the FMU from C pays less "
           "of it, and sees larger ratios.")
    lines = ["# Native FMUs", "", ABOUT, "", how, "",
             ("| component | python edition us/step | native us/step | ratio | python getReal us "
              "| native getReal us | ratio |"),
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for name, r in results.items():
        python, native = r["python"], r["native"]
        lines.append(f"| {name} | {python['step']:.1f} | {native['step']:.2f} | "
                     f"{python['step'] / native['step']:.1f} | {python['read']:.1f} | "
                     f"{native['read']:.2f} | {python['read'] / native['read']:.1f} |")
    lines += ["", STARTS, "",
              ("| component | python load ms | native load ms | python instantiation and "
               "initialisation ms | native instantiation and initialisation ms | ratio |"),
              "| --- | --- | --- | --- | --- | --- |"]
    for name, r in results.items():
        python, native = r["python"], r["native"]
        lines.append(f"| {name} | {python['load']:.2f} | {native['load']:.2f} | "
                     f"{python['start']:.2f} | {native['start']:.3f} | "
                     f"{python['start'] / native['start']:.0f} |")
    machine = (f"Measured on {os.cpu_count()} CPUs with Python {platform.python_version()} "
               f"({platform.machine()}); the absolute times move with the machine and its load, "
               "the ratios much less.")
    again = (f"To reproduce: `{command}` (the pythonfmu edition from the FMU cache, the native "
             "one built into a temporary folder).")
    lines += ["", machine, "", again, "", "## Every component", "",
              ("Native, Python-only by design (and why), or not yet translated (the translator's "
              "refusal, which names what to add next):"), "", "| component | edition |",
              "| --- | --- |"]
    lines += [f"| {name} | {status(name)} |" for name in registry.names()]
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--iterations", type=int, default=20000)
    parser.add_argument("--out", type=Path, default=Path("docs/native.md"))
    args = parser.parse_args()
    python = cache.folder("python")
    results = {}
    with tempfile.TemporaryDirectory(prefix="guideway_fmu_native_calls_") as tmp:
        tmp = Path(tmp)
        for name in native.COMPONENTS:
            fmus = {"python": python / f"{name}.fmu",
                    "native": build_native(registry.component(name), tmp / f"{name}.fmu")}
            results[name] = r = measure(name, fmus, tmp / name, args.repeats, args.iterations)
            print(f"{name}: step {r['python']['step']:.1f} / {r['native']['step']:.2f} us, "
                  f"getReal {r['python']['read']:.1f} / {r['native']['read']:.2f} us, start "
                  f"{r['python']['start']:.2f} / {r['native']['start']:.3f} ms (python / native)",
                  flush=True)
    command = (f"python benchmarks/native_calls.py --repeats {args.repeats} "
               f"--iterations {args.iterations}")
    pages.write(args.out, page(results, args, command), command, __file__)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
