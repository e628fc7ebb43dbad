"""The FMU cache: every FMU built once for its code and edition, shared by the commands, the
processes of a sweep and the workers of the test suite.

The cache folder is ``GUIDEWAY_FMU_CACHE`` when set, else the user's cache folder
(``XDG_CACHE_HOME`` or ``~/.cache`` on Linux, ``~/Library/Caches`` on macOS, ``%LOCALAPPDATA%``
on Windows) + ``guideway-fmu``; never the current folder unless told so. In it::

    <edition>/<FMU>-<code hash>.fmu        one FMU, built once (build.fmu_hash: its code and
                                           the code that packs it); a native set takes the
                                           python edition's file of a component without a
                                           native edition
    <edition>/sets/<set hash>/<FMU>.fmu    every FMU of one state of the package under its own
                                           name (hard links to the above) and README.md: the
                                           folder the commands take FMUs from by file name

The edition is how an FMU runs (fmu_build.EDITIONS): "python" (pythonfmu, in the host's
Python) or "native" (compiled C where the component has a native edition, python elsewhere: a
native set holds every FMU, so a scenario runs from it unchanged). Builds happen
under a lock on the edition's folder, and a set folder is made beside and renamed into place, so
processes that start together build each FMU once and never see a folder half made. Anything in
the cache may be deleted; what is missing is built again.
"""
from __future__ import annotations

import contextlib
import hashlib
import os
import shutil
import sys
import tempfile
from pathlib import Path

from ..components import registry
from . import build

ENVIRONMENT = "GUIDEWAY_FMU_CACHE"  # the setting that moves the cache


def root() -> Path:
    """The cache folder (module doc), absolute."""
    chosen = os.environ.get(ENVIRONMENT)
    if chosen:
        return Path(chosen).expanduser().resolve()
    home = Path.home()
    if sys.platform == "win32":
        base = Path(os.environ.get("LOCALAPPDATA") or home / "AppData" / "Local")
    elif sys.platform == "darwin":
        base = home / "Library" / "Caches"
    else:
        xdg = os.environ.get("XDG_CACHE_HOME")
        base = Path(xdg) if xdg and Path(xdg).is_absolute() else home / ".cache"
    return base / "guideway-fmu"


def folder(edition: str = "python") -> Path:
    """The cache's folder of every FMU of this package as its code stands, in ``edition``,
    building what the cache lacks. ValueError for an unknown edition; OSError naming the cache
    folder when it cannot be written."""
    build.edition_of("", edition)  # an unknown edition is refused before anything is built
    hashes = {n: build.fmu_hash(registry.component(n), edition) for n in registry.names()}
    base = root() / edition
    done = base / "sets" / hashlib.sha256(
        "\n".join(f"{n} {h}" for n, h in hashes.items()).encode()).hexdigest()[:10]
    if _complete(done, hashes):
        return done
    try:
        (base / "sets").mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OSError(f"the FMU cache {root()} cannot be written ({exc.strerror or exc}); set "
                      f"{ENVIRONMENT} to another folder or pass --fmus") from exc
    with _locked(base / "lock"), tempfile.TemporaryDirectory(prefix=".new-", dir=base) as tmp:
        if _complete(done, hashes):  # another process made it while this one waited
            return done
        stored = {n: root() / build.edition_of(n, edition) / f"{n}-{h}.fmu"
                  for n, h in hashes.items()}
        missing = [(registry.component(n), Path(tmp) / f"{n}.fmu")
                   for n, path in stored.items() if not path.is_file()]
        for fmu in build.pack_edition(missing, edition) if missing else []:
            stored[fmu.stem].parent.mkdir(parents=True, exist_ok=True)
            os.replace(fmu, stored[fmu.stem])
        made = Path(tmp) / "set"
        made.mkdir()
        for name, path in stored.items():
            _link(path, made / f"{name}.fmu")
        build.write_readme(made, sorted(made.glob("*.fmu")))
        shutil.rmtree(done, ignore_errors=True)  # a set folder someone emptied in part
        os.replace(made, done)
    return done


def _complete(done: Path, hashes: dict[str, str]) -> bool:
    return all((done / f"{name}.fmu").is_file() for name in hashes) and \
        (done / "README.md").is_file()


def _link(source: Path, target: Path) -> None:
    """``target`` as a hard link to ``source``, a copy where the file system has none."""
    try:
        os.link(source, target)
    except OSError:
        shutil.copy2(source, target)


@contextlib.contextmanager
def _locked(path: Path):
    """Hold an exclusive lock on the file ``path`` (made if missing) while the block runs; the
    system releases it if the process dies."""
    with open(path, "a+b") as handle:
        if sys.platform == "win32":
            import msvcrt
            while True:
                try:  # LK_LOCK gives up after 10 s: another process is still building
                    msvcrt.locking(handle.fileno(), msvcrt.LK_LOCK, 1)
                    break
                except OSError:
                    continue
            try:
                yield
            finally:
                handle.seek(0)
                msvcrt.locking(handle.fileno(), msvcrt.LK_UNLCK, 1)
        else:
            import fcntl
            fcntl.flock(handle.fileno(), fcntl.LOCK_EX)
            yield  # released when the file closes
