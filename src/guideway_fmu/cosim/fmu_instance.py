"""One FMI 2.0 co-simulation FMU instance driven through fmpy: variables by name, batched
access for the master's inner loop, FMU state, the instance's log, and the time spent in FMI calls."""
from __future__ import annotations

import shutil
import tempfile
import time
from collections import deque
from itertools import groupby
from ctypes import byref
from pathlib import Path

from fmpy import extract, platform, read_model_description, sharedLibraryExtension
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2Boolean, fmi2CallbackAllocateMemoryTYPE,
                       fmi2CallbackFreeMemoryTYPE, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE,
                       fmi2FMUstate, fmi2Integer, fmi2Real, fmi2ValueReference)
from fmpy.fmi2 import calloc, free
from fmpy.logging import addLoggerProxy

from ..fmi.archive import check_entries
from ..fmu_build import uri_patch
from ..fmu_build.elf import PatchError

_CTYPES = {"Real": fmi2Real, "Integer": fmi2Integer, "Boolean": fmi2Boolean, "Enumeration": fmi2Integer}
_STATUS = ["ok", "warning", "discard", "error", "fatal", "pending"]
LOG_LINES = 50  # log messages kept per instance
# Log messages by instance name. pythonfmu 0.7 sends every instance's messages to the logger of
# the instance created last (with the right instance name), so they are routed by that name.
_LOGS: dict[str, deque] = {}

__all__ = ["FmuInstance", "FMICallException", "ERROR", "FATAL"]
WARNING = 1  # fmi2Warning: the call succeeded
ERROR = 3  # fmi2Error: the instance cannot go on
FATAL = 4  # fmi2Fatal: every instance of the process is then beyond use
TEMP_PREFIX = "guideway-fmu-"  # of the temporary folder each instance's FMU is unpacked into
_UNPACKED: set[str] = set()  # those folders of this process not deleted yet


