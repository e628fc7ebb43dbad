"""The monolithic reference (guideway_fmu.reference.monolithic) against independent results."""
import dataclasses
import math
import zipfile

import numpy as np
import pytest
from scipy.optimize import brentq

from guideway_fmu.reference import monolithic
from guideway_fmu.reference.verify import verify
from guideway_fmu import scenarios
from guideway_fmu.cosim import master, system
from guideway_fmu.physics.roller_guide import carriage, four_rows
from guideway_fmu.physics.rigs import feed_motion

RIG_WIRING = scenarios.coupling()
FRICTION_WIRING = [("Feed.u", "Friction.u"), *((f"Contact.{v}", f"Friction.{v}")
                                               for v in ("F_upper", "F_lower", "h_upper", "h_lower"))]


def built_scenario(path, fmu_dir, components, connections, stop, step=1e-6):
    """Write and load a scenario; ``components`` maps instance -> (FMU file or name, parameters)."""
    b = system.Builder(path.stem).experiment(start=0.0, stop=stop, step=step)
    for name, (fmu, params) in components.items():
        b.component(name, fmu if str(fmu).endswith(".fmu") else fmu_dir / f"{fmu}.fmu", **params)
    for source, target in connections:
        b.connect(source, target)
    return system.load(system.dump(b.system(check_fmus=False), path))


def test_small_oscillation_of_dry_contact_has_the_linear_natural_frequency(fmu_dir, tmp_path):
    mass, preload = 2.5, 8000.0
    rig = built_scenario(tmp_path / "dry.toml", fmu_dir, {
        "Carriage": ("VerticalDynamics", {"mass": mass, "gravity": 0.0, "y_start": 1e-9}),
        "Contact": ("ContactDryHertz", {"preload": preload})}, RIG_WIRING, stop=3e-3)
    ref = monolithic.simulate(rig)
    y, t = ref.columns["Carriage.y"], ref.time
    np.testing.assert_array_equal(t, np.arange(3001) * 1e-6)
    i = np.flatnonzero(np.sign(y[:-1]) != np.sign(y[1:]))
    crossings = t[i] - y[i] * (t[i + 1] - t[i]) / (y[i + 1] - y[i])
    k = four_rows.quasi_static_stiffness(four_rows.Guideway(preload=preload), 0.0, lubricated=False)
    expected = math.sqrt(k / mass) / (2 * math.pi)
    assert len(crossings) > 30
    measured = (len(crossings) - 1) / (2 * (crossings[-1] - crossings[0]))
    assert measured == pytest.approx(expected, rel=1e-6)
    assert np.max(np.abs(y)) == pytest.approx(1e-9, rel=1e-4, abs=0.0)  # undamped


def test_start_offset_moves_every_state_by_that_fraction_of_its_nominal_scale(fmu_dir, tmp_path):
    # independent check: the carriage's nominal scales (physics/roller_guide/carriage.py), 1.04e-6 m and
    # 0.043 m/s, times the offset, added to its start (y_start, at rest)
    rig = built_scenario(tmp_path / "dry.toml", fmu_dir, {
        "Carriage": ("VerticalDynamics", {"gravity": 0.0, "y_start": 1e-9}),
        "Contact": ("ContactDryHertz", {})}, RIG_WIRING, stop=1e-5)
    ref = monolithic.simulate(rig, start_offset=1e-3)
    assert ref.columns["Carriage.y"][0] == pytest.approx(1e-9 + 1.04e-9, rel=1e-12)
    assert ref.columns["Carriage.y_dot"][0] == pytest.approx(4.3e-5, rel=1e-12)


@pytest.mark.parametrize("contact, film_model", [
    ("ContactEHL", "extrapolated"), ("ContactEHL", "pan_hamrock"), ("ContactDryHertz", None)])
