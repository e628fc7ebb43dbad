"""Helpers the tests import (``from support import ...``): files written for a test and scripts of
orchestration/ loaded as modules."""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

ORCHESTRATION = Path(__file__).resolve().parents[1] / "orchestration"


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
