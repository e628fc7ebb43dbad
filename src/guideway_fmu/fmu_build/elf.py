"""What the build's fixes of pythonfmu 0.7's Linux binary read in a 64-bit little-endian ELF
shared library: its sections, exported symbols, relocations and executable segment."""
from __future__ import annotations

import struct

SHT_DYNSYM, SHT_RELA = 11, 4
STT_FUNC = 2
PT_LOAD, PF_X = 1, 1


class PatchError(RuntimeError):
    """The binary is not the pythonfmu 0.7 Linux library a fix knows."""


def _header(elf: bytes) -> None:
    if elf[:4] != b"\x7fELF" or elf[4] != 2 or elf[5] != 1:
        raise PatchError("not a 64-bit little-endian ELF file")


def sections(elf: bytes):
    """(sh_name, sh_type, sh_flags, sh_addr, sh_offset, sh_size, sh_link, sh_info,
    sh_addralign, sh_entsize) of every section."""
    _header(elf)
    shoff, = struct.unpack_from("<Q", elf, 0x28)
    shentsize, shnum = struct.unpack_from("<HH", elf, 0x3A)
    for i in range(shnum):
        yield struct.unpack_from("<IIQQQQIIQQ", elf, shoff + i * shentsize)


def _dynamic_symbols(elf: bytes):
    """(name, st_info, st_shndx, st_value, st_size) of every dynamic symbol, in table order."""
    table = list(sections(elf))
    dynsym = next((s for s in table if s[1] == SHT_DYNSYM), None)
    if dynsym is None:
        raise PatchError("no dynamic symbol table")
    strtab = table[dynsym[6]]
    for entry in range(dynsym[4], dynsym[4] + dynsym[5], dynsym[9]):
        st_name, st_info, _, st_shndx, st_value, st_size = struct.unpack_from("<IBBHQQ", elf, entry)
        start = strtab[4] + st_name
        yield elf[start:elf.index(b"\0", start)], st_info, st_shndx, st_value, st_size


def symbol(elf: bytes, name: bytes) -> tuple[int, int]:
    """(address, size) of the symbol ``name`` the library defines."""
    for found, _, shndx, value, size in _dynamic_symbols(elf):
        if found == name and shndx:
            return value, size
    raise PatchError(f"no symbol {name.decode()}")


def file_offset(elf: bytes, address: int) -> int:
    """The file offset of the mapped ``address``."""
    for _, _, _, addr, offset, size, *_ in sections(elf):
        if addr and addr <= address < addr + size:
            return offset + address - addr
    raise PatchError(f"address {address:#x} is in no section")


def function_offset(elf: bytes, name: bytes) -> int:
    """File offset of the exported function ``name`` in the shared library ``elf``."""
    for found, info, shndx, value, _ in _dynamic_symbols(elf):
        if found == name and info & 0xF == STT_FUNC and shndx:
            return file_offset(elf, value)
    raise PatchError(f"no function {name.decode()}")


def relocated_to(elf: bytes, address: int) -> bytes | None:
    """The symbol whose address the dynamic linker writes at ``address``, if any."""
    names = [entry[0] for entry in _dynamic_symbols(elf)]
    for table in sections(elf):
        if table[1] != SHT_RELA:
            continue
        for entry in range(table[4], table[4] + table[5], 24):
            r_offset, r_info, _ = struct.unpack_from("<QQq", elf, entry)
            if r_offset == address and r_info >> 32:
                return names[r_info >> 32]
    return None


def executable_segment(elf: bytes) -> tuple[int, int, int, int]:
    """(program header offset, p_offset, p_vaddr, p_filesz) of the one executable LOAD segment."""
    _header(elf)
    phoff, = struct.unpack_from("<Q", elf, 0x20)
    phentsize, phnum = struct.unpack_from("<HH", elf, 0x36)
    found = []
    for i in range(phnum):
        at = phoff + i * phentsize
        p_type, p_flags, p_offset, p_vaddr, _, p_filesz = struct.unpack_from("<IIQQQQ", elf, at)
        if p_type == PT_LOAD and p_flags & PF_X:
            found.append((at, p_offset, p_vaddr, p_filesz))
    if len(found) != 1:
        raise PatchError(f"{len(found)} executable segments, not one")
    return found[0]
