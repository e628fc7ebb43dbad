"""A Python exception in an FMI call of our FMUs is fmi2Error, not a freed instance (applied by
the build to pythonfmu 0.7's Linux binary).

pythonfmu's ``PySlaveInstance::handle_py_exception`` (PySlaveInstance.cpp), which every FMI call
runs when its Python call failed, releases the slave object, its class and its log queue
(``cleanPyObject``, whose pointers it leaves set) and throws ``pythonfmu::fatal_error``, which
fmi2.cpp reports as fmi2Fatal. The instance is then freed memory that any later call touches:
a host that frees the instance after the error, as FMI allows after fmi2Error, crashed. When the
failed call left no Python error (the slave script not found under the resource path) it
returned instead, and the constructor went on to call a null class: a segfault at
instantiation. The fix, nine bytes of that function:

* the three reference decrements of the inlined ``cleanPyObject`` subtract 0: the instance, its
  class and its log queue stay alive, and fmi2FreeInstance releases them once, as it does for an
  instance that never failed;
* the exception is thrown with the type information of its base ``std::runtime_error`` (loaded
  from the base-class field of ``fatal_error``'s type information), so fmi2.cpp's functions catch
  it as a ``std::exception`` and return fmi2Error with its message logged;
* without a Python error it throws too ("unknown error"): fmi2Instantiate returns NULL.

Each site is checked to hold pythonfmu 0.7.0's bytes (or the fixed ones) before it is written.
The Windows binary is left as pythonfmu ships it: there an exception stays fmi2Fatal.
"""
from __future__ import annotations

import struct

from .elf import PatchError, file_offset, relocated_to, symbol

HANDLER = (b"_ZNK15PySlaveInstance19handle_py_exceptionERKNSt7__cxx1112basic_stringIcSt11"
           b"char_traitsIcESaIcEEE16PyGILState_STATE")
SIZE = 1465  # bytes of the function in pythonfmu 0.7.0
FATAL_TYPE, BASE_TYPE = b"_ZTIN9pythonfmu11fatal_errorE", b"_ZTISt13runtime_error"
#: (offset in the function, pythonfmu 0.7.0's bytes, the fixed ones)
NO_ERROR_RETURNS = (0x60, bytes.fromhex("0f84c2030000"), bytes.fromhex("660f1f440000"))
_RELEASE = "498b7d{field}4885ff74118b0785c0780b83e8{step}89070f84{jump}0000"
RELEASES = (0x9C, *(bytes.fromhex("".join(
    _RELEASE.format(field=field, step=step, jump=jump)
    for field, jump in (("68", "0204"), ("70", "f803"), ("78", "ee03")))) for step in ("01", "00")))
THROWN_TYPE = 0x370  # mov <the type information>(%rip), %rsi before __cxa_throw (7 bytes)
MOV_RSI = bytes.fromhex("488b35")  # mov disp32(%rip), %rsi


def patch(elf: bytes) -> bytes:
    """``elf`` with :func:`handle_py_exception` fixed (module doc; idempotent)."""
    address, size = symbol(elf, HANDLER)
    if size != SIZE:
        raise PatchError(f"handle_py_exception is {size} bytes long, not {SIZE} as in pythonfmu 0.7")
    at = file_offset(elf, address)
    out = bytearray(elf)
    for offset, original, fixed in (NO_ERROR_RETURNS, RELEASES, _thrown_type(elf, address)):
        where = slice(at + offset, at + offset + len(fixed))
        if elf[where] not in (original, fixed):
            raise PatchError(f"handle_py_exception differs from pythonfmu 0.7's at +{offset:#x}")
        out[where] = fixed
    return bytes(out)


def _thrown_type(elf: bytes, handler: int) -> tuple[int, bytes | None, bytes]:
    """(offset, shipped bytes (None: not as shipped), fixed bytes) of the load of the thrown type information: from the
    GOT entry of fatal_error's, or (fixed) from the base-class field (+16) of fatal_error's type
    information itself."""
    end = handler + THROWN_TYPE + 7  # the instruction's end, its displacements' origin
    base, _ = symbol(elf, FATAL_TYPE)
    if relocated_to(elf, base + 16) != BASE_TYPE:
        raise PatchError(f"{FATAL_TYPE.decode()} has no base {BASE_TYPE.decode()}")
    at = file_offset(elf, handler) + THROWN_TYPE
    current = elf[at:at + 7]
    got = end + struct.unpack_from("<i", current, 3)[0]
    as_shipped = current[:3] == MOV_RSI and relocated_to(elf, got) == FATAL_TYPE
    return THROWN_TYPE, current if as_shipped else None, MOV_RSI + struct.pack("<i", base + 16 - end)
