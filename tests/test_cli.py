"""The command line's table of subcommands, its one error boundary, what every command says
when its work fails, and its progress bars."""
import dataclasses
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

from guideway_fmu import cli, examples, scenarios
from guideway_fmu.cosim import interrupts
from guideway_fmu.output.progress import stages
from support import write_file, write_run_folder

CASE = str(examples.FOLDER / "ball_guides" / "zhang_wear_lg20_2kN.toml")


def test_every_command_of_the_table_has_help_and_its_own_parser(capsys):
    top, own = cli.parsers()
    assert list(own) == [c.name for c in cli.COMMANDS]
    for command in cli.COMMANDS:
        assert command.help
        with pytest.raises(SystemExit) as done:
            top.parse_args([command.name, "--help"])
        assert done.value.code == 0
        assert command.help.split()[0] in capsys.readouterr().out


def test_version_is_the_installed_package_version(capsys):
    from importlib.metadata import version
    with pytest.raises(SystemExit) as done:
        cli.main(["--version"])
    assert done.value.code == 0
    assert capsys.readouterr().out.strip() == f"guideway-fmu {version('guideway_fmu')}"


def test_a_quoted_argument_of_the_library_is_worded_as_the_commands_option():
    _, own = cli.parsers()
    sweep = next(c for c in cli.COMMANDS if c.name == "sweep")
    text = cli.in_option_terms("out/results.csv exists: continue that sweep with 'resume', or "
                               "choose another 'out' folder; 'workers' must be >= 1", sweep,
                               own["sweep"])
    assert text == ("out/results.csv exists: continue that sweep with --resume, or choose "
                    "another --out folder; --workers must be >= 1")


def test_a_quoted_file_key_or_a_name_that_is_no_option_stays_quoted():
    _, own = cli.parsers()
    wear = next(c for c in cli.COMMANDS if c.name == "wear")
    text = cli.in_option_terms("case.toml: [load] key 'points': missing; component 'Contact'",
                               wear, own["wear"])
    assert text == "case.toml: [load] key 'points': missing; component 'Contact'"


def test_a_commands_own_phrase_is_reworded():
    _, own = cli.parsers()
    export = next(c for c in cli.COMMANDS if c.name == "export-ssp")
    assert cli.in_option_terms("export without baking ('bake' False)", export,
                               own["export-ssp"]) == "export without baking (--no-bake)"