def test_body_started_at_the_static_equilibrium_stays_there(fmu_dir, tmp_path, contact, film_model):
    u, load = 0.29, 5000.0
    g = four_rows.Guideway(contact=four_rows.LineContact(model=film_model or "extrapolated"))
    body = carriage.Carriage()

    def residual(y):
        f_u, f_l, _, _ = four_rows.quasi_static_state(g, y, u, lubricated=film_model is not None)
        return body.mass * body.gravity + load - float(four_rows.net_force(g, f_u, f_l))

    y_eq = brentq(residual, 0.0, 1e-5, xtol=1e-22, rtol=1e-15)
    rig = built_scenario(tmp_path / "static.toml", fmu_dir, {
        "Feed": ("FeedKinematics", {"profile": "constant", "velocity": u}),
        "Contact": (contact, {"film_model": film_model} if film_model else {}),
        "Carriage": ("VerticalDynamics", {"load_static": load, "y_start": y_eq}),
    }, [("Feed.u", "Contact.u"), *RIG_WIRING], stop=5e-4, step=1e-5)
    ref = monolithic.simulate(rig)
    assert y_eq > 5e-7
    assert np.max(np.abs(ref.columns["Carriage.y"] - y_eq)) < 1e-9 * y_eq
    assert np.max(np.abs(ref.columns["Carriage.y_ddot"])) < 1e-3
    h = ref.columns["Contact.h_upper"]
    assert np.ptp(h) <= 1e-9 * h[0]


def test_tighter_tolerance_changes_the_loaded_rig_little(fmu_dir, tmp_path):
    rig = built_scenario(tmp_path / "loaded.toml", fmu_dir, {
        "Feed": ("FeedKinematics", {}), "Contact": ("ContactEHL", {}),
        "Carriage": ("VerticalDynamics", {"load_amplitude": 9000.0, "load_frequency": 4500.0}),
        "Friction": ("FrictionMixedEHL", {}),
    }, [("Feed.u", "Contact.u"), *RIG_WIRING, *FRICTION_WIRING], stop=2e-3, step=2e-6)
    coarse, fine = (monolithic.simulate(rig, rtol=rtol) for rtol in (1e-8, 1e-10))
    assert (fine.method, fine.rtol, coarse.rtol) == ("RK45", 1e-10, 1e-8)  # the film rate is not smooth
    assert fine.nfev > coarse.nfev > 0 and fine.wall_time > 0.0
    assert set(fine.columns) == {f"{inst}.{v.name}" for inst, variables in rig.variables.items()
                                 for v in variables.values() if v.causality == "output"}
    assert fine.units["Contact.F_upper"] == "N" and fine.units["Carriage.y_ddot"] == "m/s2"
    for name, bound in (("Contact.F_upper", 2e-6), ("Carriage.y", 2e-6), ("Contact.h_upper", 2e-5),
                        ("Friction.F_friction", 2e-5)):
        error = np.max(np.abs(coarse.columns[name] - fine.columns[name]))
        assert error < bound * np.ptp(fine.columns[name]), name


def test_film_relaxes_to_the_steady_film_at_constant_feed_velocity(fmu_dir, tmp_path):
    """The body, started at y = 0 with the films steady there, settles under a static load
    (contact damping); the films follow the changed roller loads to their new steady values."""
    u = 0.29
    rig = built_scenario(tmp_path / "film.toml", fmu_dir, {
        "Feed": ("FeedKinematics", {"profile": "constant", "velocity": u}),
        "Contact": ("ContactEHL", {"damping": 2e4}),
        "Carriage": ("VerticalDynamics", {"load_static": 20000.0}),
    }, [("Feed.u", "Contact.u"), *RIG_WIRING], stop=5e-3, step=1e-5)
    ref = monolithic.simulate(rig)
    _, _, h_upper, h_lower = four_rows.quasi_static_state(four_rows.Guideway(), ref.columns["Carriage.y"], u)
    for h, steady in ((ref.columns["Contact.h_upper"], h_upper), (ref.columns["Contact.h_lower"], h_lower)):
        change = abs(h[-1] - h[0])
        assert change > 1e-2 * h[0]
        assert abs(h[0] - steady[0]) < 1e-9 * change  # starts steady at y_start
        assert np.max(np.abs(h - steady)[:100]) > 0.1 * change  # lags the load while settling
        assert abs(h[-1] - steady[-1]) < 1e-5 * change


def _third_party_copy(fmu, path):
    """A copy of ``fmu`` whose modelDescription names another model, as a foreign FMU would."""
    with zipfile.ZipFile(fmu) as src, zipfile.ZipFile(path, "w") as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename == "modelDescription.xml":
                data = data.replace(b"FrictionCoulomb", b"ThirdParty")
            dst.writestr(item, data)
    return path


