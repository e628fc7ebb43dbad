"""FMU archives: unsafe entries refused before anything is extracted or packaged, and a copy
with other start values that our FMUs start from."""
import stat
import zipfile

import pytest

from guideway_fmu.fmi import archive
from guideway_fmu.cosim.fmu_instance import FmuInstance
from support import SYMLINK, with_entry

UNSAFE = [("../outside.txt", 0, "has a '..' path component"),
          ("resources/../../outside.txt", 0, "has a '..' path component"),
          ("/etc/outside.txt", 0, "is an absolute path"),
          ("C:/outside.txt", 0, "is an absolute path"),
          ("resources/link", SYMLINK, "is a symbolic link"),
          ("resources/fifo", (stat.S_IFIFO | 0o644) << 16, "is a special file")]


@pytest.mark.parametrize("name, mode, why", UNSAFE)
def test_unsafe_entries_are_refused_naming_the_fmu_and_the_entry(fmu_dir, tmp_path, name, mode, why):
    bad = with_entry(fmu_dir / "FeedKinematics.fmu", tmp_path / "Bad.fmu", name, mode)
    with pytest.raises(ValueError, match=f"Bad.fmu: archive entry '{name}' {why}"):
        archive.check_entries(bad)


def test_the_fmus_we_build_pass(fmu_dir):
    for fmu in fmu_dir.glob("*.fmu"):
        archive.check_entries(fmu)


@pytest.mark.parametrize("name, mode", [("../outside.txt", 0), ("/outside.txt", 0),
                                        ("resources/link", SYMLINK)])
def test_the_master_extracts_no_fmu_with_an_unsafe_entry(fmu_dir, tmp_path, monkeypatch, name, mode):
    bad = with_entry(fmu_dir / "FeedKinematics.fmu", tmp_path / "Bad.fmu", name, mode)
    extracted = []
    monkeypatch.setattr("guideway_fmu.cosim.fmu_instance.extract", lambda path: extracted.append(path))
    with pytest.raises(ValueError, match=f"Bad.fmu: archive entry '{name}'"):
        FmuInstance(bad, "Feed")
    assert extracted == []


@pytest.mark.parametrize("fmu, values, defaults", [
    ("FeedKinematics", {"profile": "oscillating", "frequency": 40.0, "u_cmd": 0.5},
     {"profile": "biharmonic", "frequency": 5.0, "u_cmd": 0.0}),
    ("ContactEHL", {"interpolate_inputs": True}, {"interpolate_inputs": False}),
    ("FrictionMixedEHL", {"rollers_per_groove": 18}, {"rollers_per_groove": 20})])
def test_a_copy_with_start_values_starts_there_and_keeps_every_other_entry(fmu_dir, tmp_path, fmu,
                                                                          values, defaults):
    source = fmu_dir / f"{fmu}.fmu"
    copy = archive.with_start_values(source, tmp_path / "copy.fmu", values)
    with zipfile.ZipFile(source) as a, zipfile.ZipFile(copy) as b:
        assert a.namelist() == b.namelist()
        assert all(a.read(n) == b.read(n) for n in a.namelist() if n != "modelDescription.xml")
    for path, expected in ((copy, values), (source, defaults)):
        instance = FmuInstance(path, fmu)
        try:
            assert {name: instance.get(name) for name in values} == expected
        finally:
            instance.close()


def test_a_start_value_of_a_missing_variable_is_refused(fmu_dir, tmp_path):
    with pytest.raises(ValueError, match="FeedKinematics.fmu: modelDescription.xml has no variable 'nope'"):
        archive.with_start_values(fmu_dir / "FeedKinematics.fmu", tmp_path / "x.fmu", {"nope": 1.0})
