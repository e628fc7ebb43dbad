"""The build's fix of pythonfmu's exception path (fmu_build/error_patch.py): the bytes it
changes in the binary pythonfmu ships, and what it does in an FMU driven by fmpy in a child
process (a crash is the failure): a Python exception in a getter or exitInitializationMode is
fmi2Error with the instance kept (pythonfmu alone: fmi2Fatal, its objects released while it
is still used); a slave script not found under the resource path fails the instantiation
(pythonfmu alone: a segfault)."""
from __future__ import annotations

import subprocess
import sys
import textwrap
import zipfile
from pathlib import Path

import pytest
import pythonfmu
from pythonfmu.builder import FmuBuilder

from guideway_fmu.fmi.archive import rewrite
from guideway_fmu.fmu_build import elf, error_patch, exit_patch

SHIPPED = (Path(pythonfmu.__file__).parent / "resources" / "binaries" / "linux64"
           / "libpythonfmu-export.so")

PROBE = '''
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real, String


class ErrorProbe(Fmi2Slave):
    """x = 1; reading x raises while `fault` is "get", leaving initialization while it is "init"."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.fault = ""
        self.register_variable(Real("x", causality=Fmi2Causality.output, getter=self._x))
        self.register_variable(String("fault", causality=Fmi2Causality.parameter,
                                      variability=Fmi2Variability.tunable))

    def _x(self):
        if self.fault == "get":
            raise ValueError("x cannot be evaluated")
        return 1.0

    def exit_initialization_mode(self):
        if self.fault == "init":
            raise ValueError("initialisation failed")

    def do_step(self, current_time, step_size):
        return True
'''

HOST = '''
import sys
from ctypes import byref
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE,
                       fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE, calloc, free)
from fmpy.logging import addLoggerProxy

fmu, fault = sys.argv[1], sys.argv[2]
md = read_model_description(fmu)
vr = {{v.name: v.valueReference for v in md.modelVariables}}
callbacks = fmi2CallbackFunctions()
callbacks.logger = fmi2CallbackLoggerTYPE(
    lambda env, name, status, category, message: print("LOG", status, message.decode(), flush=True))
callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
addLoggerProxy(byref(callbacks))
slave = FMU2Slave(guid=md.guid, unzipDirectory=extract(fmu), modelIdentifier="ErrorProbe",
                  instanceName="probe")
slave.instantiate(callbacks=callbacks, loggingOn=True)
slave.setupExperiment(startTime=0.0)
slave.enterInitializationMode()
slave.setString([vr["fault"]], [fault])
for call in (slave.exitInitializationMode, lambda: slave.getReal([vr["x"]])):
    try:
        call()
    except FMICallException as exc:
        print("STATUS", exc.status, flush=True)
slave.setString([vr["fault"]], [""])  # the instance is still there: fixed, it answers
print("X", slave.getReal([vr["x"]])[0], flush=True)
slave.terminate()
slave.freeInstance()
print("FREED", flush=True)
'''


@pytest.fixture(scope="module")
def probe(tmp_path_factory):
    """ErrorProbe.fmu as pythonfmu builds it, and with the build's fixes."""
    folder = tmp_path_factory.mktemp("error_probe")
    (folder / "error_probe.py").write_text(PROBE)
    shipped = exit_patch.patch_fmu(FmuBuilder.build_FMU(folder / "error_probe.py",
                                                        dest=folder / "ErrorProbe.fmu"))
    fixed = folder / "fixed" / "ErrorProbe.fmu"
    fixed.parent.mkdir()
    rewrite(shipped, fixed, lambda name, data: (name, error_patch.patch(data) if name.startswith(
        "binaries/linux64/") else data))
    return shipped, fixed


def host(fmu: Path, fault: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(HOST.format()), str(fmu), fault],
                          capture_output=True, text=True, timeout=120)


def test_patch_changes_nine_bytes_of_the_exception_handler_and_is_idempotent():
    original = SHIPPED.read_bytes()
    patched = error_patch.patch(original)
    address, _ = elf.symbol(original, error_patch.HANDLER)
    at = elf.file_offset(original, address)
    changed = [i - at for i, (a, b) in enumerate(zip(original, patched)) if a != b]
    # the no-error return (4 of its 6 bytes differ from the NOP), the three decrements (1 each),
    # the displacement of the type information's load (2 of 4 differ)
    assert changed == [0x60, 0x61, 0x62, 0x63, 0xAD, 0xC7, 0xE1, 0x373, 0x374]
    assert len(patched) == len(original) and error_patch.patch(patched) == patched


def test_patch_refuses_a_binary_it_does_not_know():
    original = SHIPPED.read_bytes()
    address, _ = elf.symbol(original, error_patch.HANDLER)
    at = elf.file_offset(original, address) + 0xAD  # a decrement by 2
    with pytest.raises(elf.PatchError, match=r"differs from pythonfmu 0.7's at \+0x9c"):
        error_patch.patch(original[:at] + b"\x02" + original[at + 1:])


@pytest.mark.parametrize("fault, call", [("get", "fmi2GetReal"), ("init", "fmi2ExitInitializationMode")])
def test_an_exception_is_an_error_and_the_instance_is_kept(probe, fault, call):
    _, fixed = probe
    done = host(fixed, fault)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "STATUS 3" in done.stdout  # fmi2Error
    assert "LOG 3" in done.stdout and ("x cannot be evaluated" if fault == "get"
                                        else "initialisation failed") in done.stdout
    assert "X 1.0" in done.stdout and "FREED" in done.stdout


def test_without_the_fix_the_exception_is_fatal(probe):
    shipped, _ = probe
    assert "STATUS 4" in host(shipped, "get").stdout  # fmi2Fatal: FMI allows no further call


def test_a_slave_script_that_cannot_be_found_fails_the_instantiation_instead_of_crashing(
        probe, tmp_path):
    _, fixed = probe
    broken = tmp_path / "ErrorProbe.fmu"
    with zipfile.ZipFile(fixed) as source, zipfile.ZipFile(broken, "w") as target:
        for entry in source.infolist():
            if entry.filename != "resources/slavemodule.txt":
                target.writestr(entry, source.read(entry))
    done = host(broken, "")
    assert done.returncode == 1 and "Failed to instantiate model" in done.stderr
    assert "findClass" in done.stdout  # pythonfmu's message, logged
