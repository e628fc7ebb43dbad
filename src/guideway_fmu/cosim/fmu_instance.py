"""One FMI 2.0 co-simulation FMU instance driven through fmpy, with variables by name."""
from __future__ import annotations

import shutil
from pathlib import Path

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

_SETTERS = {"Real": "setReal", "Integer": "setInteger", "Boolean": "setBoolean", "String": "setString"}
_GETTERS = {"Real": "getReal", "Integer": "getInteger", "Boolean": "getBoolean", "String": "getString"}


class FmuInstance:
    """An instantiated FMU (any FMI 2.0 CS FMU, not only ours) with name-based get/set."""

    def __init__(self, path: str | Path, name: str):
        self.path, self.name = Path(path), name
        if not self.path.is_file():
            raise FileNotFoundError(f"{name}: FMU file {self.path} does not exist")
        self.description = read_model_description(str(self.path))
        self.variables = {v.name: v for v in self.description.modelVariables}
        self._unzip = extract(str(self.path))
        self.fmu = FMU2Slave(guid=self.description.guid, unzipDirectory=self._unzip,
                             modelIdentifier=self.description.coSimulation.modelIdentifier,
                             instanceName=name)
        self.fmu.instantiate()

    def variable(self, name: str):
        if name not in self.variables:
            raise KeyError(f"{self.name}: FMU {self.path.name} has no variable {name!r}")
        return self.variables[name]

    def unit(self, name: str) -> str:
        return self.variable(name).unit or ""

    def set(self, name: str, value) -> None:
        v = self.variable(name)
        getattr(self.fmu, _SETTERS[v.type])([v.valueReference], [value])

    def get(self, name: str):
        v = self.variable(name)
        return getattr(self.fmu, _GETTERS[v.type])([v.valueReference])[0]

    def initialise(self, start_time: float, parameters: dict | None = None) -> None:
        self.fmu.setupExperiment(startTime=start_time)
        self.fmu.enterInitializationMode()
        for key, value in (parameters or {}).items():
            self.set(key, value)
        self.fmu.exitInitializationMode()

    def close(self) -> None:
        """Terminate and free the instance, unload it and delete its extracted files."""
        self.fmu.terminate()
        self.fmu.freeInstance()
        self.fmu.freeLibrary()
        shutil.rmtree(self._unzip, ignore_errors=True)