class FmuInstance:
    """An instantiated FMU (any FMI 2.0 CS FMU, not only ours).

    ``fmi_time`` [s] accumulates the wall time spent inside the batched calls, ``do_step`` and
    the state calls, so that a master can tell its own overhead from the FMUs' cost. ``log``
    holds the last LOG_LINES messages the FMU sent (logging is switched on). An FMICallException
    from any call made through these methods carries ``instance``, this instance's name.
    ``busy`` is (the FMI function, perf_counter() at its call [s]) while a call made through
    them runs (fmi2Instantiate excepted: the instance does not exist yet), else None;
    ``time`` [s] is where the last fmi2DoStep started (None before the first).
    """

    def __init__(self, path: str | Path, name: str):
        self.path, self.name = Path(path), name
        if not self.path.is_file():
            raise FileNotFoundError(f"{name}: FMU file {self.path} does not exist")
        self.description = read_model_description(str(self.path))
        self.variables = {v.name: v for v in self.description.modelVariables}
        cs = self.description.coSimulation
        self.can_get_set_state = bool(cs.canGetAndSetFMUstate)
        self.log: deque[str] = deque(maxlen=LOG_LINES)
        _LOGS[name] = self.log
        self.fmi_time = 0.0
        #: set once a call returned fmi2Fatal: FMI then forbids any further call
        self.fatal = False
        self.busy: tuple[str, float] | None = None
        self.time: float | None = None
        check_entries(self.path)
        self._unzip = tempfile.mkdtemp(prefix=TEMP_PREFIX)
        _UNPACKED.add(self._unzip)
        try:
            extract(str(self.path), self._unzip)
            self._check_resource_path(cs.modelIdentifier)
            self.fmu = FMU2Slave(guid=self.description.guid, unzipDirectory=self._unzip,
                                 modelIdentifier=cs.modelIdentifier, instanceName=name)
            self._callbacks = fmi2CallbackFunctions()
            self._callbacks.logger = fmi2CallbackLoggerTYPE(self._on_log)
            self._callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
            self._callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
            addLoggerProxy(byref(self._callbacks))
            self.fmu.instantiate(callbacks=self._callbacks, loggingOn=True)
            self._do_step = self.entry("fmi2DoStep")
        except BaseException:
            self.remove_files()  # no instance: nothing else to free
            raise

    def _check_resource_path(self, model_identifier: str) -> None:
        """Refuse (ValueError) a pythonfmu FMU that would not find its resources where it was
        extracted: pythonfmu 0.7's fmi2Instantiate decodes no escape of the resource URI but
        %20 and then crashes the process; our builds decode them (fmu_build/uri_patch.py)."""
        uri = Path(self._unzip, "resources").as_uri()
        if "%" not in uri.replace("%20", "") or not (
                self.description.generationTool or "").startswith("PythonFMU"):
            return
        binary = Path(self._unzip, "binaries", platform, model_identifier + sharedLibraryExtension)
        try:
            if uri_patch.decodes(binary.read_bytes()):
                return
        except (OSError, PatchError):
            pass  # no binary for this platform (fmpy names it next), or not one we fixed
        raise ValueError(
            f"{self.name}: FMU {self.path.name} is built with pythonfmu, whose fmi2Instantiate "
            f"cannot find its resources under {self._unzip} (it decodes no escape of the "
            f"resource URI {uri} but %20, and crashes): set TMPDIR to a folder whose path has "
            f"ASCII letters, digits, spaces and -._~/ only")

    @staticmethod
    def _on_log(env, instance, status, category, message):
        label = _STATUS[status] if 0 <= status < len(_STATUS) else str(status)
        name = (instance or b"").decode("utf-8", "replace")
        _LOGS.setdefault(name, deque(maxlen=LOG_LINES)).append(
            f"[{label}] {message.decode('utf-8', 'replace')}")

    def log_text(self) -> str:
        """The kept log, a message repeated in a row given once with its count (an FMU may say
        it at every call that meets the same bad parameter)."""
        runs = [(line, len(list(same))) for line, same in groupby(self.log)]
        return "\n".join(line if n == 1 else f"{line} ({n} times)" for line, n in runs) or \
            "(the FMU logged nothing)"

    def errors(self) -> list[str]:
        """The messages the FMU logged with status error or fatal (among the kept ones)."""
        return [line.split("] ", 1)[1] for line in self.log
                if line.startswith(("[error] ", "[fatal] "))]

    # -- by name ---------------------------------------------------------------------------
    def variable(self, name: str):
        if name not in self.variables:
            raise ValueError(f"{self.name}: FMU {self.path.name} has no variable {name!r}")
        return self.variables[name]

    def unit(self, name: str) -> str:
        return self.variable(name).unit or ""

    def set(self, name: str, value) -> None:
        v = self.variable(name)
        if v.type == "String":
            self.call(self.fmu.setString, [v.valueReference], [str(value)])
        else:
            self.writer([name])([value])

    def get(self, name: str):
        """The variable's value; a String as text (fmpy returns the C bytes)."""
        v = self.variable(name)
        if v.type == "String":
            value = self.call(self.fmu.getString, [v.valueReference])[0]
            return value.decode("utf-8", "replace") if isinstance(value, bytes) else value
        return self.reader([name])()[0]

    # -- calls ---------------------------------------------------------------------------------
    def call(self, function, *args):
        """``function(*args)``, an FMI call of this instance through fmpy (whose method names
        are those of FMI without "fmi2"): timed into ``fmi_time``, and an FMICallException it
        raises names the instance."""
        name = function.__name__
        t0 = time.perf_counter()
        self.busy = (name if name.startswith("fmi2") else f"fmi2{name[0].upper()}{name[1:]}", t0)
        try:
            result = function(*args)
        except FMICallException as exc:
            exc.instance = self.name
            raise
        finally:
            self.busy = None
        self.fmi_time += time.perf_counter() - t0
        return result

    # -- batched access for the master ------------------------------------------------------
    def entry(self, function: str):
        """The FMI function's C entry point as a call of this instance: timed into ``fmi_time``;
        a status above fmi2Warning raises FMICallException naming the function and the
        instance. It calls the shared library directly (fmpy's wrapper adds a frame and a lookup,
        about 0.5 us, to each of the master's calls)."""
        c_function = getattr(self.fmu.dll, function)  # ctypes function with fmpy's argtypes
        clock = time.perf_counter

        def call(*args):
            t0 = clock()
            self.busy = (function, t0)
            status = c_function(*args)
            self.busy = None
            self.fmi_time += clock() - t0
            if status > WARNING:
                exc = FMICallException(function=function, status=status)
                exc.instance = self.name
                raise exc
            return status
        return call

    def _batch(self, names, setter: bool):
        types = {self.variable(n).type for n in names}
        if len(types) != 1 or not types <= set(_CTYPES):
            raise ValueError(f"{self.name}: a batch needs variables of one type among "
                             f"{sorted(_CTYPES)}, got {sorted(types)} for {list(names)}")
        kind = types.pop()
        n = len(names)
        vrs = (fmi2ValueReference * n)(*[self.variable(x).valueReference for x in names])
        values = (_CTYPES[kind] * n)()
        prefix = "fmi2Set" if setter else "fmi2Get"
        call = self.entry(prefix + ("Integer" if kind == "Enumeration" else kind))
        return self.fmu.component, call, vrs, values, n

    def reader(self, names):
        """A function returning the current values of ``names`` (one type) as a list, one FMI call."""
        comp, get, vrs, values, n = self._batch(names, setter=False)

        def read():
            get(comp, vrs, n, values)
            return values[:]
        return read

    def writer(self, names):
        """A function setting ``names`` (one type) from a sequence of values, one FMI call."""
        comp, put, vrs, values, n = self._batch(names, setter=True)

        def write(new):
            values[:] = new
            put(comp, vrs, n, values)
        return write

    def do_step(self, t: float, h: float) -> None:
        """fmi2DoStep from t [s] over h [s]; raises FMICallException on discard, error or fatal."""
        self.time = t
        self._do_step(self.fmu.component, t, h, 0)

    def get_state(self):
        """Save the FMU state; free it with :meth:`free_state`."""
        state = fmi2FMUstate()
        self.call(self.fmu.fmi2GetFMUstate, self.fmu.component, byref(state))
        return state

    def set_state(self, state) -> None:
        self.call(self.fmu.fmi2SetFMUstate, self.fmu.component, state)

    def free_state(self, state) -> None:
        self.call(self.fmu.fmi2FreeFMUstate, self.fmu.component, byref(state))

    # -- life cycle ------------------------------------------------------------------------
    def enter_initialisation(self, start_time: float, parameters: dict | None = None,
                             stop_time=None) -> None:
        """Set up the experiment from ``start_time`` [s], enter Initialization Mode, set the
        parameters (or inputs' start values) by name."""
        self.call(self.fmu.setupExperiment, None, start_time, stop_time)  # no tolerance
        self.call(self.fmu.enterInitializationMode)
        for key, value in (parameters or {}).items():
            self.set(key, value)

    def exit_initialisation(self) -> None:
        self.call(self.fmu.exitInitializationMode)

    def initialise(self, start_time: float, parameters: dict | None = None, stop_time=None) -> None:
        """:meth:`enter_initialisation`, then :meth:`exit_initialisation`."""
        self.enter_initialisation(start_time, parameters, stop_time)
        self.exit_initialisation()

    def close(self) -> FMICallException | None:
        """Terminate and free the instance, unload it and delete its extracted files; after
        fmi2Fatal only the files (FMI allows no call into an instance then). Returns the
        FMICallException of a terminate that failed (the instance is freed all the same, unless
        it failed fatally: ``fatal`` is then set), else None."""
        failed = None
        if not self.fatal:
            try:
                self.call(self.fmu.terminate)
            except FMICallException as exc:
                failed = exc
                self.fatal = exc.status == FATAL
            if not self.fatal:
                self.call(self.fmu.freeInstance)
        self.remove_files()
        return failed

    def remove_files(self) -> None:
        """Delete the folder the FMU was unpacked into."""
        shutil.rmtree(self._unzip, ignore_errors=True)
        _UNPACKED.discard(self._unzip)


def remove_unpacked() -> None:
    """Delete every folder an instance of this process unpacked its FMU into and has not
    deleted: the only step allowed when the process ends around instances stuck in calls (a
    loaded library stays mapped while its file is gone)."""
    for folder in list(_UNPACKED):
        shutil.rmtree(folder, ignore_errors=True)
        _UNPACKED.discard(folder)
