"""The FMU cache (fmu_build/cache.py): where it is, one build per FMU code and edition, safe when
processes build at once, never the working folder."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from guideway_fmu import cli
from guideway_fmu.components import registry
from guideway_fmu.fmu_build import build, cache


def test_the_cache_is_the_setting_else_the_users_cache_folder(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "platform", "linux")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.delenv(cache.ENVIRONMENT)
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    assert cache.root() == tmp_path / "home" / ".cache" / "guideway-fmu"
    monkeypatch.setenv("XDG_CACHE_HOME", "relative")  # not absolute: ignored, as XDG says
    assert cache.root() == tmp_path / "home" / ".cache" / "guideway-fmu"
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cache.root() == tmp_path / "xdg" / "guideway-fmu"
    monkeypatch.setenv(cache.ENVIRONMENT, str(tmp_path / "chosen"))
    assert cache.root() == tmp_path / "chosen"


def test_an_unknown_edition_is_refused_naming_the_known_ones():
    with pytest.raises(ValueError, match="unknown FMU edition 'wasm'; known: python, native"):
        cache.folder("wasm")


def test_a_cache_that_cannot_be_written_is_named_with_the_ways_around(tmp_path, monkeypatch):
    (tmp_path / "file").write_text("not a folder")
    monkeypatch.setenv(cache.ENVIRONMENT, str(tmp_path / "file" / "cache"))
    with pytest.raises(OSError, match=r"the FMU cache .*file/cache cannot be written .*"
                                      r"GUIDEWAY_FMU_CACHE .*--fmus"):
        cache.folder()


def test_the_tests_use_a_cache_of_their_own(fmu_dir, fmu_cache):
    assert fmu_dir.is_relative_to(fmu_cache) and os.environ[cache.ENVIRONMENT] == str(fmu_cache)
    assert fmu_dir == fmu_cache / "python" / "sets" / fmu_dir.name


def _stored(folder: Path) -> Path:
    """A cache holding only the built FMUs of the session's cache, no set folder."""
    (folder / "python").mkdir(parents=True)
    for fmu in (Path(os.environ[cache.ENVIRONMENT]) / "python").glob("*.fmu"):
        shutil.copy2(fmu, folder / "python")
    return folder


def test_fmus_of_unchanged_code_are_not_built_again(fmu_dir, tmp_path, monkeypatch):
    monkeypatch.setenv(cache.ENVIRONMENT, str(_stored(tmp_path / "cache")))
    monkeypatch.setattr(build, "pack", lambda *a, **k: pytest.fail("an FMU was built"))
    folder = cache.folder()
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        [f"{n}.fmu" for n in registry.names()] + ["README.md"])
    assert (folder / "README.md").read_text() == (fmu_dir / "README.md").read_text()
    stored = tmp_path / "cache" / "python" / f"ContactEHL-{build.built_tag(folder / 'ContactEHL.fmu')}.fmu"
    assert folder / "ContactEHL.fmu" != stored and os.path.samefile(folder / "ContactEHL.fmu", stored)


def test_a_set_folder_with_an_fmu_deleted_is_made_again(tmp_path, monkeypatch):
    monkeypatch.setenv(cache.ENVIRONMENT, str(_stored(tmp_path / "cache")))
    folder = cache.folder()
    (folder / "Wear.fmu").unlink()
    assert cache.folder() == folder and build.built_tag(folder / "Wear.fmu") == build.code_hash(
        build.shipped_files(registry.component("Wear")))


def test_changed_code_builds_that_fmu_alone_into_a_new_set(fmu_dir, tmp_path, monkeypatch):
    monkeypatch.setenv(cache.ENVIRONMENT, str(_stored(tmp_path / "cache")))
    wear, real, pack = build.shipped_files(registry.component("Wear")), build.code_hash, build.pack
    monkeypatch.setattr(build, "code_hash", lambda files, data=None:
                        "0123456789" if files == wear else real(files, data))
    packed = []
    monkeypatch.setattr(build, "pack", lambda slaves, *a: packed.extend(
        c.__name__ for c, _ in slaves) or pack(slaves, *a))
    folder = cache.folder()
    assert packed == ["Wear"] and folder.name != fmu_dir.name  # another state of the package
    assert build.built_tag(folder / "Wear.fmu") == "0123456789"
    assert (tmp_path / "cache" / "python" / "Wear-0123456789.fmu").is_file()
    assert os.path.samefile(folder / "ContactEHL.fmu",
                            next((tmp_path / "cache" / "python").glob("ContactEHL-*.fmu")))


@pytest.mark.slow
def test_two_processes_filling_an_empty_cache_at_once_get_one_whole_folder(tmp_path):
    program = ("from guideway_fmu.fmu_build import cache\n"
               "folder = cache.folder()\n"
               "print(folder, sorted(p.name for p in folder.iterdir()))\n")
    env = {**os.environ, cache.ENVIRONMENT: str(tmp_path / "cache")}
    children = [subprocess.Popen([sys.executable, "-c", program], env=env, text=True,
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE) for _ in range(2)]
    done = [child.communicate(timeout=600) for child in children]
    assert [child.returncode for child in children] == [0, 0], [err for _, err in done]
    assert done[0][0] == done[1][0]  # the same folder with the same files
    edition = tmp_path / "cache" / "python"
    (folder,) = (edition / "sets").iterdir()
    stored = {f"{n}-{build.built_tag(folder / f'{n}.fmu')}.fmu" for n in registry.names()}
    assert {p.name for p in edition.iterdir()} == stored | {"lock", "sets"}  # nothing half made
    for fmu in edition.glob("*.fmu"):  # every one whole
        assert zipfile.ZipFile(fmu).testzip() is None


def test_run_of_a_shipped_scenario_writes_nothing_into_the_working_folder(tmp_path, monkeypatch,
                                                                        fmu_dir, capsys):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["run", "soleimanian2020_9000N_4500Hz_dry", "--stop", "2e-5", "--out", "out",
                     "--no-progress"]) == 0
    assert json.loads(capsys.readouterr().out)["steps"] == 5
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
