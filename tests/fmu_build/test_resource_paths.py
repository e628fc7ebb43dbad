"""FMUs extracted under any path (fmu_build/uri_patch.py, cosim/fmu_instance.py): the build's
decoding of the resource URI in pythonfmu's Linux binary, runs whose temporary and output
folders hold non-ASCII characters, spaces and escapes (before: exit 139, a segfault at the
first instantiation, with no message), and the master's refusal of a pythonfmu FMU without the
fix, which would crash the process."""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
import pythonfmu

from guideway_fmu.cosim.fmu_instance import FmuInstance
from guideway_fmu.fmu_build import elf, uri_patch

SHIPPED = (Path(pythonfmu.__file__).parent / "resources" / "binaries" / "linux64"
           / "libpythonfmu-export.so")
SCENARIO = "soleimanian2020_9000N_4500Hz"
#: folder names a URI escapes: a user name with an umlaut, a space, a '+' and a literal '%41'
AWKWARD = "Jürgen tmp+%41"


def test_patch_jumps_from_fmi2instantiate_to_the_decoder_and_is_idempotent():
    original = SHIPPED.read_bytes()
    patched = uri_patch.patch(original)
    assert not uri_patch.decodes(original) and uri_patch.decodes(patched)
    assert len(patched) == len(original) and uri_patch.patch(patched) == patched
    address, _ = elf.symbol(original, uri_patch.FUNCTION)
    hook = elf.file_offset(original, address) + uri_patch.HOOK
    header, p_offset, _, p_filesz = elf.executable_segment(original)
    changed = {i for i, (a, b) in enumerate(zip(original, patched)) if a != b}
    code = len(uri_patch.DECODER) + 5  # and the jump back
    cave = range(p_offset + p_filesz, p_offset + p_filesz + 16 + code)
    # the hook (5 bytes), the segment's file and memory sizes, the code behind the segment
    assert changed <= set(range(hook, hook + 5)) | set(range(header + 0x20, header + 0x30)) | set(cave)
    assert elf.executable_segment(patched)[3] - p_filesz <= 16 + code


def test_patch_refuses_a_binary_it_does_not_know():
    original = SHIPPED.read_bytes()
    address, _ = elf.symbol(original, uri_patch.FUNCTION)
    at = elf.file_offset(original, address) + 0x100
    with pytest.raises(elf.PatchError, match="fmi2Instantiate differs from pythonfmu 0.7's"):
        uri_patch.patch(original[:at] + bytes([original[at] ^ 1]) + original[at + 1:])


def run(fmu_dir, folder: Path) -> subprocess.CompletedProcess:
    """A 0.4 ms run of the lubricated scenario, TMPDIR and --out under ``folder``."""
    (folder / "tmp").mkdir(parents=True)
    return subprocess.run([sys.executable, "-m", "guideway_fmu.cli", "run", SCENARIO, "--fmus",
                           str(fmu_dir), "--stop", "0.0004", "--out", str(folder / "out"),
                           "--no-progress"], capture_output=True, text=True, timeout=300,
                          env={**os.environ, "TMPDIR": str(folder / "tmp")})


@pytest.fixture(scope="module")
def plain_run(fmu_dir, tmp_path_factory):
    folder = tmp_path_factory.mktemp("plain")
    done = run(fmu_dir, folder)
    assert done.returncode == 0, done.stderr[-2000:]
    return (folder / "out" / "results.csv").read_text()


@pytest.mark.parametrize("name", [AWKWARD, pytest.param("with space", marks=pytest.mark.slow),
                                  pytest.param("Jürgen", marks=pytest.mark.slow)])
def test_a_run_under_awkward_temporary_and_output_folders_gives_the_plain_results(
        fmu_dir, tmp_path, plain_run, name):
    done = run(fmu_dir, tmp_path / name)
    assert done.returncode == 0, (done.returncode, done.stderr[-2000:])
    assert (tmp_path / name / "out" / "results.csv").read_text() == plain_run
    assert list((tmp_path / name / "tmp").iterdir()) == []  # the extracted FMUs removed


def test_the_master_refuses_a_pythonfmu_fmu_that_would_crash_there(faulty, tmp_path, monkeypatch):
    # conftest's Faulty: a plain pythonfmu FMU, without the build's decoding
    scratch = tmp_path / AWKWARD
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    with pytest.raises(ValueError, match=r"Faulty.fmu is built with pythonfmu, whose "
                                         r"fmi2Instantiate cannot find its resources.*TMPDIR"):
        FmuInstance(faulty, "F")
    assert list(scratch.iterdir()) == []
