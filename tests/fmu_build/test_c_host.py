"""The FMUs in a plain C host (fmu_build/c_host.c: dlopen and FMI calls, as commercial tools and
libcosim drive an FMU) with the environment `guideway-fmu host-env` prints.

Before the build kept SciPy's _uarray module alive at exit (components/runtime.py), the host died
at exit after every call had returned OK: FeedKinematics 10 of 10 runs (SIGSEGV), HorizontalRig
and Wear in every run too. Skipped where no C compiler is installed."""
from __future__ import annotations

import shlex
import shutil
import subprocess
import sys

import fmpy
import numpy as np
import pytest

from guideway_fmu.components import registry
from guideway_fmu.fmu_build import host_env

pytestmark = pytest.mark.skipif(shutil.which("cc") is None and shutil.which("gcc") is None,
                                reason="no C compiler to build the C host")
RUNS_PER_FMU = 5
STEPS = 10


def printed_environment() -> dict[str, str]:
    """The environment as the README's recipe takes it: a shell that evals `host-env`'s output."""
    command = f"{shlex.quote(sys.executable)} -m guideway_fmu.cli host-env"
    script = f'eval "$({command})" && printf "%s\\0" "$LD_PRELOAD" "$PYTHONHOME" "$PYTHONPATH"'
    out = subprocess.run(["bash", "-c", script], check=True, capture_output=True, text=True).stdout
    values = out.split("\0")[:3]
    assert all(values), out
    return dict(zip(("LD_PRELOAD", "PYTHONHOME", "PYTHONPATH"), values))


@pytest.fixture(scope="module")
def c_host(tmp_path_factory):
    return host_env.compile_c_host(tmp_path_factory.mktemp("c_host"))


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    path = tmp_path_factory.mktemp("table") / "force.csv"
    path.write_text("time,normal_force\n0,100\n1,200\n")
    return path


def start_values(fmu, table) -> dict:
    return {"table_file": str(table)} if fmu.stem == "ForceTable" else {}


@pytest.fixture(scope="module")
def environment():
    return printed_environment()


def test_host_env_prints_a_loadable_libpython_home_and_site_packages_with_numpy():
    env = printed_environment()
    assert set(env) == {"LD_PRELOAD", "PYTHONHOME", "PYTHONPATH"}
    assert "libpython3" in env["LD_PRELOAD"] and host_env.Path(env["LD_PRELOAD"]).is_file()
    assert (host_env.Path(env["PYTHONHOME"]) / "lib" / f"python3.{sys.version_info.minor}").is_dir()
    assert str(host_env.Path(np.__file__).parents[1]) in env["PYTHONPATH"].split(":")


@pytest.mark.slow
@pytest.mark.parametrize("name", registry.names())  # one FMU each: the workers share them out
def test_every_fmu_exits_cleanly_in_a_c_host_and_agrees_with_fmpy_to_12_digits(
        name, fmu_dir, c_host, table, environment, tmp_path):
    fmu = fmu_dir / f"{name}.fmu"
    values = start_values(fmu, table)
    runs = [host_env.run_in_c_host(c_host, fmu, environment, work_dir=tmp_path, steps=STEPS,
                                   start_values=values) for _ in range(RUNS_PER_FMU)]
    assert [(r.status, r.stderr[-300:]) for r in runs if r.status != 0] == []
    md = fmpy.read_model_description(str(fmu))
    h = float(md.defaultExperiment.stepSize)
    names = list(runs[0].outputs)
    ref = fmpy.simulate_fmu(str(fmu), step_size=h, output_interval=h, stop_time=STEPS * h,
                            output=names, start_values=values, set_stop_time=False)
    # 12 digits of each output's scale, the largest output of the same unit; below 1e-30
    # (SI) a value is the round-off of a zero (a carriage at rest: 1e-36 rad), not a digit
    unit = {v.name: v.unit or v.declaredType for v in md.modelVariables}
    scale = {unit[n]: max(abs(ref[m][-1]) for m in names if unit[m] == unit[n]) for n in names}
    for n in names:
        assert abs(runs[0].outputs[n] - ref[n][-1]) <= max(1e-12 * scale[unit[n]], 1e-30), n
    assert all(r.outputs == runs[0].outputs for r in runs)


def test_failed_instantiate_names_the_cause_on_stderr_with_logging_off(fmu_dir, c_host, tmp_path):
    hidden = tmp_path / "hidden"
    (hidden / "numpy").mkdir(parents=True)
    (hidden / "numpy" / "__init__.py").write_text(
        "raise ImportError('numpy deliberately hidden by the test')\n")
    env = printed_environment()
    env["PYTHONPATH"] = f"{hidden}:{env['PYTHONPATH']}"
    env["C_HOST_LOGGING"] = "0"
    run = host_env.run_in_c_host(c_host, fmu_dir / "FeedKinematics.fmu", env, work_dir=tmp_path)
    assert run.status == 2  # fmi2Instantiate returned NULL
    assert "FMU FeedKinematics cannot import its code" in run.stderr
    assert "host-env" in run.stderr and "numpy deliberately hidden by the test" in run.stderr


def test_check_reports_a_bad_start_value_by_name(fmu_dir, c_host, tmp_path):
    with pytest.raises(host_env.HostEnvError, match="no Real or String variable 'nonsense'"):
        host_env.run_in_c_host(c_host, fmu_dir / "FeedKinematics.fmu", printed_environment(),
                               work_dir=tmp_path, start_values={"nonsense": 1.0})


@pytest.mark.slow
def test_host_env_check_runs_an_fmu_in_the_c_host():
    done = subprocess.run([sys.executable, "-m", "guideway_fmu.cli", "host-env", "--check"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "FeedKinematics.fmu ran in a C host with this environment and exited 0" in done.stderr


def test_a_discarded_step_names_its_cause_on_stderr_with_logging_off(fmu_dir, c_host, tmp_path):
    env = dict(printed_environment(), C_HOST_LOGGING="0")
    run = host_env.run_in_c_host(c_host, fmu_dir / "ForceTable.fmu", env, work_dir=tmp_path)
    assert run.status == 3  # fmi2DoStep returned fmi2Discard
    assert "ForceTable c_host: table_file is empty" in run.stderr


def test_host_env_check_of_a_file_that_is_no_fmu_is_a_clear_error(tmp_path):
    junk = tmp_path / "junk.fmu"
    junk.write_text("not a zip archive")
    done = subprocess.run([sys.executable, "-m", "guideway_fmu.cli", "host-env", "--check",
                           str(junk)], capture_output=True, text=True)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert f"{junk}: not an FMU that can be read" in done.stderr


def test_an_fmu_finds_its_resources_under_a_path_a_uri_escapes(fmu_dir, c_host, tmp_path):
    # the C host passes the resource URI percent-encoded, as FMI asks: before the build decoded
    # it (fmu_build/uri_patch.py), pythonfmu looked for its script under the escaped path and
    # the host died in fmi2Instantiate (SIGSEGV). The host runs in a UTF-8 locale, as a user's
    # tool does: in the C locale the embedded interpreter can encode no such path (ASCII), and
    # the instantiation fails with that message
    awkward = tmp_path / "Jürgen tmp+%41"
    awkward.mkdir()
    run = host_env.run_in_c_host(c_host, fmu_dir / "FeedKinematics.fmu",
                                 {**printed_environment(), "LC_ALL": "C.UTF-8"}, work_dir=awkward)
    assert run.status == 0, run.stderr[-2000:]
    assert set(run.outputs) and all(np.isfinite(list(run.outputs.values())))
