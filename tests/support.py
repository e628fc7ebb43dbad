"""Helpers the tests import (``from support import ...``): files written for a test (a run
folder among them), scripts of orchestration/ loaded as modules, the real records found through
GUIDEWAY_FMU_DATA, an FMU with an unsafe archive entry, and a guard against calls that never
return."""
from __future__ import annotations

import csv
import importlib.util
import json
import os
import signal
import stat
import sys
import zipfile
from contextlib import contextmanager
from ctypes import byref
from pathlib import Path

import numpy as np
import pytest
from fmpy import calloc, free
from fmpy.fmi2 import (
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)
from fmpy.logging import addLoggerProxy

ORCHESTRATION = Path(__file__).resolve().parents[1] / "orchestration"
#: the one setting of the real records' folder (emps-identification/, emps-validation/); no
#: default: outside the repository, only the user knows where it is
DATA = "GUIDEWAY_FMU_DATA"


def write_file(folder: Path, text: str, name: str) -> Path:
    """``text`` written to ``folder``/``name``; the file's path."""
    path = Path(folder) / name
    path.write_text(text)
    return path


#: a lubricated contact instance's parameters in a run folder's summary.json (SI units)
RUN_PARAMETERS = {"roller_length": 0.008, "roller_radius": 0.0025, "e_reduced": 2e11,
                  "viscosity": 0.195, "pressure_viscosity": 2.2e-8}


def write_run_folder(folder: Path, time, load, u, film, parameters=RUN_PARAMETERS,
                     columns=None) -> Path:
    """A run folder as ``guideway-fmu run`` writes one, for ehl-cycle: results.csv with the
    columns time, Feed.u, Contact.F_upper, Contact.h_upper (or ``columns``) and summary.json
    with the Contact instance's ``parameters``."""
    folder.mkdir(parents=True, exist_ok=True)
    columns = columns or ["time", "Feed.u", "Contact.F_upper", "Contact.h_upper"]
    with (folder / "results.csv").open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        w.writerows(np.column_stack([time, u, load, film]).tolist())
    return write_run_summary(folder, {"Contact": parameters})


def write_run_summary(folder: Path, parameters: dict) -> Path:
    """summary.json of the run in ``folder``: the instances' ``parameters``, and what its
    results.csv holds, as a run writes it (cosim/run.py)."""
    stored = {"rows": len((folder / "results.csv").read_text().splitlines()) - 1,
              "bytes": (folder / "results.csv").stat().st_size}
    (folder / "summary.json").write_text(json.dumps({"parameters": parameters, "results": stored}))
    return folder


def load_script(path: Path):
    """The Python script ``path`` (of orchestration/, not a package module) as a module named
    after its stem, registered in sys.modules while it runs (its dataclasses look it up there),
    whatever held that name before put back after."""
    spec = importlib.util.spec_from_file_location(Path(path).stem, path)
    module = importlib.util.module_from_spec(spec)
    before = sys.modules.get(spec.name)
    sys.modules[spec.name] = module
    try:
        spec.loader.exec_module(module)
    finally:
        if before is None:
            del sys.modules[spec.name]
        else:
            sys.modules[spec.name] = before
    return module


def real_records() -> Path | None:
    """The folder of real records DATA names, None where the variable is unset."""
    folder = os.environ.get(DATA)
    return Path(folder) if folder else None


def real_record(name: str) -> Path:
    """The real record ``name`` (e.g. emps-validation), a folder of :func:`real_records`; skips
    the calling test, naming DATA and what it should point at, where the variable is unset or
    the record is not there."""
    folder = real_records()
    if folder is None:
        pytest.skip(f"{DATA} is not set: point it at the folder of real records "
                    f"(emps-identification/, emps-validation/; orchestration/real_data/README.md)")
    if not (folder / name).is_dir():
        pytest.skip(f"{folder / name} is not a folder: {DATA} must point at the folder holding "
                    f"the real record {name}/")
    return folder / name


SYMLINK = (stat.S_IFLNK | 0o777) << 16  # a Unix symbolic link's st_mode in a zip entry


def with_entry(fmu, out, name, mode):
    """A copy of ``fmu`` at ``out`` with one more entry ``name`` (Unix ``mode`` in the high bits
    of its external attributes; a link's data is its target)."""
    with zipfile.ZipFile(fmu) as src, zipfile.ZipFile(out, "w") as dst:
        for info in src.infolist():
            dst.writestr(info, src.read(info))
        info = zipfile.ZipInfo(name)
        info.create_system, info.external_attr = 3, mode
        dst.writestr(info, "/etc/passwd" if mode == SYMLINK else "x")
    return out


@contextmanager
def returns(within: float = 60.0):
    """Fail the test, rather than hang the run, when the block has not finished ``within``
    seconds: the guard of a call that looped without end before its fix. Far above what the
    call takes, it measures nothing (SIGALRM: the main thread of a POSIX process)."""
    def expired(signum, frame):
        raise AssertionError(f"the call did not return within {within} s: an unbounded loop")

    previous = signal.signal(signal.SIGALRM, expired)
    signal.setitimer(signal.ITIMER_REAL, within)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


#: a scenario of the probe FMU `Faulty` (tests/conftest.py) alone, instance R
PROBE_SCENARIO = """\
name = "probe"

[experiment]
stop = {stop}
step = {step}
algorithm = "jacobi"
{extra}
[components.R]
fmu = "{fmu}"
parameters = {{ fault = "{fault}" }}
"""


def probe_scenario(folder: Path, fmu, fault: str = "none", stop: float = 0.01,
                   step: float = 0.001, extra: str = "") -> Path:
    """probe.toml in ``folder``: the probe FMU ``fmu`` with ``fault`` (conftest's Faulty) run
    for ``stop`` s at steps of ``step`` s, ``extra`` lines added to [experiment]."""
    return write_file(folder, PROBE_SCENARIO.format(fmu=fmu, fault=fault, stop=stop, step=step,
                                                    extra=extra), "probe.toml")


def capturing_callbacks(messages: list):
    """FMI callbacks whose logger appends (status, message) to ``messages``. Keep them as long as
    the instance lives: fmpy's default callbacks log through one process-wide proxy, which
    points at whatever logger another test installed last, freed or not."""
    def logger(environment, instance, status, category, message):
        messages.append((status, message.decode("utf-8", "replace")))

    callbacks = fmi2CallbackFunctions()
    callbacks.logger = fmi2CallbackLoggerTYPE(logger)
    callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
    callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    addLoggerProxy(byref(callbacks))  # formats the variadic message before it reaches Python
    return callbacks
