"""The scenario check refuses what would hang or break a run later: a step the clock cannot
resolve at the experiment's largest time (t + h == t looped for ever in ``run`` and ``verify``)
and instance names that ``<instance>.<variable>`` references cannot carry (``"P.1"`` ended in a
bare ``error: 'P'``). The probe FMU `Faulty` is in tests/conftest.py."""
from __future__ import annotations

import json
import math
import re

import pytest

from guideway_fmu import cli
from guideway_fmu.cosim import master, system
from support import write_file


def scenario(tmp_path, fmu, experiment="stop = 0.01\nstep = 0.001", name="P"):
    """probe.toml: one instance ``name`` of ``fmu`` (no fault), the ``experiment`` table's body."""
    return write_file(tmp_path, f'[experiment]\n{experiment}\nalgorithm = "jacobi"\n\n'
                                f'[components.{json.dumps(name)}]\nfmu = "{fmu}"\n'
                                'parameters = { fault = "none" }\n', "probe.toml")


@pytest.mark.parametrize("experiment, key", [
    ("start = 1.0\nstop = 2.0\nstep = 1e-17", "step"),  # t + h == t at t = 1 s
    ("stop = 0.01\nstep = 1e-300", "step"),  # advances, by nothing useful
    ("start = -1e6\nstop = 0.0\nstep = 1e-10", "step"),  # the largest |time| counts
    ("stop = 10.0\nstep = 1e-3\ntolerance = 1e-3\nmin_step = 1e-12", "min_step"),
])
def test_a_step_the_clock_cannot_resolve_is_refused_naming_the_key(tmp_path, faulty, experiment,
                                                                   key):
    with pytest.raises(system.ScenarioError,
                       match=rf"probe.toml: \[experiment\] key '{key}': .* too small for the "
                             r"clock .* must be >= "):
        system.load(scenario(tmp_path, faulty, experiment))


@pytest.mark.parametrize("command", ["run", "verify"])
def test_run_and_verify_with_a_step_that_makes_no_progress_exit_2_naming_it(
        tmp_path, faulty, capsys, command):
    path = scenario(tmp_path, faulty, "start = 1.0\nstop = 2.0\nstep = 1e-3")
    out = ["--out", str(tmp_path / "out")] if command == "run" else []
    assert cli.main([command, str(path), "--step", "1e-17", *out]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"guideway-fmu {command}: error:") and "Traceback" not in err
    assert "[experiment] key 'step': 1e-17 s is too small for the clock" in err


def test_the_smallest_step_the_clock_resolves_runs_its_steps(tmp_path, faulty):
    # the limiting case of the rule: 2^20 float spacings at the largest time, 1 s here
    h = system.STEP_RESOLUTION * math.ulp(1.0)
    s = system.Builder("fine").experiment(start=1.0 - 4 * h, stop=1.0, step=h, algorithm="jacobi")
    result = master.simulate(s.component("P", faulty, fault="none").system())
    assert result.steps == 4 and result.recording.time[-1] == 1.0
    with pytest.raises(system.ScenarioError, match="key 'step'"):
        s.experiment(step=h / 2).system()


@pytest.mark.parametrize("name, problem", [
    ("", "must not be empty"),
    ("P.1", "must not contain '.'"),
    ("P\n", "must not contain a control character"),
    (" P", "must not begin or end with white space"),
])
def test_an_instance_name_references_cannot_carry_is_refused_naming_it(tmp_path, faulty, name,
                                                                        problem):
    path = scenario(tmp_path, faulty, name=name)
    with pytest.raises(system.ScenarioError,
                       match=rf"probe.toml: \[components\] key '{re.escape(repr(name)[1:-1])}': an "
                             rf"instance name {problem}"):
        system.load(path)


def test_run_with_a_dotted_instance_name_exits_2_naming_it(tmp_path, faulty, capsys):
    path = scenario(tmp_path, faulty, name="P.1")
    assert cli.main(["run", str(path), "--out", str(tmp_path / "out"), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert "[components] key 'P.1': an instance name must not contain '.'" in err
