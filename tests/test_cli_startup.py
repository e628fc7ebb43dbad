"""``guideway-fmu`` starts at once: help, version and the errors a user meets first (a path that
does not exist, a scenario's name, a bad sweep file) are told before the heavy libraries load.
Checked by what the command imports (``python -X importtime``), not by the clock."""
from __future__ import annotations

import re
import subprocess
import sys

import pytest

HEAVY = {"numpy", "scipy", "matplotlib", "fmpy", "dask", "distributed", "pythonfmu",
         "guideway_fmu.cosim"}


def imported(tmp_path, *args) -> tuple[set[str], subprocess.CompletedProcess]:
    """(the modules ``guideway-fmu ARGS`` imported, the finished process) run in ``tmp_path``."""
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "guideway_fmu.cli", *args],
                          cwd=tmp_path, capture_output=True, text=True, timeout=120)
    modules = set(re.findall(r"^import time:.*\|\s*(\S+)$", done.stderr, re.M))
    return modules, done


def told(done: subprocess.CompletedProcess) -> str:
    """The lines of stderr that are not import times."""
    return "\n".join(line for line in done.stderr.splitlines()
                     if not line.startswith("import time:"))


@pytest.mark.parametrize("args", [["--help"], ["--version"], ["run", "--help"]])
def test_help_and_version_load_no_library(tmp_path, args):
    modules, done = imported(tmp_path, *args)
    assert done.returncode == 0 and done.stdout
    assert not modules & HEAVY, modules & HEAVY


@pytest.mark.parametrize("args, message", [
    (["modes", "nofile.toml"], "nofile.toml: cannot read: no such carriage file"),
    (["feed-unit", "nofile.toml"], "nofile.toml: cannot read: no such feed-unit file"),
    (["ball-to-ball", "nofile.toml"], "nofile.toml: cannot read: no such ball-to-ball case file"),
    (["wear", "nofile.toml"], "nofile.toml: cannot read: no such wear case file"),
    (["sweep", "nofile.toml", "--out", "o"], "nofile.toml: cannot read: no such sweep file"),
    (["diagnose", "nodir", "--out", "o"], "nodir: cannot read: no such measured-run folder"),
    (["ehl-cycle", "nodir", "--out", "o"], "nodir: cannot read: no such run folder"),
    (["run", "no_such", "--out", "o"], "scenario 'no_such' is neither a file nor a shipped"),
    (["verify", "no_such"], "scenario 'no_such' is neither a file nor a shipped"),
    (["export-ssp", "no_such", "x.ssp"], "scenario 'no_such' is neither a file nor a shipped"),
    (["facts", "--u", "fast"], "argument --u: invalid float value: 'fast'"),
])
def test_a_missing_input_or_a_wrong_name_is_told_before_any_library_loads(tmp_path, args,
                                                                           message):
    modules, done = imported(tmp_path, *args)
    assert done.returncode == 2 and message in told(done), told(done)
    assert not modules & HEAVY, modules & HEAVY
    assert sorted(p.name for p in tmp_path.iterdir()) == []  # nothing written


def test_a_bad_sweep_file_is_told_before_dask_loads(tmp_path):
    (tmp_path / "bad.toml").write_text('scenario = "soleimanian2020_9000N_4500Hz"\ndesing = 1\n')
    modules, done = imported(tmp_path, "sweep", "bad.toml", "--out", "o")
    assert done.returncode == 2
    assert told(done) == ("guideway-fmu sweep: error: bad.toml: [top level] key 'desing': is not "
                          "a known key (known: description, design, experiment, outputs, "
                          "scenario)")
    assert not modules & {"dask", "distributed", "scipy"}, modules