@pytest.mark.parametrize("case, message", [
    ("third_party", r"component 'Other': FMU ThirdParty.fmu \(model identifier 'ThirdParty'\) cannot"),
    ("feed_input", r"component 'Feed' \(FeedKinematics\): cannot be modelled: profile 'input'"),
    ("bad_parameter", r"component 'Contact' \(ContactEHL\): .*damping must be >= 0"),
    ("algebraic_loop", r"algebraic loop (Carriage -> Contact -> Carriage|Contact -> Carriage -> Contact)"),
])
def test_unsupported_component_or_wiring_is_refused_naming_the_component(fmu_dir, tmp_path, case, message):
    components = {"Feed": ("FeedKinematics", {}), "Contact": ("ContactEHL", {}),
                  "Carriage": ("VerticalDynamics", {}), "Friction": ("FrictionCoulomb", {})}
    wiring = [("Feed.u", "Contact.u"), *RIG_WIRING, ("Feed.u", "Friction.u"),
              ("Contact.F_upper", "Friction.F_upper"), ("Contact.F_lower", "Friction.F_lower")]
    if case == "third_party":
        components["Other"] = (_third_party_copy(fmu_dir / "FrictionCoulomb.fmu",
                                                 tmp_path / "ThirdParty.fmu"), {})
    elif case == "feed_input":
        components["Feed"] = ("FeedKinematics", {"profile": "input"})
    elif case == "algebraic_loop":  # y_ddot feeds through F_contact, which feeds through y
        wiring[wiring.index(("Carriage.y", "Contact.y"))] = ("Carriage.y_ddot", "Contact.y")
    else:
        components["Contact"] = ("ContactEHL", {"damping": -1.0})
    rig = built_scenario(tmp_path / f"{case}.toml", fmu_dir, components, wiring, stop=1e-4)
    with pytest.raises(ValueError, match=message):
        monolithic.simulate(rig)


def test_generic_assembly_unconnected_force_is_free_fall_hand_calculation(fmu_dir, tmp_path):
    # F_contact unconnected stays at its start value 0: y = v0 t + g t^2 / 2.
    rig = built_scenario(tmp_path / "fall.toml", fmu_dir, {
        "Carriage": ("VerticalDynamics", {"y_dot_start": 0.1})}, [], stop=1e-2, step=1e-3)
    ref = monolithic.simulate(rig)
    t = ref.time
    np.testing.assert_allclose(ref.columns["Carriage.y"], 0.1 * t + 0.5 * carriage.STANDARD_GRAVITY * t**2,
                               rtol=1e-9, atol=1e-15)


