"""The one-byte exit fix of pythonfmu's Linux binary (fmu_build/exit_patch.py), checked against
the binary pythonfmu ships; the C-host tests (test_c_host.py) check what it fixes."""
from pathlib import Path

import pythonfmu
import pytest

from guideway_fmu.fmu_build import elf, exit_patch

SHIPPED = (Path(pythonfmu.__file__).parent / "resources" / "binaries" / "linux64"
           / "libpythonfmu-export.so")


def test_patch_changes_one_byte_to_ret_after_the_functions_endbr64_and_is_idempotent():
    original = SHIPPED.read_bytes()
    patched = exit_patch.patch(original)
    changed = [i for i, (a, b) in enumerate(zip(original, patched)) if a != b]
    at = elf.function_offset(original, exit_patch.SYMBOL)
    assert len(patched) == len(original) and changed == [at + 4]
    assert patched[at:at + 5] == bytes.fromhex("f30f1efa") + b"\xc3"
    assert exit_patch.patch(patched) == patched


def test_patch_refuses_a_binary_it_does_not_know():
    original = SHIPPED.read_bytes()
    at = elf.function_offset(original, exit_patch.SYMBOL)
    other = original[:at] + b"\x55" + original[at + 1:]  # another prologue
    with pytest.raises(elf.PatchError, match="does not start as in pythonfmu 0.7"):
        exit_patch.patch(other)
    with pytest.raises(elf.PatchError, match="not a 64-bit little-endian ELF"):
        exit_patch.patch(b"MZ" + original[2:])
    with pytest.raises(elf.PatchError, match="no function nothing"):
        elf.function_offset(original, b"nothing")


def test_patch_fmu_patches_the_linux_binary_and_keeps_every_other_entry(tmp_path):
    import zipfile

    fmu = tmp_path / "P.fmu"
    with zipfile.ZipFile(fmu, "w") as archive:
        archive.writestr("modelDescription.xml", b"<x/>")
        archive.writestr("binaries/linux64/P.so", SHIPPED.read_bytes())
        archive.writestr("binaries/win64/P.dll", b"MZ windows")
    exit_patch.patch_fmu(fmu)
    with zipfile.ZipFile(fmu) as archive:
        assert archive.read("modelDescription.xml") == b"<x/>"
        assert archive.read("binaries/win64/P.dll") == b"MZ windows"
        assert archive.read("binaries/linux64/P.so") == exit_patch.patch(SHIPPED.read_bytes())
