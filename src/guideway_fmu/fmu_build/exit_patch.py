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

import struct
from pathlib import Path

from ..fmi.archive import rewrite

SYMBOL = b"finalizePythonInterpreter"
ENDBR64 = bytes.fromhex("f30f1efa")
RET = b"\xc3"


class ExitPatchError(RuntimeError):
    """The binary is not the pythonfmu 0.7 Linux library this patch knows."""


def _sections(elf: bytes):
    if elf[:4] != b"\x7fELF" or elf[4] != 2 or elf[5] != 1:
        raise ExitPatchError("not a 64-bit little-endian ELF file")
    shoff, = struct.unpack_from("<Q", elf, 0x28)
    shentsize, shnum = struct.unpack_from("<HH", elf, 0x3A)
    for i in range(shnum):
        # sh_name, sh_type, sh_flags, sh_addr, sh_offset, sh_size, sh_link, sh_info, sh_addralign, sh_entsize
        yield struct.unpack_from("<IIQQQQIIQQ", elf, shoff + i * shentsize)


def function_offset(elf: bytes, name: bytes = SYMBOL) -> int:
    """File offset of the exported function ``name`` in the shared library ``elf``."""
    sections = list(_sections(elf))
    dynsym = next((s for s in sections if s[1] == 11), None)  # SHT_DYNSYM
    if dynsym is None:
        raise ExitPatchError("no dynamic symbol table")
    strtab = sections[dynsym[6]]
    for entry in range(dynsym[4], dynsym[4] + dynsym[5], dynsym[9]):
        st_name, st_info, _, st_shndx, st_value, _ = struct.unpack_from("<IBBHQQ", elf, entry)
        start = strtab[4] + st_name
        if elf[start:elf.index(b"\0", start)] == name and st_info & 0xF == 2 and st_shndx:  # FUNC
            section = sections[st_shndx]
            return section[4] + st_value - section[3]
    raise ExitPatchError(f"no function {name.decode()}")


def patch(elf: bytes) -> bytes:
    """``elf`` with ``finalizePythonInterpreter`` returning at once (idempotent)."""
    at = function_offset(elf)
    if elf[at:at + 4] != ENDBR64:
        raise ExitPatchError(f"{SYMBOL.decode()} does not start as in pythonfmu 0.7")
    return elf[:at + 4] + RET + elf[at + 5:]


def patch_fmu(fmu: str | Path) -> Path:
    """Rewrite the FMU archive ``fmu`` with its Linux binaries patched; returns its path."""
    return rewrite(fmu, fmu, patch_entry)


def patch_entry(name: str, data: bytes) -> tuple[str, bytes]:
    """An FMU archive entry with :func:`patch` applied if it is a Linux binary."""
    if name.startswith("binaries/linux64/") and name.endswith(".so"):
        return name, patch(data)
    return name, data
