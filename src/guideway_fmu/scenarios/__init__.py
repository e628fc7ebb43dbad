"""The shipped scenarios: the cases of Soleimanian et al. (2020) as TOML systems.

Written by ``orchestration/make_soleimanian2020_scenarios.py`` (edit that, not the files). They
name their FMUs by file name only, so every command finds them in one FMU folder (``--fmus``,
default ``./fmus``, built on demand) from any working directory.
"""
from __future__ import annotations

from pathlib import Path

FOLDER = Path(__file__).resolve().parent


def names() -> list[str]:
    """The shipped scenarios' names (file stems), sorted."""
    return sorted(p.stem for p in FOLDER.glob("*.toml"))


def find(scenario: str | Path) -> Path:
    """The file of a scenario given by path or by a shipped scenario's name; ValueError naming
    the shipped ones when it is neither."""
    path = Path(scenario)
    if path.is_file():
        return path
    shipped = FOLDER / f"{path.name.removesuffix('.toml')}.toml"
    if path.parent == Path(".") and shipped.is_file():
        return shipped
    raise ValueError(f"scenario {str(scenario)!r} is neither a file nor a shipped scenario; "
                     f"shipped: {', '.join(names())}")


def is_shipped(path: Path) -> bool:
    """Whether ``path`` is one of the shipped scenario files."""
    return Path(path).resolve().parent == FOLDER
