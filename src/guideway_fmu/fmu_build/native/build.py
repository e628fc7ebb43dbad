"""Compile a component's C unit and pack it as an FMI 2.0 co-simulation FMU.

The FMU holds the modelDescription of the Python edition (same variables, units, start values,
ModelStructure and DefaultExperiment) with the co-simulation capabilities of the native one,
the shared library for this platform under ``binaries/<platform>/`` and, under ``sources/``,
the C it was compiled from. The compiler is ``cc`` unless GUIDEWAY_FMU_CC names another.
"""
from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path
from xml.etree import ElementTree

import fmpy

from ..build import code_hash, shipped_files
from .component import Unit

HERE = Path(__file__).resolve().parent
RUNTIME = ("gw_runtime.h", "fmi2_slave.c")
FMI_HEADERS = ("fmi2Functions.h", "fmi2FunctionTypes.h", "fmi2TypesPlatform.h")
PLATFORM = fmpy.platform  # linux64, win64, darwin64
SUFFIX = {"win64": ".dll", "darwin64": ".dylib"}.get(PLATFORM, ".so")
CAPABILITIES = {"needsExecutionTool": "false", "canHandleVariableCommunicationStepSize": "true",
                "canGetAndSetFMUstate": "true", "canSerializeFMUstate": "true",
                "canNotUseMemoryManagementFunctions": "true", "canBeInstantiatedOnlyOncePerProcess":
                "false"}


def sources(cls, folder: Path) -> tuple[Path, str]:
    """Write the C sources of ``cls`` into ``folder``: (the unit's path, its GUID)."""
    unit = Unit(cls)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{cls.__name__}.c"
    path.write_text(unit.text, encoding="utf-8")
    for name in RUNTIME:
        shutil.copy2(HERE / name, folder / name)
    headers = Path(fmpy.__file__).parent / "c-code"
    for name in FMI_HEADERS:
        shutil.copy2(headers / name, folder / name)
    return path, unit.guid


def compile_unit(unit: Path, library: Path) -> Path:
    """Compile ``unit`` (with the files beside it) into the shared library ``library``."""
    compiler = shlex.split(os.environ.get("GUIDEWAY_FMU_CC", "cc"))
    command = [*compiler, "-shared", "-fPIC", "-O2", "-std=c99", "-D_DEFAULT_SOURCE",
               "-fvisibility=default", "-Wall", "-Wno-unused-label", "-Wno-unused-function",
               "-Wno-unused-variable", "-Wno-unused-but-set-variable", "-o", str(library),
               str(unit), "-lm"]
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        raise RuntimeError(f"compiling {unit.name} failed ({' '.join(command)}):\n"
                           f"{result.stderr[-4000:]}")
    return library


def native_hash(cls) -> str:
    """The code hash of the native FMU of ``cls``: its Python definition, the translator and
    the C runtime (fmu_build.build.code_hash)."""
    return code_hash(sorted({*shipped_files(cls), *HERE.glob("*.py"),
                             *(HERE / name for name in RUNTIME)}))


def model_description(cls, guid: str) -> bytes:
    """The Python edition's modelDescription with the native edition's capabilities; the
    generationTool names the code hash (fmu_build.build.built_edition reads it)."""
    example = cls(instance_name="native", resources=None)
    root = example.to_xml()
    root.set("guid", f"{{{guid}}}")
    root.set("generationTool", f"guideway-fmu native edition {native_hash(cls)}")
    cosim = root.find("CoSimulation")
    cosim.attrib.update(CAPABILITIES)
    cosim.set("modelIdentifier", cls.__name__)
    ElementTree.indent(root)
    return ElementTree.tostring(root, encoding="utf-8", xml_declaration=True)


def build_native(cls, dest: str | Path) -> Path:
    """Build the native edition of the component class ``cls`` as the FMU file ``dest``."""
    dest = Path(dest)
    with tempfile.TemporaryDirectory(prefix="guideway_fmu_native_") as tmp:
        folder = Path(tmp) / "sources"
        unit, guid = sources(cls, folder)
        library = compile_unit(unit, Path(tmp) / f"{cls.__name__}{SUFFIX}")
        dest.parent.mkdir(parents=True, exist_ok=True)
        partial = dest.with_name(dest.name + ".partial")
        with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as archive:
            archive.writestr("modelDescription.xml", model_description(cls, guid))
            archive.write(library, f"binaries/{PLATFORM}/{library.name}")
            for path in sorted(folder.iterdir()):
                archive.write(path, f"sources/{path.name}")
        partial.replace(dest)
    return dest


if __name__ == "__main__":  # python -m guideway_fmu.fmu_build.native.build NAME OUT.fmu
    from ...components import registry
    print(build_native(registry.component(sys.argv[1]), sys.argv[2]))
