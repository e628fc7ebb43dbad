"""Helpers the tests import (``from support import ...``): files written for a test, scripts of
orchestration/ loaded as modules, and the real records found through GUIDEWAY_FMU_DATA."""
from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

import pytest

ORCHESTRATION = Path(__file__).resolve().parents[1] / "orchestration"
#: the one setting of the real records' folder (emps-identification/, emps-validation/); no
#: default: outside the repository, only the user knows where it is
DATA = "GUIDEWAY_FMU_DATA"


def write_file(folder: Path, text: str, name: str) -> Path:
    """``text`` written to ``folder``/``name``; the file's path."""
    path = Path(folder) / name
    path.write_text(text)
    return path


def load_script(path: Path):
    """The Python script ``path`` (of orchestration/, not a package module) as a module named
    after its stem, registered in sys.modules while it runs (its dataclasses look it up there),
    whatever held that name before put back after."""
    spec = importlib.util.spec_from_file_location(Path(path).stem, path)
    module = importlib.util.module_from_spec(spec)
    before = sys.modules.get(spec.name)
    sys.modules[spec.name] = module
    try:
        spec.loader.exec_module(module)
    finally:
        if before is None:
            del sys.modules[spec.name]
        else:
            sys.modules[spec.name] = before
    return module


def real_records() -> Path | None:
    """The folder of real records DATA names, None where the variable is unset."""
    folder = os.environ.get(DATA)
    return Path(folder) if folder else None


def real_record(name: str) -> Path:
    """The real record ``name`` (e.g. emps-validation), a folder of :func:`real_records`; skips
    the calling test, naming DATA and what it should point at, where the variable is unset or
    the record is not there."""
    folder = real_records()
    if folder is None:
        pytest.skip(f"{DATA} is not set: point it at the folder of real records "
                    f"(emps-identification/, emps-validation/; orchestration/real_data/README.md)")
    if not (folder / name).is_dir():
        pytest.skip(f"{folder / name} is not a folder: {DATA} must point at the folder holding "
                    f"the real record {name}/")
    return folder / name
