"""The example inputs shipped in the package (guideway_fmu/examples) and ``guideway-fmu examples``:
every example copied out and listed, nothing overwritten, the measured run what its README's
command makes and what diagnose finds in it."""
from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

from guideway_fmu import cli, examples, scenarios

RUN = examples.FOLDER / "measured_run"


def test_the_command_copies_every_example_and_lists_what_it_wrote(tmp_path, capsys):
    assert cli.main(["examples", str(tmp_path / "x")]) == 0
    listed = capsys.readouterr().out.splitlines()
    written = sorted(str(p) for p in (tmp_path / "x").rglob("*") if p.is_file())
    assert sorted(listed) == written
    names = {p.relative_to(tmp_path / "x").as_posix() for p in (tmp_path / "x").rglob("*")
             if p.is_file()}
    assert {"README.md", "ball_guides/wu2012_table2_moment_0.toml",
            "ball_guides/zhang2019_vertical_10kN.toml", "ball_guides/lin2019_case_a.toml",
            "ball_guides/zhang_wear_lg20_2kN.toml", "measured_run/rig.toml",
            "measured_run/data.csv", "measured_run/README.md",
            "scenarios/sweeps/soleimanian2020_envelope_vs_frequency.toml"} <= names
    assert {f"scenarios/{n}.toml" for n in scenarios.names()} <= names
    assert not any("__init__" in n or n.endswith(".pyc") for n in names)
    for name, source in examples.sources().items():
        assert (tmp_path / "x" / name).read_bytes() == source.read_bytes()


def test_the_command_overwrites_nothing_and_names_the_files_in_the_way(tmp_path, capsys):
    mine = tmp_path / "x" / "ball_guides" / "lin2019_case_a.toml"
    mine.parent.mkdir(parents=True)
    mine.write_text("mine")
    (tmp_path / "x" / "README.md").write_text("mine too")
    assert cli.main(["examples", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "2 of the examples' files exist already" in err
    assert "README.md, ball_guides/lin2019_case_a.toml; nothing was copied" in err
    assert mine.read_text() == "mine"
    assert sorted(p.name for p in (tmp_path / "x").rglob("*")) == [
        "README.md", "ball_guides", "lin2019_case_a.toml"]


def test_a_file_where_the_folder_should_be_is_refused(tmp_path, capsys):
    (tmp_path / "x").write_text("a file")
    assert cli.main(["examples", str(tmp_path / "x")]) == 2
    assert f"{tmp_path / 'x'} is a file, not a folder" in capsys.readouterr().err


def test_the_measured_run_is_small_and_what_its_readme_command_makes(tmp_path):
    command = re.search(r'^ +(python -c ".*")$', (RUN / "README.md").read_text(), re.M)[1]
    code = command.removeprefix('python -c "').removesuffix('"')
    subprocess.run([sys.executable, "-c", code], cwd=tmp_path, check=True, timeout=300)
    for name in ("rig.toml", "data.csv"):
        assert (tmp_path / "measured_run" / name).read_bytes() == (RUN / name).read_bytes(), name
    assert sum(p.stat().st_size for p in RUN.iterdir()) < 300e3


@pytest.mark.slow
def test_diagnose_names_the_hidden_effect_with_fmus_from_the_cache(tmp_path, fmu_dir):
    # the command as a user runs it: no --fmus; nothing but its --out folder written
    done = subprocess.run([sys.executable, "-m", "guideway_fmu.cli", "diagnose", str(RUN),
                           "--out", "out"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    diagnosis = json.loads((tmp_path / "out" / "diagnosis.json").read_text())
    assert diagnosis["missing_effect"] == "presliding_hysteresis"
    assert diagnosis["gap_after"] < 0.5 * diagnosis["gap_before"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
    assert not (tmp_path / "out" / "fmus").exists()
