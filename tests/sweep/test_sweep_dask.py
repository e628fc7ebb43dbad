"""Sweeps on a real dask.distributed LocalCluster of two worker processes: the same numbers as a
serial run, a worker killed under a point, a failing point, an interrupted sweep resumed."""
import csv
import json
import os
import subprocess
import sys
import threading
import time

import pytest

from guideway_fmu.sweep import run, sweep_file
from guideway_fmu.sweep.point import run_point

# a Dask cluster of two worker processes (its own cores: runs alone) and co-simulations
pytestmark = [pytest.mark.slow, pytest.mark.serial]

POINTS = """[design]
kind = "points"
points = [
    { "Carriage.load_amplitude" = 6000.0, "Carriage.load_frequency" = 2500.0 },
    { "Carriage.load_amplitude" = 9000.0, "Carriage.load_frequency" = 4500.0 },
    { "Carriage.load_amplitude" = 12000.0, "Carriage.load_frequency" = 5000.0 },
    { "Carriage.load_amplitude" = 12000.0, "Carriage.load_frequency" = 9000.0 },
]
"""


@pytest.fixture(scope="module")
def client():
    with run.dask_client(workers=2) as client:
        yield client


def rows(out):
    with (out / "results.csv").open(newline="") as f:
        return list(csv.DictReader(f))


def test_two_workers_give_the_numbers_of_a_serial_run(client, write_sweep, fmu_dir, tmp_path):
    sweep = sweep_file.load(write_sweep(POINTS), fmu_dir)
    outcome = run.run_sweep(sweep, tmp_path / "out", client, progress=False)
    assert (outcome.ok, outcome.failed, outcome.retried) == (4, 0, 0)
    table = {r["point"]: r for r in rows(tmp_path / "out")}
    assert sorted(table) == sorted(sweep.ids)
    # independent: every point run here, one after the other, in the test's own process
    for point_id, point in zip(sweep.ids, sweep.points):
        serial = run_point(sweep.system, point, sweep.outputs)["outputs"]
        assert {c: float(table[point_id][c]) for c in serial} == serial  # the same numbers
        for name, value in point.items():
            assert float(table[point_id][name]) == value
    assert {p.rsplit("/", 1)[-1] for p in outcome.files} >= {
        "results.csv", "results.json", "envelope_Contact.F_upper.png", "rms_Carriage.y.png"}


def test_a_killed_worker_costs_a_retry_and_a_failing_point_is_recorded(client, write_sweep,
                                                                        fmu_dir, tmp_path):
    bad = '    { "Carriage.load_amplitude" = 9000.0, "Carriage.load_frequency" = -1.0 },\n]'
    sweep = sweep_file.load(write_sweep(POINTS.replace("\n]", "\n" + bad), stop=0.02), fmu_dir)
    killed = []

    def kill_the_first_busy_worker():  # os._exit in the worker process while it runs a point
        deadline = time.monotonic() + 60
        while not killed and time.monotonic() < deadline:
            for worker, keys in client.processing().items():
                if keys:
                    killed.append(keys[0])
                    client.run(os._exit, 1, workers=[worker], on_error="ignore")
                    break
            time.sleep(0.005)

    killer = threading.Thread(target=kill_the_first_busy_worker)
    killer.start()
    outcome = run.run_sweep(sweep, tmp_path / "out", client, progress=False, plot=False)
    killer.join()
    table = {r["point"]: r for r in rows(tmp_path / "out")}
    assert sorted(table) == sorted(sweep.ids)  # nothing lost
    failed = table[sweep.ids[4]]
    assert (failed["status"], failed["attempts"]) == ("failed", "2")
    assert "ExternalLoad.frequency must be >= 0" in failed["error"] and failed["envelope(Contact.F_upper)"] == ""
    victim = table[killed[0].split("-")[1]]
    assert (victim["status"], victim["attempts"]) == ("ok", "2")  # retried after its worker died
    assert all(table[i]["status"] == "ok" for i in sweep.ids[:4])
    assert (outcome.ok, outcome.failed, outcome.retried) == (4, 1, 2)


def test_resume_runs_only_the_points_missing_from_the_table(client, write_sweep, fmu_dir,
                                                            tmp_path):
    sweep = sweep_file.load(write_sweep(POINTS), fmu_dir)
    out = tmp_path / "out"
    run.run_sweep(sweep, out, client, progress=False, plot=False)
    full = (out / "results.csv").read_text().splitlines(keepends=True)
    # a sweep killed after two points, while writing the third row
    (out / "results.csv").write_text("".join(full[:3]) + full[3][:20])
    with pytest.raises(ValueError, match="exists: continue that sweep with 'resume'"):
        run.run_sweep(sweep, out, client, progress=False, plot=False)
    outcome = run.run_sweep(sweep, out, client, resume=True, progress=False, plot=False)
    assert (outcome.skipped, outcome.ok) == (2, 2)  # two points run, not four
    resumed = (out / "results.csv").read_text().splitlines(keepends=True)
    assert resumed[:3] == full[:3]  # the finished rows kept as they were, the torn one cut
    ids = [r["point"] for r in rows(out)]
    assert sorted(ids) == sorted(sweep.ids)  # each point once: none repeated, none lost
    again = run.run_sweep(sweep, out, client, resume=True, progress=False, plot=False)
    assert (again.skipped, again.ok) == (4, 0)


def test_the_command_runs_a_sweep_on_its_own_cluster(write_sweep, fmu_dir, tmp_path):
    path = write_sweep('[design]\nkind = "factorial"\n[design.values]\n'
                       '"Carriage.load_frequency" = [2500.0, 4500.0]\n')
    run_ = subprocess.run([sys.executable, "-m", "guideway_fmu.cli", "sweep", str(path), "--out",
                           str(tmp_path / "out"), "--fmus", str(fmu_dir), "--workers", "1",
                           "--no-progress"], capture_output=True, text=True, timeout=300)
    assert run_.returncode == 0, run_.stderr[-3000:]
    assert json.loads(run_.stdout)["ok"] == 2
    results = json.loads((tmp_path / "out" / "results.json").read_text())
    assert [p["parameters"]["Carriage.load_frequency"] for p in results["points"]] == [2500.0, 4500.0]
    assert results["outputs"][2]["unit"] == "Hz" and results["outputs"][0]["unit"] == "N"
