#!/usr/bin/env python3
"""Set up a local virtual environment (.venv) and run the main job or the tests.

    python3 bootstrap.py demo [args...]   build the FMUs and run the demo (guideway-fmu demo)
    python3 bootstrap.py test [args...]   run the test suite (pytest)

Needs only Python 3.10+ with venv; everything else comes from PyPI into .venv.
"""
from __future__ import annotations

import subprocess
import sys
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parent
VENV = ROOT / ".venv"
BIN = VENV / ("Scripts" if sys.platform == "win32" else "bin")


def _run(*cmd) -> int:
    print("+", " ".join(map(str, cmd)), flush=True)
    return subprocess.call([str(c) for c in cmd], cwd=ROOT)


def main(argv: list[str]) -> int:
    if not argv or argv[0] not in ("demo", "test"):
        print(__doc__, file=sys.stderr)
        return 2
    if not (BIN / "python").exists():
        venv.EnvBuilder(with_pip=True).create(VENV)
    if _run(BIN / "python", "-m", "pip", "install", "--quiet", "-e", f"{ROOT}[test]") != 0:
        print("bootstrap: installing the package into .venv failed", file=sys.stderr)
        return 1
    if argv[0] == "demo":
        return _run(BIN / "guideway-fmu", "demo", *argv[1:])
    return _run(BIN / "python", "-m", "pytest", *argv[1:])


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
