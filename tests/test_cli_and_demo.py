import html
import json
import os
import re
import shutil
import subprocess
import sys
import zipfile
from html.parser import HTMLParser

import numpy as np
import pytest
from fmpy import read_model_description

from guideway_fmu import cli, scenarios
from guideway_fmu.demo import job
from guideway_fmu.physics.roller_guide import four_rows


def test_cli_unknown_fmu_is_a_clear_error(tmp_path, capsys):
    assert cli.main(["build", "--out", str(tmp_path), "ContactMagic"]) == 2
    err = capsys.readouterr().err
    assert "ContactMagic" in err and "Traceback" not in err


def test_cli_facts_natural_frequency_near_published_6590_hz(capsys):
    assert cli.main(["facts"]) == 0
    facts = json.loads(capsys.readouterr().out)
    assert abs(facts["natural_frequency_lubricated_Hz"] / 6590.0 - 1) < 0.01
    assert facts["preload_per_roller_N"] == 460.0  # 9200 N per groove of 20


def test_stiffness_curves_through_fmus_match_physics_derivative(fmu_dir):
    y = np.linspace(-1e-6, 1e-6, 21)  # both rows loaded: no kink inside the differences
    curves = job.stiffness_curves(fmu_dir, y)
    g = four_rows.Guideway()
    inner = slice(1, -1)  # np.gradient is one-sided at the ends
    np.testing.assert_allclose(curves["K_dry"][inner], curves["K_contact_output_dry"][inner], rtol=2e-3)
    np.testing.assert_allclose(curves["K_lubricated"][inner],
                               four_rows.quasi_static_stiffness(g, y, job.RIG_SPEED)[inner], rtol=2e-3)
    assert abs(curves["F_lubricated"][10]) < 1e-6  # y = 0: symmetric preload


SCENARIOS = scenarios.FOLDER


