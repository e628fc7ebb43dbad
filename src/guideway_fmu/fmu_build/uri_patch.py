"""Our FMUs find their resources under any path: pythonfmu 0.7's Linux ``fmi2Instantiate``
percent-decodes the resource URI (applied by the build).

FMI passes ``fmuResourceLocation`` as a file URI, percent-encoded: fmpy and our C host write
a folder ``Jürgen/x`` as ``file:///<parent>/J%C3%BCrgen/x``. pythonfmu's ``fmi2Instantiate`` (fmi2.cpp)
replaces ``%20`` by a space, drops ``file://`` and reads ``slavemodule.txt`` and the slave script
under what is left: under a path holding any other escaped character (a user name with an
umlaut, a ``+``, a ``%``) it finds neither, and its constructor then called a null class: a
segfault at instantiation, with no message, for every FMU. The fix adds code behind the last
function of the executable segment (in the zero padding the segment's last page already maps),
which decodes every ``%XX`` of the path in place after pythonfmu's own handling, and jumps to it
from there; pythonfmu's handling of ``%20`` first, ours of the rest, gives the path exactly
(``%2520`` -> ``%20``). The function is checked to be pythonfmu 0.7.0's by its hash. The
Windows binary is left as pythonfmu ships it.

The added code, assembled with GNU as (``as --64``); ``0xf0(%rsp)`` is the path's
``std::string`` (data, length) in ``fmi2Instantiate``'s frame, no caller-saved register is live
at the hook, and the patch appends the jump back::

        mov    0xf0(%rsp), %rsi        # read pointer: the string's data
        mov    0xf8(%rsp), %rcx        # its length
        add    %rsi, %rcx              # its end
        mov    %rsi, %rdi              # write pointer
    next:
        cmp    %rcx, %rsi
        jae    done
        movzbl (%rsi), %eax
        inc    %rsi
        cmp    $0x25, %al              # '%'
        jne    store
        lea    2(%rsi), %rdx
        cmp    %rcx, %rdx
        ja     store                   # fewer than two characters follow: a plain '%'
        movzbl (%rsi), %edx
        lea    -0x30(%rdx), %r8d       # '0'..'9'
        cmp    $9, %r8d
        jbe    1f
        or     $0x20, %edx             # 'A'..'F' as 'a'..'f'
        lea    -0x57(%rdx), %r8d       # 'a' - 10
        lea    -0x61(%rdx), %edx
        cmp    $5, %edx
        ja     store                   # not a hex digit: a plain '%'
    1:  movzbl 1(%rsi), %edx
        lea    -0x30(%rdx), %r9d
        cmp    $9, %r9d
        jbe    2f
        or     $0x20, %edx
        lea    -0x57(%rdx), %r9d
        lea    -0x61(%rdx), %edx
        cmp    $5, %edx
        ja     store
    2:  shl    $4, %r8d
        or     %r9d, %r8d
        mov    %r8d, %eax              # the decoded byte
        add    $2, %rsi
    store:
        mov    %al, (%rdi)
        inc    %rdi
        jmp    next
    done:
        movb   $0, (%rdi)              # the terminator
        sub    0xf0(%rsp), %rdi
        mov    %rdi, 0xf8(%rsp)        # the decoded length
        mov    0x18(%rsp), %rsi        # the instruction the hook replaced
"""
from __future__ import annotations

import hashlib
import struct

from .elf import PatchError, executable_segment, file_offset, symbol

FUNCTION = b"fmi2Instantiate"
SHA256 = "28e4db3717b5977dbcf693f3212e1370b001a981e66a5555250299a259eef8f6"  # pythonfmu 0.7.0's
HOOK = 0x5C0  # mov 0x18(%rsp), %rsi: after "file://" is dropped, before the path is used
REPLACED = bytes.fromhex("488b742418")
DECODER = bytes.fromhex(
    "488bb424f0000000488b8c24f80000004801f14889f74839ce73610fb60648ffc63c257550488d5602"
    "4839ca77470fb616448d42d04183f809760f83ca20448d42a98d529f83fa05772b0fb65601448d4ad0"
    "4183f909760f83ca20448d4aa98d529f83fa05770e41c1e0044509c84489c04883c602880748ffc7eb"
    "9ac60700482bbc24f00000004889bc24f8000000488b742418")
JMP = b"\xe9"


def patch(elf: bytes) -> bytes:
    """``elf`` whose fmi2Instantiate decodes the resource URI (module doc; idempotent)."""
    if decodes(elf):
        return elf  # fixed before
    address, size = symbol(elf, FUNCTION)
    at = file_offset(elf, address)
    header, p_offset, p_vaddr, p_filesz = executable_segment(elf)
    cave = -(-(p_offset + p_filesz) // 16) * 16  # file offset, 16-byte aligned
    if hashlib.sha256(elf[at:at + size]).hexdigest() != SHA256:
        raise PatchError("fmi2Instantiate differs from pythonfmu 0.7's")
    code_address = p_vaddr + cave - p_offset
    back = address + HOOK + len(REPLACED)
    code = DECODER + JMP + struct.pack("<i", back - (code_address + len(DECODER) + 5))
    end = cave + len(code)
    if end > -(-(p_offset + p_filesz) // 4096) * 4096 or any(elf[p_offset + p_filesz:end]):
        raise PatchError("no free room after the executable segment")
    out = bytearray(elf)
    out[cave:end] = code
    out[at + HOOK:at + HOOK + 5] = JMP + struct.pack("<i", code_address - (address + HOOK + 5))
    struct.pack_into("<QQ", out, header + 0x20, end - p_offset, end - p_offset)  # filesz, memsz
    return bytes(out)


def decodes(elf: bytes) -> bool:
    """Whether the library's fmi2Instantiate jumps to the decoder (the fix is applied)."""
    address, _ = symbol(elf, FUNCTION)
    at = file_offset(elf, address) + HOOK
    if elf[at:at + 1] != JMP:
        return False
    target = address + HOOK + 5 + struct.unpack_from("<i", elf, at + 1)[0]
    _, p_offset, p_vaddr, p_filesz = executable_segment(elf)
    start = p_offset + target - p_vaddr
    return p_vaddr <= target and elf[start:start + len(DECODER)] == DECODER
