#!/usr/bin/env python3
"""Set up a local virtual environment (.venv) and run the main job or the tests.

    python3 bootstrap.py demo [args...]   the demo (guideway-fmu demo)
    python3 bootstrap.py test [args...]   the whole test suite: the tests on every core
                                          (pytest-xdist), then those marked serial alone;
                                          args go to both passes (paths, -k, -x)

Needs only Python 3.11+ with venv; everything else comes from PyPI into .venv. It checks
the version first, in a form older Pythons (3.6 on) still parse.
"""
import os
import shutil
import subprocess
import sys
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parent
VENV = ROOT / ".venv"
BIN = VENV / ("Scripts" if sys.platform == "win32" else "bin")
LOG = VENV / "pip-install.log"
NEEDS = (3, 11)  # pyproject.toml's requires-python
NO_TESTS = 5  # pytest's exit status when a pass selects no test


def _run(*cmd) -> int:
    print("+", " ".join(map(str, cmd)), flush=True)
    return subprocess.call([str(c) for c in cmd], cwd=ROOT)


def _setup() -> "str | None":
    """Create .venv and install the package with its test tools; None, or the one line that
    says what failed and what is needed."""
    if not (BIN / "python").exists():
        try:
            venv.EnvBuilder(with_pip=True).create(VENV)
        except (OSError, subprocess.CalledProcessError) as exc:
            shutil.rmtree(VENV, ignore_errors=True)  # the next run starts afresh
            return (f"cannot create {VENV} ({exc}); Python's venv module with ensurepip is "
                    "needed (Debian, Ubuntu: apt install python3-venv)")
    print(f"+ pip install -e .[test] into {VENV} (log: {LOG})", flush=True)
    with LOG.open("w") as log:
        status = subprocess.call([str(BIN / "python"), "-m", "pip", "install", "-e",
                                  f"{ROOT}[test]"], cwd=ROOT, stdout=log, stderr=subprocess.STDOUT)
    if status != 0:
        errors = [line for line in LOG.read_text().splitlines() if line.startswith("ERROR")]
        return (f"installing the package into {VENV} failed: "
                f"{errors[-1] if errors else 'see the log'} (all of it: {LOG})")
    return None


def workers() -> int:
    """The cores this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


def test(args: "list[str]", python: Path = BIN / "python") -> int:
    """The suite in two passes: every test not marked serial on all cores, then the serial ones
    (they measure memory or start process pools and Dask clusters of their own) alone.
    The worse status of the two; a pass that selects nothing counts as passed unless both do.
    ``python``: the interpreter with the package and pytest (benchmarks/workday.py passes its
    own)."""
    pytest = [python, "-m", "pytest"]
    statuses = [_run(*pytest, "-m", "not serial", "-n", workers(), *args),
                _run(*pytest, "-m", "serial", "-n", "0", *args)]
    ran = [status for status in statuses if status != NO_TESTS]
    return max(ran) if ran else NO_TESTS


def main(argv: "list[str]") -> int:
    if sys.version_info < NEEDS:
        print(f"bootstrap: guideway-fmu needs Python {'.'.join(map(str, NEEDS))} or newer; this "
              f"is {sys.version.split()[0]} ({sys.executable}): run bootstrap.py with a newer "
              "python3", file=sys.stderr)
        return 1
    if not argv or argv[0] not in ("demo", "test"):
        print(__doc__, file=sys.stderr)
        return 2
    problem = _setup()
    if problem:
        print(f"bootstrap: {problem}", file=sys.stderr)
        return 1
    if argv[0] == "demo":
        return _run(BIN / "guideway-fmu", "demo", *argv[1:])
    return test(argv[1:])


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