def test_a_library_error_about_an_argument_exits_2_naming_the_option(capsys):
    assert cli.main(["wear", CASE, "--distance", "-1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("guideway-fmu wear: error: --distance must be")
    assert err.count("\n") == 1


def test_an_error_that_is_not_the_librarys_named_kind_is_not_hidden(monkeypatch):
    def broken(args):
        raise KeyError("a defect, not bad input")
    commands = tuple(dataclasses.replace(c, run=broken) if c.name == "scenarios" else c
                     for c in cli.COMMANDS)
    monkeypatch.setattr(cli, "COMMANDS", commands)
    with pytest.raises(KeyError, match="a defect"):
        cli.main(["scenarios"])


def test_the_command_runs_one_thread_numerical_libraries_unless_the_user_chose(monkeypatch):
    seen = {}
    monkeypatch.setattr(cli, "main", lambda: seen.update(
        {v: cli.os.environ.get(v) for v in cli.THREAD_VARIABLES}) or 0)
    for variable in cli.THREAD_VARIABLES:
        monkeypatch.delenv(variable, raising=False)
    monkeypatch.setenv("MKL_NUM_THREADS", "3")
    monkeypatch.setattr(interrupts, "exit_without_finalising", sys.exit)
    with pytest.raises(SystemExit) as done:
        cli.entry()
    assert done.value.code == 0
    assert seen == {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "3"}


# -- every command says when its work failed -------------------------------------------------
EXAMPLES = examples.FOLDER / "ball_guides"


def _broken_fmu_scenario(tmp_path, fmu_dir):
    """A scenario whose one FMU has lost its binaries: the run cannot instantiate it."""
    broken = tmp_path / "VerticalDynamics.fmu"
    with zipfile.ZipFile(fmu_dir / "VerticalDynamics.fmu") as src, \
            zipfile.ZipFile(broken, "w") as dst:
        for item in src.infolist():
            if not item.filename.startswith("binaries/"):
                dst.writestr(item, src.read(item))
    return write_file(tmp_path, f'[experiment]\nstop = 1e-3\nstep = 1e-5\n'
                                f'[components.Carriage]\nfmu = "{broken}"\n', "s.toml")


def _unmodelled_scenario(tmp_path, fmu_dir):
    """A feed driven by an input: the monolithic reference has no model of it."""
    return write_file(tmp_path, f'[experiment]\nstop = 1e-3\nstep = 1e-5\n[components.Feed]\n'
                                f'fmu = "{fmu_dir}/FeedKinematics.fmu"\n'
                                f'parameters = {{ profile = "input" }}\n', "s.toml")


def _standing_feed_run(tmp_path, fmu_dir):
    """A run folder whose feed stands still until 40 us (instants before have no film)."""
    t = np.arange(30) * 4e-6
    return write_run_folder(tmp_path / "run", t, np.full(t.size, 400.0),
                            np.where(t < 4e-5, 0.0, 0.26), np.full(t.size, 2e-7))


def _edited(path: Path, old: str, new: str):
    def write(tmp_path, fmu_dir):
        text = path.read_text()
        assert old in text
        return write_file(tmp_path, text.replace(old, new), path.name)
    return write


#: command -> (input maker (tmp_path, fmu_dir) -> path or None, arguments with {input},
#: {tmp} and {fmus}, words of the one line on stderr): an input that makes the command's
#: work fail. A command missing here fails the test below.
FAILING = {
    "build": (None, ["--out", "{tmp}", "ContactMagic"], ["ContactMagic"]),
    "host-env": (None, ["--check", "{tmp}/missing.fmu"], ["missing.fmu"]),
    "scenarios": None,  # takes no input (checked): nothing of the user's can make it fail
    "examples": (lambda tmp_path, fmu_dir: write_file(tmp_path, "", "a_file"), ["{input}"],
                 ["is a file, not a folder"]),
    "run": (_broken_fmu_scenario, ["{input}", "--out", "{tmp}/o"], ["cannot instantiate Carriage"]),
    "sweep": (_edited(scenarios.FOLDER / "sweeps" / "soleimanian2020_envelope_vs_frequency.toml",
                      '"Carriage.load_amplitude"', '"Carriage.no_such_parameter"'),
              ["{input}", "--out", "{tmp}/o", "--fmus", "{fmus}"], ["no_such_parameter"]),
    "verify": (_unmodelled_scenario, ["{input}"], ["Feed"]),
    "export-ssp": (None, ["soleimanian2020_unloaded", "--fmus", "{fmus}", "{tmp}/no/x.ssp"],
                   ["does not exist"]),
    "export-fmu": (None, ["soleimanian2020_unloaded", "--fmus", "{fmus}", "{tmp}/x.zip"],
                   [".fmu"]),
    "diagnose": (None, ["{tmp}/nothing", "--out", "{tmp}/o"], ["nothing"]),
    "demo": (None, ["--out", "{tmp}/o", "--fmus", "{tmp}/f", "--stop", "-1"], ["--stop"]),
    "facts": (None, ["--u", "nan"], ["--u must be finite"]),
    "ehl": (None, ["--W", "1e-2", "--U", "1e-11", "--G", "4500", "--nodes", "65"],
            ["did not converge"]),
    "ehl-cycle": (_standing_feed_run, ["{input}", "--out", "{tmp}/o", "--times", "2e-5,1.1e-4",
                                       "--history", "0", "--nodes", "257"],
                  ["instants not solved: A (t = 2e-05 s)"]),
    "modes": (_edited(EXAMPLES / "wu2012_hertz_moment_2p9.toml", "[load]",
                      "[load]\nforce_y = 10.0"), ["{input}"], ["no ball resists"]),
    "feed-unit": (_edited(EXAMPLES / "zhang2019_vertical_10kN.toml", "[load]", "[load]\nmass = 1"),
                  ["{input}"], ["mass"]),
    "ball-to-ball": (_edited(EXAMPLES / "lin2019_case_a.toml", "side_ratio = -0.6",
                             "side_ratio = -1.5"), ["{input}"], ["two-point contact"]),
    "wear": (None, [CASE, "--distance", "-1"], ["--distance"]),
}


@pytest.mark.parametrize("name", [c.name for c in cli.COMMANDS])
def test_every_command_exits_non_zero_with_one_line_when_its_work_fails(name, request, tmp_path,
                                                                        capsys):
    assert name in FAILING, f"no input that makes {name!r} fail: add one to FAILING"
    if FAILING[name] is None:  # nothing to fail on: the command takes no argument
        _, own = cli.parsers()
        assert [a.dest for a in own[name]._actions] == ["help"]
        return
    make, arguments, words = FAILING[name]
    fmu_dir = request.getfixturevalue("fmu_dir") if any(
        "{fmus}" in a for a in arguments) or make is not None else None
    made = make(tmp_path, fmu_dir) if make is not None else None
    argv = [a.format(input=made, tmp=tmp_path, fmus=fmu_dir) for a in arguments]
    assert cli.main([name, *argv]) != 0
    err = capsys.readouterr().err
    assert err.startswith(f"guideway-fmu {name}: ") and err.count("\n") == 1, err
    assert "Traceback" not in err
    for word in words:
        assert word in err


# -- progress and what the commands wrote ----------------------------------------------------
LONG = ("run", "sweep", "verify", "diagnose", "demo", "ehl-cycle", "ball-to-ball")


def test_the_commands_that_run_long_can_be_told_to_show_no_progress():
    _, own = cli.parsers()
    for name in LONG:
        assert "--no-progress" in own[name]._option_string_actions, name


@pytest.mark.parametrize("terminal, flags, shown", [
    (True, [], True), (True, ["--no-progress"], False), (False, [], False)])
def test_a_progress_bar_shows_on_a_terminal_unless_told_not_to(tmp_path, capsys, monkeypatch,
                                                               terminal, flags, shown):
    monkeypatch.setattr(sys.stderr, "isatty", lambda: terminal)
    t = np.arange(30) * 4e-6
    run = write_run_folder(tmp_path / "run", t, 300 + 100 * np.sin(2e4 * t), np.full(30, 0.26),
                           np.full(30, 2e-7))
    assert cli.main(["ehl-cycle", str(run), "--out", str(tmp_path / "o"), "--count", "2",
                     "--history", "2e-5", "--nodes", "129", *flags]) == 0
    err = capsys.readouterr().err
    assert ("EHL at the instants" in err and "sample" in err) is shown
    assert shown or err == ""


def test_stages_count_each_stage_done_and_name_the_one_under_way(capsys):
    with stages("job", 3, True) as begin:
        begin("first")
        begin("second")
        begin("third")
    bar = capsys.readouterr().err.replace("\r", "\n")
    assert "job: first" in bar and "0/3 stages done" in bar
    assert "job: second" in bar and "1/3" in bar and "job: third" in bar and "3/3" in bar
    with pytest.raises(RuntimeError):
        with stages("job", 3, True) as begin:
            begin("first")
            raise RuntimeError("stopped")
    bar = capsys.readouterr().err.replace("\r", "\n")
    assert "0/3" in bar and "1/3" not in bar  # where the work stopped
    with stages("job", 3, False) as begin:
        begin("first")
    assert capsys.readouterr().err == ""
