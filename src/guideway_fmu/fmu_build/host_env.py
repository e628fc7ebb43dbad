"""The environment a C host (a tool that dlopens FMUs, as libcosim and commercial tools do) needs to
run our FMUs with the current Python, and a check that runs one FMU in such a host.

A pythonfmu FMU embeds the interpreter: the host process must have ``libpython`` loaded with its
symbols global before it opens the FMU (``LD_PRELOAD``), and the interpreter must find its
standard library (``PYTHONHOME``) and a ``site-packages`` with numpy and scipy (``PYTHONPATH``).
The check compiles ``c_host.c`` (a plain FMI 2.0 host) with the system's C compiler and runs one
FMU in it, in a child process given only that environment.
"""
from __future__ import annotations

import os
import shlex
import shutil
import site
import subprocess
import sys
import sysconfig
import tempfile
import zipfile
from dataclasses import dataclass
from pathlib import Path

import fmpy
from fmpy import read_model_description

C_HOST_SOURCE = Path(__file__).with_name("c_host.c")


class HostEnvError(RuntimeError):
    """The current interpreter cannot serve a C host, or the check could not be run."""


def host_environment() -> dict[str, str]:
    """``LD_PRELOAD``, ``PYTHONHOME`` and ``PYTHONPATH`` for a C host using this interpreter."""
    if sys.platform != "linux":
        raise HostEnvError(f"host-env knows the C-host environment on Linux only, not {sys.platform}")
    if not sysconfig.get_config_var("Py_ENABLE_SHARED"):
        raise HostEnvError(f"{sys.executable} is built without a shared libpython; a C host "
                           "needs one (a Python configured with --enable-shared)")
    libpython = Path(sysconfig.get_config_var("LIBDIR")) / sysconfig.get_config_var("INSTSONAME")
    if not libpython.is_file():
        raise HostEnvError(f"libpython of {sys.executable} not found at {libpython}")
    paths = [p for p in site.getsitepackages() if Path(p).is_dir()]
    return {"LD_PRELOAD": str(libpython), "PYTHONHOME": sys.base_prefix,
            "PYTHONPATH": os.pathsep.join(paths)}


def exports(environment: dict[str, str]) -> str:
    """``environment`` as shell ``export`` lines."""
    return "".join(f"export {k}={shlex.quote(v)}\n" for k, v in environment.items())


def compile_c_host(out_dir: Path, platform: str | None = None) -> Path:
    """Compile ``c_host.c`` into ``out_dir`` for this platform, or cross-compile it for
    ``platform`` (fmu_build.native.build.compiler); returns the executable."""
    headers = Path(fmpy.__file__).parent / "c-code"
    if platform is None:
        compiler = shutil.which("cc") or shutil.which("gcc")
        if compiler is None:
            raise HostEnvError("no C compiler (cc or gcc) on PATH to build the C host of the check")
        command, executable = [compiler], Path(out_dir) / "c_host"
    else:
        from .native.build import compiler as cross
        command, executable = cross(platform), Path(out_dir) / f"c_host_{platform}"
        executable = executable.with_suffix(".exe") if platform == "win64" else executable
    result = subprocess.run([*command, "-O1", "-o", str(executable), str(C_HOST_SOURCE),
                             f"-I{headers}", *([] if platform == "win64" else ["-ldl"])],
                            capture_output=True, text=True)
    if result.returncode != 0:
        raise HostEnvError(f"compiling {C_HOST_SOURCE.name} failed:\n{result.stderr}")
    return executable


@dataclass
class HostRun:
    """One run of an FMU in the C host: exit status, the outputs after the last step, stderr."""

    fmu: Path
    status: int
    outputs: dict[str, float]
    stderr: str


def run_in_c_host(executable: Path, fmu: str | Path, environment: dict[str, str], *,
                  work_dir: Path, steps: int = 10, step_size: float | None = None,
                  start_values: dict[str, float | str] | None = None,
                  platform: str = "linux64", launcher: tuple[str, ...] = ()) -> HostRun:
    """Run ``fmu`` for ``steps`` steps (default step: its DefaultExperiment's) in the C host
    ``executable``, in a child whose environment is ``environment`` and PATH only, with the Real
    or String variables of ``start_values`` (by name) set before initialisation; the binary of
    ``platform``, the host started by ``launcher`` where it needs one (wine)."""
    fmu = Path(fmu)
    try:
        md = read_model_description(str(fmu))
    except (OSError, ValueError, zipfile.BadZipFile) as exc:  # fmpy's messages, with the file
        raise HostEnvError(f"{fmu}: not an FMU that can be read: {exc}") from exc
    by_name = {v.name: v for v in md.modelVariables}
    settings = []
    for name, value in (start_values or {}).items():
        if name not in by_name or by_name[name].type not in ("Real", "String"):
            raise HostEnvError(f"{fmu.name} has no Real or String variable {name!r}")
        kind = "r" if by_name[name].type == "Real" else "s"
        settings.append(f"{kind}:{by_name[name].valueReference}={value}")
    unpacked = Path(tempfile.mkdtemp(prefix=f"{fmu.stem}_", dir=work_dir))
    with zipfile.ZipFile(fmu) as archive:
        archive.extractall(unpacked)
    outputs = [v for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
    h = step_size or (md.defaultExperiment.stepSize if md.defaultExperiment else 1e-4)
    from .native.build import CROSS
    suffix = CROSS[platform][1]
    binary = unpacked / "binaries" / platform / f"{md.coSimulation.modelIdentifier}{suffix}"
    command = [*launcher, str(executable), str(binary), (unpacked / "resources").as_uri(), md.guid,
               repr(float(h)), str(steps), *settings, *[str(v.valueReference) for v in outputs]]
    result = subprocess.run(command, capture_output=True, text=True,
                            env={"PATH": os.environ.get("PATH", ""), **environment})
    values = result.stdout.split()[1:] if result.returncode == 0 else []
    shutil.rmtree(unpacked, ignore_errors=True)
    return HostRun(fmu, result.returncode, dict(zip((v.name for v in outputs), map(float, values))),
                   result.stderr)


def check(fmu: str | Path | None = None, environment: dict[str, str] | None = None) -> HostRun:
    """Run ``fmu`` (default: FeedKinematics, built for the check) in the compiled C host with
    ``environment`` (default: :func:`host_environment`); the caller judges ``status``."""
    from .build import build

    environment = environment or host_environment()
    with tempfile.TemporaryDirectory(prefix="guideway_fmu_host_env_") as tmp:
        tmp = Path(tmp)
        fmu = Path(fmu) if fmu is not None else build(tmp / "fmus", ["FeedKinematics"])[0]
        if not fmu.is_file():
            raise HostEnvError(f"no FMU at {fmu}")
        return run_in_c_host(compile_c_host(tmp), fmu, environment, work_dir=tmp)
