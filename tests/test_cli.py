"""The command line's table of subcommands and its one error boundary."""
import dataclasses

import pytest

from guideway_fmu import cli, examples

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
