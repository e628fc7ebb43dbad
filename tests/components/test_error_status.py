"""An FMU that logs an error returns a status other than fmi2OK from the call that met it
(components/base.py): a discarded step, or fmi2Error from a getter or exitInitializationMode,
and the master stops naming the FMU's message (runs of the command line in child processes)."""
from __future__ import annotations

import re
import subprocess
import sys

import pytest

from guideway_fmu import scenarios

SCENARIO = "soleimanian2020_9000N_4500Hz"


def run_with_carriage(fmu_dir, tmp_path, setting: str):
    """``guideway-fmu run`` of the lubricated scenario for 0.4 ms with ``setting`` added to the
    carriage's parameters, in a child process."""
    text = scenarios.find(SCENARIO).read_text()
    scenario = tmp_path / "scenario.toml"
    scenario.write_text(text.replace("[components.Carriage.parameters]\n",
                                     f"[components.Carriage.parameters]\n{setting}\n"))
    return subprocess.run([sys.executable, "-m", "guideway_fmu.cli", "run", str(scenario),
                           "--fmus", str(fmu_dir), "--stop", "0.0004", "--out",
                           str(tmp_path / "out"), "--no-progress"],
                          capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("setting, message", [
    # the lower rollers part by 7e9 m: their load underflows to 0, their steady film is infinite;
    # before, the contact logged "not finite; keeping the last valid values" under fmi2OK and the
    # run ended with exit 0, F_contact = 0 N and no error
    ("y_start = 1e10", r"outputs \{.*'h_lower': inf.*\} are not finite"),
    # no roller load balances an approach of 7e299 m: the steady solve's bracket grew without end
    ("y_start = 1e300", "steady roller load: no roller load"),
], ids=["1e10", "1e300"])
def test_a_contact_that_cannot_evaluate_stops_the_run_with_its_message(fmu_dir, tmp_path,
                                                                       setting, message):
    done = run_with_carriage(fmu_dir, tmp_path, setting)
    assert done.returncode == 2, (done.returncode, done.stderr[-3000:])
    assert "FMU instance 'Contact' failed during initialisation" in done.stderr
    assert "status 3 (error)" in done.stderr  # fmi2Error (fmu_build/error_patch.py)
    assert re.search(message, done.stderr), done.stderr[-3000:]
