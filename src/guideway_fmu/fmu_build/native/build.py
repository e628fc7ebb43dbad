"""Compile a component's C unit and pack it as an FMI 2.0 co-simulation FMU.

The FMU holds the modelDescription of the Python edition (same variables, units, start values,
ModelStructure and DefaultExperiment) with the co-simulation capabilities of the native one,
a shared library under ``binaries/<platform>/`` for this platform and, when asked, for the
others of CROSS, and under ``sources/`` the C it was compiled from (a host of another platform
can compile it). This platform's compiler is ``cc`` unless GUIDEWAY_FMU_CC names another; the
others are cross-compiled with zig's C compiler (the ``ziglang`` package: ``pip install
'guideway-fmu[cross]'``).
"""
from __future__ import annotations

import importlib.util
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
from . import GENERATION_TOOL
from .component import Unit

HERE = Path(__file__).resolve().parent
RUNTIME = ("gw_runtime.h", "fmi2_slave.c")
FMI_HEADERS = ("fmi2Functions.h", "fmi2FunctionTypes.h", "fmi2TypesPlatform.h")
PLATFORM = fmpy.platform  # linux64, win64, darwin64
#: FMI platform -> (zig's target, the shared library's suffix)
CROSS = {"linux64": ("x86_64-linux-gnu", ".so"), "win64": ("x86_64-windows-gnu", ".dll"),
         "darwin64": ("x86_64-macos", ".dylib")}
SUFFIX = CROSS.get(PLATFORM, ("", ".so"))[1]
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


def compiler(platform: str = PLATFORM) -> list[str]:
    """The C compiler command for ``platform``: this one's (module doc), or zig's cross compiler
    (RuntimeError naming the package to install when it is missing)."""
    if platform == PLATFORM:
        return shlex.split(os.environ.get("GUIDEWAY_FMU_CC", "cc"))
    if platform not in CROSS:
        raise ValueError(f"unknown platform {platform!r}; known: {', '.join(CROSS)}")
    if importlib.util.find_spec("ziglang") is None:
        raise RuntimeError(f"cross-compiling for {platform} needs zig's C compiler: "
                           "pip install 'guideway-fmu[cross]' (the ziglang package)")
    return [sys.executable, "-m", "ziglang", "cc", "-target", CROSS[platform][0]]


def compile_unit(unit: Path, library: Path, platform: str = PLATFORM) -> Path:
    """Compile ``unit`` (with the files beside it) into the shared library ``library`` for
    ``platform``."""
    command = [*compiler(platform), "-shared", "-O2", "-std=c99", "-D_DEFAULT_SOURCE",
               "-Wall", "-Wno-unused-label", "-Wno-unused-function",
               "-Wno-unused-variable", "-Wno-unused-but-set-variable", "-o", str(library),
               str(unit)] + ([] if platform == "win64" else ["-fPIC", "-fvisibility=default",
                                                             "-lm"])
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
    root.set("generationTool", f"{GENERATION_TOOL} {native_hash(cls)}")
    cosim = root.find("CoSimulation")
    cosim.attrib.update(CAPABILITIES)
    cosim.set("modelIdentifier", cls.__name__)
    ElementTree.indent(root)
    return ElementTree.tostring(root, encoding="utf-8", xml_declaration=True)


def build_native(cls, dest: str | Path, platforms: tuple[str, ...] = (PLATFORM,)) -> Path:
    """Build the native edition of the component class ``cls`` as the FMU file ``dest``, with a
    binary for each of ``platforms`` (module doc)."""
    dest = Path(dest)
    with tempfile.TemporaryDirectory(prefix="guideway_fmu_native_") as tmp:
        folder = Path(tmp) / "sources"
        unit, guid = sources(cls, folder)
        libraries = {}
        for platform in dict.fromkeys(platforms):
            (Path(tmp) / platform).mkdir()
            suffix = CROSS.get(platform, ("", SUFFIX))[1]
            libraries[platform] = compile_unit(
                unit, Path(tmp) / platform / f"{cls.__name__}{suffix}", platform)
        dest.parent.mkdir(parents=True, exist_ok=True)
        partial = dest.with_name(dest.name + ".partial")
        with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as archive:
            archive.writestr("modelDescription.xml", model_description(cls, guid))
            for platform, library in libraries.items():
                archive.write(library, f"binaries/{platform}/{library.name}")
            for path in sorted(folder.iterdir()):
                archive.write(path, f"sources/{path.name}")
        partial.replace(dest)
    return dest


if __name__ == "__main__":  # python -m guideway_fmu.fmu_build.native.build NAME OUT.fmu [PLATFORM ...]
    from ...components import registry
    print(build_native(registry.component(sys.argv[1]), sys.argv[2],
                       tuple(sys.argv[3:]) or (PLATFORM,)))
