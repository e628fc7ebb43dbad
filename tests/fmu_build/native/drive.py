"""Drive an FMU through fmpy's FMU2Slave with a script of parameters and inputs (both editions
alike), recording outputs, statuses and the messages the FMU logs."""
from __future__ import annotations

import shutil
import tempfile

from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, fmi2Discard, fmi2OK, fmi2Terminated
from support import capturing_callbacks


class Driven:
    """One instance of the FMU at ``path``; ``messages`` collects what it logs."""

    def __init__(self, path, name="instance"):
        self.description = read_model_description(path)
        self.folder = extract(path, tempfile.mkdtemp(prefix="native_drive_"))
        self.refs = {v.name: v for v in self.description.modelVariables}
        self.messages = []
        self.slave = FMU2Slave(guid=self.description.guid, unzipDirectory=self.folder,
                               modelIdentifier=self.description.coSimulation.modelIdentifier,
                               instanceName=name)
        self._callbacks = capturing_callbacks(self.messages)
        self.slave.instantiate(loggingOn=True, callbacks=self._callbacks)

    def set(self, values: dict) -> None:
        for name, value in values.items():
            v = self.refs[name]
            if v.type == "Real":
                self.slave.setReal([v.valueReference], [float(value)])
            elif v.type == "Integer":
                self.slave.setInteger([v.valueReference], [int(value)])
            elif v.type == "String":
                self.slave.setString([v.valueReference], [value])
            else:
                self.slave.setBoolean([v.valueReference], [bool(value)])

    def outputs(self) -> dict:
        names = [v.name for v in self.description.outputs and
                 [o.variable for o in self.description.outputs]]
        values = self.slave.getReal([self.refs[n].valueReference for n in names])
        return dict(zip(names, values))

    def start(self, parameters: dict, inputs: dict, t0: float = 0.0) -> None:
        self.set(parameters)
        self.slave.setupExperiment(startTime=t0)
        self.slave.enterInitializationMode()
        self.set(inputs)
        self.slave.exitInitializationMode()

    def step(self, t: float, h: float) -> int:
        """fmi2OK, or fmi2Discard (then :attr:`terminated` says what the FMU reported)."""
        try:
            self.slave.doStep(currentCommunicationPoint=t, communicationStepSize=h)
            return fmi2OK
        except FMICallException as exc:  # fmpy raises on a status other than OK
            if exc.status != fmi2Discard:
                raise
            return fmi2Discard

    @property
    def terminated(self) -> bool:
        return bool(self.slave.getBooleanStatus(fmi2Terminated))

    def close(self) -> None:
        try:
            self.slave.terminate()
        finally:
            self.slave.freeInstance()
            shutil.rmtree(self.folder, ignore_errors=True)


def run_script(path, parameters: dict, inputs: list[dict], step: float) -> list[dict]:
    """The outputs at the start and after each step of ``inputs`` (one dict per step)."""
    fmu = Driven(path)
    try:
        fmu.start(parameters, inputs[0])
        rows = [fmu.outputs()]
        for k, values in enumerate(inputs):
            fmu.set(values)
            assert fmu.step(k * step, step) == fmi2OK
            rows.append(fmu.outputs())
        return rows
    finally:
        fmu.close()
