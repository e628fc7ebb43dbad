"""Make the Linux binary of pythonfmu 0.7 safe at process exit (applied by the build).

pythonfmu keeps the embedded interpreter in a static ``std::shared_ptr<PyState>``, whose
destructor (registered with ``__cxa_atexit``) finalises the interpreter and frees it, and declares
``finalizePythonInterpreter`` (``pyState = nullptr``) a destructor of the library as well. On
Linux the exit handlers run the shared pointer's destructor first, so ``finalizePythonInterpreter``
then decrements the use count inside the freed block. Whether that write lands in a chunk glibc
is using decides the outcome: C hosts died at exit with ``free(): corrupted unsorted chunks``
(HorizontalRig in every run from one folder, none from another), and Python hosts with
``corrupted double-linked list`` in about 3.5 % of runs. The function only repeats what the
destructor already did, so the build makes it return at once: one byte, after checking that the
function starts as pythonfmu 0.7's does. The Windows binary calls it from ``DllMain`` before the
static destructors run, which is safe, and is left unchanged.
"""
from __future__ import annotations

from pathlib import Path

from ..fmi.archive import rewrite
from .elf import PatchError, function_offset

SYMBOL = b"finalizePythonInterpreter"
ENDBR64 = bytes.fromhex("f30f1efa")
RET = b"\xc3"


def patch(elf: bytes) -> bytes:
    """``elf`` with ``finalizePythonInterpreter`` returning at once (idempotent)."""
    at = function_offset(elf, SYMBOL)
    if elf[at:at + 4] != ENDBR64:
        raise PatchError(f"{SYMBOL.decode()} does not start as in pythonfmu 0.7")
    return elf[:at + 4] + RET + elf[at + 5:]


def patch_fmu(fmu: str | Path) -> Path:
    """Rewrite the FMU archive ``fmu`` with its Linux binaries patched; returns its path."""
    return rewrite(fmu, fmu, patch_entry)


def patch_entry(name: str, data: bytes) -> tuple[str, bytes]:
    """An FMU archive entry with :func:`patch` applied if it is a Linux binary."""
    if name.startswith("binaries/linux64/") and name.endswith(".so"):
        return name, patch(data)
    return name, data
