"""The pythonfmu runtime the components run on, and what a built FMU does for its host's interpreter.

Runtime. Inside a built FMU the build places the pythonfmu it built with in the FMU's own package
(``<package>/_pythonfmu``) and the components take it from there, so an FMU keeps its own runtime
when another pythonfmu FMU (another build or version) was loaded into the process first and
``pythonfmu`` in ``sys.modules`` is that one. Outside an FMU (tests, the build) the installed
pythonfmu is used.

Interpreter. Two defects outside this project would otherwise corrupt the host's heap:

* pythonfmu 0.7 releases a reference it does not own to the slave script's namespace on every
  instantiation (it re-executes the script in that namespace, then decrements it). The script
  calls :func:`hold_namespace` each time it runs, which takes the reference back. Cost: none per
  instance, no limit on instantiations.
* SciPy's ``scipy._lib._uarray._uarray`` extension frees an exception type it created when its
  module object is deallocated, while other modules still hold that type. An interpreter that is
  finalised with it loaded (pythonfmu finalises the interpreter it started when a C host exits)
  then reads freed memory: the host died at exit in every run of FeedKinematics. At exit, before
  the interpreter tears its modules down, :func:`_keep_uarray_loaded` keeps that module alive;
  the process is ending, so nothing is lost by not freeing it.
"""
from __future__ import annotations

import atexit
import ctypes
import importlib
import importlib.util
import sys

_BUNDLED = f"{__package__.rsplit('.', 1)[0]}._pythonfmu"
pythonfmu = importlib.import_module(_BUNDLED if importlib.util.find_spec(_BUNDLED) else "pythonfmu")
_enums = importlib.import_module(f"{pythonfmu.__name__}.enums")

Boolean = pythonfmu.Boolean
DefaultExperiment = pythonfmu.DefaultExperiment
Fmi2Causality = pythonfmu.Fmi2Causality
Fmi2Slave = pythonfmu.Fmi2Slave
Fmi2Variability = pythonfmu.Fmi2Variability
Integer = pythonfmu.Integer
Real = pythonfmu.Real
String = pythonfmu.String
Fmi2Initial = _enums.Fmi2Initial
Fmi2Status = _enums.Fmi2Status

_UARRAY = "scipy._lib._uarray._uarray"


def hold_namespace(namespace: dict) -> None:
    """Add one reference to the slave script's ``namespace`` (its ``globals()``); the script
    calls this every time it is executed, once more than pythonfmu releases."""
    ctypes.pythonapi.Py_IncRef(ctypes.py_object(namespace))


def _keep_uarray_loaded() -> None:
    module = sys.modules.get(_UARRAY)
    if module is not None:
        ctypes.pythonapi.Py_IncRef(ctypes.py_object(module))


atexit.register(_keep_uarray_loaded)
