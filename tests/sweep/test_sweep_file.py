"""Reading a sweep file: the points it asks for, and clear errors naming file, table and key."""
import pytest

from guideway_fmu import cli
from guideway_fmu.cosim.system import ScenarioError
from guideway_fmu.sweep import sweep_file

FACTORIAL = """[design]
kind = "factorial"
[design.values]
"Carriage.load_amplitude" = [6000.0, 12000.0]
"Carriage.load_frequency" = [2500.0, 4500.0, 9000.0]
"""


def test_factorial_file_gives_its_points_with_the_experiment_changed(write_sweep, fmu_dir):
    sweep = sweep_file.load(write_sweep(FACTORIAL, stop=3e-3), fmu_dir)
    assert sweep.system.experiment.stop == 3e-3
    assert sweep.parameters == ("Carriage.load_amplitude", "Carriage.load_frequency")
    assert len(sweep.points) == 6 and len(set(sweep.ids)) == 6
    assert [o.column for o in sweep.outputs] == [
        "envelope(Contact.F_upper)", "rms(Carriage.y)", "dominant_frequency(Carriage.y)"]


def test_latin_hypercube_and_explicit_points(write_sweep, fmu_dir):
    lhs = sweep_file.load(write_sweep('[design]\nkind = "latin-hypercube"\nsamples = 5\n'
                                      '[design.ranges]\n"Contact.preload" = [20000.0, 40000.0]\n'),
                          fmu_dir)
    assert len(lhs.points) == 5 and all(20000 <= p["Contact.preload"] < 40000 for p in lhs.points)
    explicit = sweep_file.load(write_sweep(
        '[design]\nkind = "points"\npoints = [{ "Carriage.mass" = 3.0 }, { "Carriage.mass" = 3.5 }]\n'),
        fmu_dir)
    assert explicit.points == ({"Carriage.mass": 3.0}, {"Carriage.mass": 3.5})


@pytest.mark.parametrize("design, outputs, message", [
    (FACTORIAL.replace("load_frequency", "load_freq"), None,
     r"sweep.toml: \[design.values\] key 'Carriage.load_freq': the scenario refuses it: .*"
     r"soleimanian2020_9000N_4500Hz.toml: \[components.Carriage.parameters\] key 'load_freq': "
     r"VerticalDynamics.fmu has no parameter or input of that name"),
    (FACTORIAL.replace("[6000.0, 12000.0]", '[6000.0, "high"]'), None,
     r"key 'Carriage.load_amplitude': .*Real variable cannot take 'high'"),
    (FACTORIAL.replace('"Carriage.load_amplitude"', '"Rail.load_amplitude"'), None,
     r"key 'Rail.load_amplitude': .*no component 'Rail'"),
    (FACTORIAL.replace('"factorial"', '"grid"'), None,
     r"\[design\] key 'kind': must be one of factorial, points, latin-hypercube"),
    ('[design]\nkind = "latin-hypercube"\nsamples = 4\n[design.ranges]\n"Contact.preload" = [4.0, 1.0]\n',
     None, r"\[design.ranges\] key 'Contact.preload': must be \[low, high\]"),
    (FACTORIAL, '[[outputs]]\nvariable = "Contact.F_upper"\nreduce = "mean"\n',
     r"\[outputs #1\] key 'reduce': must be one of peak, rms, envelope, dominant_frequency"),
    (FACTORIAL, '[[outputs]]\nvariable = "Contact.F_lost"\nreduce = "peak"\n',
     r"\[outputs #1\] key 'variable': Contact.F_lost is not recorded"),
    (FACTORIAL, '[[outputs]]\nvariable = "Carriage.y"\nreduce = "peak"\nsettle = 0.01\n',
     r"\[outputs #1\] key 'settle': must be >= 0 s and shorter than the run"),
])
def test_bad_sweep_files_name_the_file_the_key_and_the_fault(write_sweep, fmu_dir, design,
                                                             outputs, message):
    path = write_sweep(design, **({"outputs": outputs} if outputs else {}))
    with pytest.raises(ScenarioError, match=message):
        sweep_file.load(path, fmu_dir)


def test_the_command_reports_a_bad_sweep_file_and_exits_2(write_sweep, fmu_dir, tmp_path, capsys):
    path = write_sweep(FACTORIAL.replace("load_frequency", "load_freq"))
    code = cli.main(["sweep", str(path), "--out", str(tmp_path / "out"), "--fmus", str(fmu_dir)])
    assert code == 2
    assert "guideway-fmu sweep: error:" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()  # refused before any point ran


def test_an_experiment_change_the_scenario_refuses_is_named(write_sweep, fmu_dir):
    with pytest.raises(ScenarioError, match=r"sweep.toml: \[experiment\] key 'stop': the scenario "
                       r"refuses it: .*\[experiment\] key 'step': must be > 0 and <= stop - start"):
        sweep_file.load(write_sweep(FACTORIAL, stop=1e-6), fmu_dir)