@pytest.mark.slow
def test_cli_run_unloaded_rig_oscillates_at_the_natural_frequency(fmu_dir, tmp_path, capsys):
    out = tmp_path / "run"
    assert cli.main(["run", str(SCENARIOS / "soleimanian2020_unloaded.toml"), "--fmus", str(fmu_dir),
                     "--stop", "1.5e-3", "--out", str(out), "--no-progress"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["steps"] == 375 and summary["algorithm"] == "stabilised"  # 4 us steps
    assert summary["parameters"]["Contact"]["preload"] == 36800.0
    assert summary["parameters"]["Feed"]["profile"] == "biharmonic"  # text, not "b'biharmonic'"
    assert {"results.csv", "time.png", "spectrum.png", "film.png", "envelope.png"} <= set(summary["files"])
    data = np.genfromtxt(out / "results.csv", delimiter=",", names=True)
    y = data["Carriagey"] - data["Carriagey"].mean()
    crossings = np.count_nonzero(np.diff(np.sign(y)) != 0)
    assert abs(crossings / 2 / data["time"][-1] / 6590.0 - 1) < 0.1  # ~10 periods, published 6590 Hz
    assert np.all(data["FrictionF_friction"] < 0)  # the feed velocity is positive here


def test_cli_verify_json_meets_the_accuracy_target_on_a_short_loaded_run(fmu_dir, capsys):
    assert cli.main(["verify", str(SCENARIOS / "soleimanian2020_9000N_4500Hz.toml"), "--fmus", str(fmu_dir),
                     "--stop", "2e-3", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert set(report) >= {"rms_error", "peak_error", "wall_time_cosim", "wall_time_reference"}
    assert report["rms_error"]["Contact.F_upper"] < 0.01
    assert "Carriage.y" in report["peak_error"]
    # the reference moves by under 1e-6 of the range when disturbed here (measured): pointwise
    assert report["signal"] == "Contact.F_upper" and report["criterion"] == "pointwise"
    assert max(report["predictability"]["spread"].values()) < 1e-3 and report["passed"] is True


def test_cli_export_ssp_writes_a_package_baked_unless_told_not_to(fmu_dir, tmp_path, capsys):
    scenario = str(SCENARIOS / "soleimanian2020_9000N_4500Hz_dry.toml")
    for flags, name in (([], "baked.ssp"), (["--no-bake"], "plain.ssp")):
        assert cli.main(["export-ssp", scenario, "--fmus", str(fmu_dir), str(tmp_path / name), *flags]) == 0
        with zipfile.ZipFile(tmp_path / name) as zf:
            assert "resources/ContactDryHertz.fmu" in zf.namelist()
            (tmp_path / name).with_suffix(".fmu").write_bytes(zf.read("resources/VerticalDynamics.fmu"))
    starts = {v.name: v.start for v in read_model_description(str(tmp_path / "baked.fmu")).modelVariables}
    assert float(starts["load_amplitude"]) == 9000.0  # the scenario's load, 0 in the FMU as built
    assert (tmp_path / "plain.fmu").read_bytes() == (fmu_dir / "VerticalDynamics.fmu").read_bytes()


def test_cli_run_bad_scenario_is_a_clear_error(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("[experiment]\nstop = 1.0\n")
    assert cli.main(["run", str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "bad.toml" in err and "components" in err and "Traceback" not in err


@pytest.fixture(scope="module")
def demo_run(tmp_path_factory):
    """The demo run once in a subprocess from another directory (runs of 2 ms, FMUs from the
    test session's cache): (the folder it ran in, the finished process)."""
    cwd = tmp_path_factory.mktemp("demo")
    done = subprocess.run([sys.executable, "-m", "guideway_fmu.cli", "demo", "--out", "demo",
                           "--stop", "2e-3"], cwd=cwd, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    return cwd, done


@pytest.mark.slow
@pytest.mark.serial  # the demo's sweep starts a Dask cluster of two worker processes
def test_demo_main_job_end_to_end_from_another_directory(demo_run):
    tmp_path, done = demo_run
    summary = json.loads((tmp_path / "demo" / "summary.json").read_text())
    assert sorted(p.name for p in tmp_path.iterdir()) == ["demo"]  # no FMUs in the working folder
    assert set(summary["runs"]) == set(job.DEMO_SCENARIOS)
    assert summary["verify"]["soleimanian2020_9000N_4500Hz"]["rms_error_Contact.F_upper"] < 0.01
    assert (tmp_path / "demo" / "soleimanian2020_9000N_4500Hz_dry" / "spectrum.png").exists()
    diagnosis = summary["diagnose"]
    assert diagnosis["missing_effect"] == diagnosis["hidden_effect"] == "presliding_hysteresis"
    assert diagnosis["gap_after"] < 0.5 * diagnosis["gap_before"]
    assert (tmp_path / "demo" / "diagnose_example" / "report.html").exists()
    sweep = summary["sweep"]
    assert sweep["ok"] == sweep["points"] == 21 and len(sweep["plots"]) == 3
    # a short summary, not the JSON, ending with where the page is
    assert not done.stdout.lstrip().startswith("{")
    assert done.stdout.strip().splitlines()[-1] == f"open {(tmp_path / 'demo' / 'index.html').as_uri()}"


class _Page(HTMLParser):
    """The img sources, link targets and text of an HTML page."""

    def __init__(self):
        super().__init__()
        self.images, self.links, self.text = [], [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "img":
            self.images.append(attrs["src"])
        elif tag == "a":
            self.links.append(attrs["href"])

    def handle_data(self, data):
        self.text.append(data)


@pytest.mark.slow
@pytest.mark.serial  # with the demo run it reads
def test_demo_page_shows_every_plot_the_demo_wrote_with_its_command(demo_run):
    out = demo_run[0] / "demo"
    page = _Page()
    page.feed((out / "index.html").read_text(encoding="utf-8"))
    written = sorted(p.relative_to(out).as_posix() for p in out.rglob("*.png"))
    assert len(written) >= 19  # stiffness, 3 runs x 4, 3 sweep outputs, 3 diagnosis plots
    assert sorted(page.images) == written  # each once, relative to the page
    assert all((out / link).is_file() for link in page.links)
    text = "".join(page.text)
    for command in ("guideway-fmu demo --out demo --stop 0.002",  # FMUs from the cache
                    "guideway-fmu verify soleimanian2020_9000N_4500Hz --stop 0.002",
                    "guideway-fmu sweep demo/envelope_vs_frequency.toml",
                    "guideway-fmu diagnose demo/diagnose_example/run"):
        assert command in text
    assert "presliding_hysteresis" in text and "--fmus" not in text


def _browser() -> str | None:
    return next(filter(None, map(shutil.which, ("chromium", "chromium-browser", "google-chrome"))), None)


_IMAGE_CHECK = """<script>window.addEventListener("load", () => {
  const broken = [...document.images].filter(i => !(i.complete && i.naturalWidth > 0));
  const pre = document.createElement("pre");
  pre.id = "image-check";
  pre.textContent = JSON.stringify({images: document.images.length,
                                    broken: broken.map(i => i.getAttribute("src"))});
  document.body.appendChild(pre);
});</script>"""


@pytest.mark.slow
@pytest.mark.serial  # with the demo run it reads
@pytest.mark.skipif(_browser() is None, reason="no headless browser (chromium) installed; "
                    "test_demo_page_shows_every_plot... checks the image paths with html.parser")
def test_demo_page_renders_in_a_headless_browser_without_broken_images(demo_run, tmp_path):
    out = demo_run[0] / "demo"
    browser = [_browser(), "--headless", "--no-sandbox", "--disable-gpu",
               "--virtual-time-budget=10000"]
    shot = tmp_path / "index.png"
    subprocess.run([*browser, f"--screenshot={shot}", "--window-size=1200,3000",
                    (out / "index.html").as_uri()], check=True, capture_output=True, timeout=120)
    assert shot.stat().st_size > 10_000  # a page, not a blank window
    checked = out / "index.image-check.html"  # the page with a script that counts broken images
    checked.write_text((out / "index.html").read_text(encoding="utf-8")
                       .replace("</body>", _IMAGE_CHECK + "</body>"), encoding="utf-8")
    dom = subprocess.run([*browser, "--dump-dom", checked.as_uri()], check=True,
                         capture_output=True, text=True, timeout=120).stdout
    report = json.loads(html.unescape(re.search(r'<pre id="image-check">(.*?)</pre>', dom).group(1)))
    assert report["images"] >= 19 and report["broken"] == []


def test_cli_demo_refuses_bad_stop_before_any_work(tmp_path, capsys):
    assert cli.main(["demo", "--out", str(tmp_path / "o"), "--fmus", str(tmp_path / "f"),
                     "--stop", "-1"]) == 2
    assert "--stop" in capsys.readouterr().err
    assert not (tmp_path / "f").exists()


def test_verify_refuses_a_system_the_reference_cannot_model_before_co_simulating(
        fmu_dir, tmp_path, monkeypatch):
    from guideway_fmu.reference import verify
    from guideway_fmu.cosim import master, system
    path = tmp_path / "commanded.toml"
    path.write_text(f'[experiment]\nstop = 1e-3\nstep = 1e-5\n[components.Feed]\n'
                    f'fmu = "{fmu_dir}/FeedKinematics.fmu"\n'
                    f'parameters = {{ profile = "input" }}\n')  # u from an input: no model
    monkeypatch.setattr(master, "simulate", lambda *a, **k: pytest.fail("co-simulation ran"))
    with pytest.raises(ValueError, match="Feed"):
        verify.verify(system.load(path))


def test_run_with_an_fmu_that_cannot_be_instantiated_is_a_clear_error(fmu_dir, tmp_path, capsys):
    broken = tmp_path / "VerticalDynamics.fmu"
    with zipfile.ZipFile(fmu_dir / "VerticalDynamics.fmu") as src, zipfile.ZipFile(broken, "w") as dst:
        for item in src.infolist():  # the same FMU without its binaries
            if not item.filename.startswith("binaries/"):
                dst.writestr(item, src.read(item))
    path = tmp_path / "s.toml"
    path.write_text(f'[experiment]\nstop = 1e-3\nstep = 1e-5\n[components.Carriage]\nfmu = "{broken}"\n')
    assert cli.main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert "cannot instantiate Carriage" in err and "Traceback" not in err


def test_exit_without_finalising_keeps_buffered_output_and_the_code():
    # the exit FMU-loading programs take (issue 21's finalisation crash): what was printed
    # without a newline still arrives, the code is the one given, and no atexit handler runs
    program = ("import atexit, sys\n"
               "from guideway_fmu.cosim.interrupts import exit_without_finalising\n"
               "atexit.register(lambda: print('finalised'))\n"
               "print('out', end='')\n"
               "sys.stderr.write('err')\n"
               "exit_without_finalising(3)\n")
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                          timeout=60)
    assert (done.returncode, done.stdout, done.stderr) == (3, "out", "err")


# -- what the commands print, and their exit statuses ----------------------------------------
@pytest.mark.slow
def test_run_of_a_scenario_without_plots_plots_every_instance_and_lists_its_files(
        fmu_dir, tmp_path, capsys):
    from guideway_fmu.cosim import system
    b = system.Builder("my_rig").experiment(stop=2e-3, step=2e-6, algorithm="stabilised")
    b.component("Carriage", fmu_dir / "VerticalDynamics.fmu", load_static=500.0)
    b.component("Contact", fmu_dir / "ContactDryHertz.fmu")
    b.connect("Carriage.y", "Contact.y").connect("Contact.F_contact", "Carriage.F_contact")
    b.tangent("Contact.F_contact", "Contact.y", "Contact.K_contact", "Carriage.K_contact")
    system.dump(b.system(), tmp_path / "my_rig.toml")
    out = tmp_path / "out"
    assert cli.main(["run", str(tmp_path / "my_rig.toml"), "--out", str(out)]) == 0
    printed = json.loads(capsys.readouterr().out)
    written = json.loads((out / "summary.json").read_text())["files"]
    assert printed["files"] == [str(out / name) for name in written]
    # the carriage settles onto the rollers at its natural frequency: both oscillate
    assert written[3:] == ["time_Carriage.png", "spectrum_Carriage.png", "time_Contact.png",
                           "spectrum_Contact.png"]
    assert all((out / name).is_file() for name in written)


def test_verify_exits_1_with_one_line_when_the_verdict_is_failed(fmu_dir, capsys, monkeypatch):
    from guideway_fmu.reference import verify
    monkeypatch.setattr(verify, "verify", lambda system, progress: {
        "scenario": system.name, "criterion": "pointwise", "passed": False})
    assert cli.main(["verify", "soleimanian2020_unloaded", "--fmus", str(fmu_dir), "--json"]) == 1
    printed = capsys.readouterr()
    assert json.loads(printed.out)["passed"] is False  # the report, printed all the same
    assert printed.err.startswith("guideway-fmu verify: soleimanian2020_unloaded FAILED")
    assert printed.err.count("\n") == 1


def test_sweep_with_failed_points_exits_2_after_its_table(tmp_path, capsys, monkeypatch):
    import contextlib
    from guideway_fmu.sweep import run, sweep_file
    table = str(tmp_path / "o" / "results.csv")
    monkeypatch.setattr(sweep_file, "load", lambda path, fmus, edition: None)
    monkeypatch.setattr(run, "dask_client", lambda workers, scheduler: contextlib.nullcontext())
    monkeypatch.setattr(run, "run_sweep", lambda *args, **kwargs: run.Outcome(
        points=9, skipped=0, ok=7, failed=2, retried=2, files=[table]))
    (tmp_path / "s.toml").write_text("")  # read by the mocked loader only
    assert cli.main(["sweep", str(tmp_path / "s.toml"), "--out", str(tmp_path / "o")]) == 2
    printed = capsys.readouterr()
    assert json.loads(printed.out)["failed"] == 2
    assert printed.err == (f"guideway-fmu sweep: error: 2 of the 9 points failed; their errors "
                           f"are in {table} (rerun them with --resume)\n")


def test_diagnose_lists_the_files_it_wrote(tmp_path, capsys, monkeypatch):
    from guideway_fmu.diagnose import workflow
    (tmp_path / "o").mkdir()
    (tmp_path / "o" / "old.txt").write_text("from an earlier day")
    os.utime(tmp_path / "o" / "old.txt", (0, 0))

    def diagnose(run_dir, out_dir, fmu_dir, progress):
        (out_dir / "report.html").write_text("<html></html>")
        return {"missing_effect": "none", "candidates": []}

    monkeypatch.setattr(workflow, "diagnose", diagnose)
    (tmp_path / "run").mkdir()  # read by the mocked workflow only
    assert cli.main(["diagnose", str(tmp_path / "run"), "--out", str(tmp_path / "o")]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed == {"missing_effect": "none", "files": [str(tmp_path / "o" / "report.html")]}
