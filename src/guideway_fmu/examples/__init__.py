"""The example inputs shipped with the package, copied out by ``guideway-fmu examples DIR``.

    README.md      what each is and a command to try
    ball_guides/   case files of the modes, feed-unit, ball-to-ball and wear commands
    measured_run/  a small measured run for diagnose (rig.toml, data.csv; its README.md gives
                   the command that made it)
    scenarios/     the shipped scenarios and sweeps (guideway_fmu/scenarios), copied beside them
"""
from __future__ import annotations

import shutil
from pathlib import Path

from .. import scenarios

FOLDER = Path(__file__).resolve().parent
KINDS = (".md", ".toml", ".csv")  # the examples' files (the folder also holds this module)


def sources() -> dict[Path, Path]:
    """Every example: its path in the folder it is copied into -> the shipped file."""
    found = {p.relative_to(FOLDER): p for p in FOLDER.rglob("*")
             if p.is_file() and p.suffix in KINDS}
    found.update({Path("scenarios") / p.relative_to(scenarios.FOLDER): p
                  for p in scenarios.FOLDER.rglob("*.toml")})
    return dict(sorted(found.items()))


def copy_out(dest: str | Path) -> list[Path]:
    """Copy every example into the folder ``dest`` (made if missing) and return the files
    written. FileExistsError naming the files already there, before anything is copied: none
    is overwritten."""
    dest = Path(dest)
    if dest.exists() and not dest.is_dir():
        raise NotADirectoryError(f"{dest} is a file, not a folder to copy the examples into")
    targets = {dest / name: source for name, source in sources().items()}
    there = [str(name) for name in sources() if (dest / name).exists()]
    if there:
        raise FileExistsError(f"{dest}: {len(there)} of the examples' files exist already and "
                              f"are not overwritten: {', '.join(there)}; nothing was copied")
    for target, source in targets.items():
        target.parent.mkdir(parents=True, exist_ok=True)
        with source.open("rb") as read, target.open("xb") as write:
            shutil.copyfileobj(read, write)
    return list(targets)
