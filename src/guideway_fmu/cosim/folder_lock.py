"""One writer per output folder: a run, sweep or diagnosis holds an exclusive lock on its
``--out`` folder while it writes there, and a second one into the same folder is refused at
once (two runs into one folder both exited 0 over a results.csv with NUL bytes and rows of mixed
lengths).

The lock is ``fcntl.flock`` on LOCK_FILE inside the folder. The kernel releases it when its file
is closed, which leaving :func:`folder_lock` does on every way out, and when the process ends
however it ends (a step timeout or a signal that ends it, a crash, SIGKILL). The file stays:
removing it would let a third writer lock a new file while a second still held the old one. It
holds the holder's process id, for the message of the refused one.
"""
from __future__ import annotations

import contextlib
import fcntl
import os
from pathlib import Path

LOCK_FILE = ".guideway-fmu.lock"


class FolderInUse(OSError):
    """Another run, sweep or diagnosis writes into the folder (holds its lock)."""


@contextlib.contextmanager
def folder_lock(folder: str | Path):
    """Create ``folder`` if needed and hold its lock while entered; FolderInUse naming the
    folder (and the holder's process id where it is known) if another holds it."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / LOCK_FILE
    fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(fd, 32, 0).decode("ascii", "replace").strip()
            raise FolderInUse(
                f"{folder}: another run writes into this folder (process "
                f"{holder or 'unknown'} holds {path}); wait for it to end or choose another "
                "output folder") from None
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
        yield folder
    finally:
        os.close(fd)  # releases the lock
