"""Rewriting an FMU archive entry by entry: the one loop behind the build's finishing, the exit
patch and FMU copies with other start values."""
from __future__ import annotations

import zipfile
from pathlib import Path
from typing import Callable


def rewrite(source: str | Path, target: str | Path,
            transform: Callable[[str, bytes], tuple[str, bytes]]) -> Path:
    """Write ``target`` with every entry of the zip archive ``source`` passed through
    ``transform(name, data) -> (name, data)``; ``target`` may be ``source`` (replaced once the
    new archive is complete). Returns ``target``."""
    source, target = Path(source), Path(target)
    partial = target.with_name(target.name + ".partial")
    try:
        with zipfile.ZipFile(source) as src, \
                zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as dst:
            for info in src.infolist():
                dst.writestr(*transform(info.filename, src.read(info)))
    except BaseException:
        partial.unlink(missing_ok=True)  # nothing half-written left beside the target
        raise
    partial.replace(target)
    return target
