"""The package as a user gets it: a wheel built from the sources, installed into a fresh virtual
environment, runs ``guideway-fmu`` with its examples from an unrelated folder.

Nothing is downloaded: the wheel is built with this environment's setuptools (no build
isolation), and the fresh environment finds the dependencies (numpy, fmpy, ...) in this one's
site-packages through a .pth file, while guideway_fmu itself comes from the wheel."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import venv
import zipfile
from importlib.metadata import version
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow  # a wheel built and installed: about half a minute

REPO = Path(__file__).resolve().parents[1]


def _run(*command, cwd, env=None) -> subprocess.CompletedProcess:
    done = subprocess.run([str(c) for c in command], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, f"{command}:\n{done.stdout[-2000:]}\n{done.stderr[-3000:]}"
    return done


def test_a_wheel_installs_a_command_that_runs_its_examples_from_anywhere(tmp_path):
    if tuple(map(int, version("setuptools").split(".")[:2])) < (70, 1):
        pytest.fail(f"setuptools {version('setuptools')} cannot build the wheel without build "
                    "isolation: install the test extra (pip install -e .[test] needs >= 70.1)")
    source = tmp_path / "source"  # what the sdist holds: no build folder left from earlier builds
    shutil.copytree(REPO / "src", source / "src",
                    ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(REPO / name, source)
    _run(sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "--no-index",
         "--wheel-dir", tmp_path / "wheels", source, cwd=tmp_path)
    (wheel,) = (tmp_path / "wheels").glob("guideway_fmu-*.whl")
    inside = set(zipfile.ZipFile(wheel).namelist())
    assert {"guideway_fmu/examples/measured_run/data.csv", "guideway_fmu/examples/README.md",
            "guideway_fmu/examples/ball_guides/wu2012_table2_moment_0.toml",
            "guideway_fmu/scenarios/soleimanian2020_unloaded.toml",
            "guideway_fmu/scenarios/sweeps/soleimanian2020_envelope_vs_frequency.toml",
            "guideway_fmu/fmu_build/c_host.c", "guideway_fmu/fmu_build/native/fmi2_slave.c",
            "guideway_fmu/fmu_build/native/gw_runtime.h"} <= inside
    assert not any(n.startswith(("tests/", "benchmarks/", "orchestration/")) for n in inside)

    fresh = tmp_path / "venv"
    venv.create(fresh, with_pip=False)
    python = fresh / ("Scripts/python.exe" if sys.platform == "win32" else "bin/python")
    purelib = Path(_run(python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])",
                        cwd=tmp_path).stdout.strip())
    shared = [p for p in sys.path if Path(p).name in ("site-packages", "dist-packages")]
    (purelib / "dependencies.pth").write_text("\n".join(shared) + "\n")
    _run(sys.executable, "-m", "pip", "--python", python, "install", "--no-index", "--no-deps",
         "--force-reinstall", wheel, cwd=tmp_path)

    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    command = python.parent / "guideway-fmu"
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    where = _run(python, "-c", "import guideway_fmu; print(guideway_fmu.__file__)",
                 cwd=elsewhere, env=env).stdout
    assert Path(where.strip()).is_relative_to(purelib)  # the wheel's, not the sources'
    assert _run(command, "--version", cwd=elsewhere, env=env).stdout.startswith("guideway-fmu 0.")
    listed = _run(command, "examples", "x", cwd=elsewhere, env=env).stdout.splitlines()
    assert "x/ball_guides/wu2012_table2_moment_0.toml" in listed
    modes = _run(command, "modes", "x/ball_guides/wu2012_table2_moment_0.toml", cwd=elsewhere,
                 env=env).stdout
    assert "pitching" in modes and "yawing" in modes
    # FMUs built from the installed package (its own files found among site-packages)
    env["GUIDEWAY_FMU_CACHE"] = str(tmp_path / "cache")
    _run(command, "run", "soleimanian2020_unloaded", "--stop", "0.0004", "--out", "run",
         "--no-progress", cwd=elsewhere, env=env)
    assert (elsewhere / "run" / "results.csv").is_file()
    for edition in ("python", "native"):  # the native edition compiled from the installed C
        _run(command, "run", "soleimanian2020_9000N_4500Hz", "--stop", "0.0004", "--out", edition,
             "--edition", edition, "--no-progress", cwd=elsewhere, env=env)
    assert (elsewhere / "native" / "results.csv").read_text() == \
        (elsewhere / "python" / "results.csv").read_text()