def test_generic_assembly_horizontal_rig_drive_force_hand_calculation(fmu_dir, tmp_path):
    # A rig of the discrepancy workflow: Coulomb friction at constant loads against the
    # bi-harmonic feed, drive_force = m a + mu 2N (F_U + F_L) s(u) + offset.
    mass, mu, load, offset = 3.0, 0.01, 200.0, 1.5
    rig = built_scenario(tmp_path / "rig.toml", fmu_dir, {
        "Feed": ("FeedKinematics", {}),
        "Friction": ("FrictionCoulomb", {"coefficient": mu, "F_upper": load, "F_lower": load}),
        "Rig": ("HorizontalRig", {"mass": mass, "drive_offset": offset})},
        [("Feed.u", "Friction.u"), ("Feed.a", "Rig.a"), ("Friction.F_friction", "Rig.F_friction")],
        stop=0.2, step=1e-3)
    ref = monolithic.simulate(rig)
    _, u, a = feed_motion.BiHarmonic().evaluate(ref.time)
    expected = mass * a + mu * 2 * 20 * 2 * load * np.tanh(u / 1e-4) + offset
    np.testing.assert_allclose(ref.columns["Rig.drive_force"], expected, rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize("profile", [
    feed_motion.BiHarmonic(), feed_motion.Oscillating(), feed_motion.Constant(),
    feed_motion.Trapezoid(distance=-0.01, v_max=0.3, a_max=30.0, t_start=0.01),
    feed_motion.Table(time=(0.0, 0.01, 0.03, 0.04), velocity=(0.0, 0.2, -0.1, 0.05))])
def test_fast_feed_velocity_equals_the_profile(profile):
    """The reference's right-hand side asks the feed model for u alone (velocity_at); the
    outputs come from evaluate."""
    t = np.linspace(-0.01, 0.06, 1401)
    model = feed_motion.FeedModel(profile)
    fast = [model.outputs(float(s), (), {}, ("u",))["u"] for s in t]
    np.testing.assert_allclose(fast, profile.evaluate(t)[1], rtol=1e-12, atol=1e-15)


def test_times_must_increase_from_the_start(fmu_dir, tmp_path):
    rig = built_scenario(tmp_path / "t.toml", fmu_dir, {"Contact": ("ContactDryHertz", {}),
                                                        "Carriage": ("VerticalDynamics", {})},
                         RIG_WIRING, stop=1e-4)
    ref = monolithic.simulate(rig, times=[2e-5, 5e-5])
    np.testing.assert_array_equal(ref.time, [2e-5, 5e-5])
    for times in ([-1e-5, 5e-5], [5e-5, 2e-5]):
        with pytest.raises(ValueError, match="times must increase"):
            monolithic.simulate(rig, times=times)


def _effect_rig(tmp_path, fmu_dir, fmu, params, stop=0.02, velocity=0.05):
    return built_scenario(tmp_path / f"{fmu}.toml", fmu_dir, {
        "Feed": ("FeedKinematics", {"profile": "constant", "velocity": velocity}),
        "Friction": (fmu, {"coefficient": 0.01, "F_upper": 100.0, "F_lower": 50.0,
                           "rollers_per_groove": 10, **params}),
        "Rig": ("HorizontalRig", {"mass": 2.0})},
        [("Feed.u", "Friction.u"), ("Feed.x", "Friction.x"), ("Feed.a", "Rig.a"),
         ("Friction.F_friction", "Rig.F_friction")], stop=stop, step=1e-4)


def test_dahl_rig_builds_up_friction_over_the_presliding_distance_hand_calculation(fmu_dir, tmp_path):
    # one element from z = 0 at constant u: z = 1 - exp(-u t / delta), drive force = F_c z
    rig = _effect_rig(tmp_path, fmu_dir, "FrictionDahl", {"presliding_distance": 2e-4})
    ref = monolithic.simulate(rig)
    expected = 30.0 * -np.expm1(-0.05 * ref.time / 2e-4)
    np.testing.assert_allclose(ref.columns["Rig.drive_force"], expected, rtol=1e-6, atol=1e-6)


def test_preload_loss_rig_follows_the_running_distance_hand_calculation(fmu_dir, tmp_path):
    rig = _effect_rig(tmp_path, fmu_dir, "FrictionPreloadLoss", {"loss": 0.5, "wear_distance": 4e-4})
    ref = monolithic.simulate(rig)
    expected = 30.0 * (1.0 - 0.5 * -np.expm1(-0.05 * ref.time / 4e-4)) * np.tanh(0.05 / 1e-4)
    np.testing.assert_allclose(ref.columns["Rig.drive_force"], expected, rtol=1e-6, atol=1e-6)


@pytest.mark.slow
@pytest.mark.parametrize("fmu, params", [
    ("FrictionDahl", {"presliding_distance": 1e-4, "second_distance": 1e-3, "second_share": 0.4}),
    ("FrictionPreloadLoss", {"loss": 0.3, "wear_distance": 0.002}),
    ("FrictionBallToBall", {"table_end": 0.004, "factors": "1 1.5 0.8 1.2"}),
    ("FrictionPositionDependent", {"table_start": -0.002, "table_end": 0.002, "factors": "1 2 1"}),
    ("FrictionStribeck", {"static_coefficient": 0.02, "stribeck_velocity": 0.01, "viscous": 50.0}),
])
def test_verify_covers_the_diagnosers_rigs_cross_tool(fmu_dir, tmp_path, fmu, params):
    # the co-simulation (exact path updates per step, Jacobi) against the reference (LSODA on
    # the derivatives) under an oscillating feed with reversals
    rig = built_scenario(tmp_path / f"{fmu}.toml", fmu_dir, {
        "Feed": ("FeedKinematics", {"profile": "oscillating", "mean_velocity": 0.0,
                                    "frequency": 20.0}),
        "Friction": (fmu, {"coefficient": 0.01, "F_upper": 100.0, "F_lower": 50.0,
                           "rollers_per_groove": 10, **params}),
        "Rig": ("HorizontalRig", {"mass": 2.0})},
        [("Feed.u", "Friction.u"), ("Feed.a", "Rig.a"), ("Friction.F_friction", "Rig.F_friction")]
        + ([("Feed.x", "Friction.x")] if fmu != "FrictionStribeck" else []), stop=0.1, step=1e-5)
    report = verify(rig)
    # the paths are exact per step and the reference's tolerance is 1e-10: measured 5e-12 to
    # 3e-11 of the force's range
    assert report["rms_error"]["Rig.drive_force"] < 1e-8, report


@pytest.mark.slow
def test_verify_covers_the_ball_carriage_scenario_cross_tool(fmu_dir, tmp_path):
    # the shipped scenario over its first 20 ms (the feed starts at 10 ms): co-simulation with
    # RK4 substeps and held inputs against LSODA on the same model; u and phi stay at round-off
    # (no load drives them), so only the loaded coordinates are compared. Measured: 4e-4 of the
    # range for v, theta, psi and 1.6e-3 for the row load, whose range is small (a ball passing
    # the end of the load zone makes a step the two integrators place slightly apart)
    rig = system.load(scenarios.find("wu2012_ball_carriage_moment"), fmu_dir=fmu_dir)
    rig = dataclasses.replace(rig, experiment=dataclasses.replace(rig.experiment, stop=0.02))
    report = verify(rig)
    for name in ("Carriage.v", "Carriage.theta", "Carriage.psi", "Carriage.row_load_1"):
        assert report["rms_error"][name] < 3e-3, (name, report["rms_error"])


def test_verify_covers_the_feed_unit_milling_scenario_cross_tool(fmu_dir, tmp_path):
    # the shipped scenario over 30 ms: three stateless FMUs in a Gauss-Seidel chain (feed ->
    # end mill -> feed unit) against the reference evaluating the same models at the same
    # instants; each FMU and the reference solve the table's equilibrium from their own last
    # answer, so agreement says the equilibrium is unique and converged. Measured: 1e-15 to
    # 3e-15 of the range
    rig = system.load(scenarios.find("zhang2019_feed_unit_milling"), fmu_dir=fmu_dir)
    rig = dataclasses.replace(rig, experiment=dataclasses.replace(rig.experiment, stop=0.03))
    report = verify(rig)
    for name in ("Mill.F_y", "Unit.delta_y", "Unit.delta_z", "Unit.epsilon_x", "Unit.epsilon_y",
                 "Unit.epsilon_z", "Unit.tool_d_z"):
        assert report["rms_error"][name] < 1e-10, (name, report["rms_error"])


def _ball_row_rig(fmu_dir, step):
    """The shipped ball-to-ball scenario's feed, ball row and rig, the row's load held at the
    carriage's mean (the stiff carriage alone costs minutes in the reference)."""
    lin = system.load(scenarios.find("lin2019_ball_to_ball_friction"), fmu_dir=fmu_dir)
    components = {name: c for name, c in lin.components.items() if name != "Carriage"}
    components["Row"] = system.Component("Row", components["Row"].fmu,
                                         {**components["Row"].parameters, "F_normal": 420.0})
    return system.check(dataclasses.replace(
        lin, components=components, variables={}, feedthrough={},
        connections=tuple(c for c in lin.connections if "Carriage" not in (c.source, c.target)),
        experiment=dataclasses.replace(lin.experiment, stop=0.08, step=step),
        record=("Row.F_friction", "Row.groups", "Rig.drive_force"), plots={}), "row test")


@pytest.mark.slow
def test_ball_row_cosimulation_converges_to_the_reference_between_contact_events(fmu_dir):
    # RK4 substeps with held inputs (event-located) against RK45 on the same row (not smooth)
    # through contacts forming and breaking. The friction jumps where a gap closes or a group
    # parts; held inputs shift those instants by O(h), so the RMS error is dominated by a few
    # samples at the jumps and falls like sqrt(h) only. The yardsticks are the typical error
    # between events (median, first order in h) and the mean friction (the work done).
    errors = []
    for step in (2e-4, 1e-4):
        rig = _ball_row_rig(fmu_dir, step)
        rec = master.simulate(rig).recording
        ref = monolithic.simulate(rig, times=rec.time)
        assert ref.method == "RK45"
        ours, theirs = rec.columns["Row.F_friction"], ref.columns["Row.F_friction"]
        assert np.ptp(theirs) > 0.2 and np.max(ref.columns["Row.groups"]) > np.min(
            ref.columns["Row.groups"])  # contacts do form and break
        errors.append(np.median(np.abs(ours - theirs)) / np.ptp(theirs))
        assert ours.mean() == pytest.approx(theirs.mean(), rel=0.02)
    assert errors[1] < 2e-3  # measured 1.2e-3 of the range at 1e-4 s, 1.2e-4 at 1e-5 s
    assert errors[0] / errors[1] > 1.6  # first order: 2 when the step halves
