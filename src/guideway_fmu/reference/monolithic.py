"""Monolithic reference (issue 3): a system's equations integrated in one process.

The same equations as the FMUs, built from the same parameters by the same ``from_parameters``
functions of ``physics/``, integrated with SciPy's ``solve_ivp`` at a tight tolerance: the
reference that co-simulation results are measured against. A component is recognised by its
FMU's model identifier (FeedKinematics, ContactEHL, ContactDryHertz, VerticalDynamics,
FrictionMixedEHL, FrictionCoulomb); its parameters are the FMU's start values overridden by the
scenario's, and ``system.connections`` say which body drives which contact.

Equations, in continuous time:

* state: y [m] and y_dot [m/s] of every VerticalDynamics body, and the films h_U, h_L [m] of every
  ContactEHL with film_model "extrapolated" (``RowKernel.film_rate``, the squeeze relation);
* M y'' = M g + F_e(t) + F_ext - F_contact, F_e the ``ExternalLoad`` of the load_* parameters at
  t, F_ext constant (its start value or the scenario's), F_contact the net force of the contact
  whose F_contact output feeds the body, plus damping * y_dot. The body's K_contact, C_contact
  and law_* inputs and the contact's interpolate_inputs (``STEP_SETTINGS``) are not used: they
  only shape the FMUs' steps, not the equations;
* the feed velocity u is the profile evaluated at t (``velocity_at``); an unconnected input is
  constant at its start value; the dry contact has no film; film_model "pan_hamrock" is the
  quasi-static film of ``guideway.quasi_static_state`` at every evaluation (no state, slow);
* initial state: y_start, y_dot_start, and the films of ``quasi_static_state`` at y_start and
  u(start), as ``ContactEHL.initialise``.

Outputs are evaluated on the trajectories with the array functions of ``physics/`` (the
independent check of ``RowKernel``): every output of every component. Tolerances: ``rtol`` as
given and atol = rtol x scale, the scale being the contact's preload approach delta0 (about 1 um)
for y and the films and delta0 * omega0 for y_dot (omega0 the dry natural angular frequency).

Integrators (``benchmarks/monolithic_integrators.py``), over 0.01 s of the unloaded rig
(bi-harmonic feed, extrapolated film, rail, mixed friction) and of the same rig under a
9000 N / 4500 Hz harmonic load: wall time of the integration (2-CPU machine shared with other
jobs, least of three runs, about +-30 %), and the RMS difference of Contact.F_upper from a DOP853
run at rtol 1e-12, relative to the range of F_upper (4.8 N unloaded, 1690 N loaded):

======  =====  ==================================  ==================================
method  rtol   unloaded: wall [s], nfev, RMS diff   loaded: wall [s], nfev, RMS diff
======  =====  ==================================  ==================================
LSODA   1e-8   0.10     3 462   6.4e-5              0.54    24 112   2.7e-6
LSODA   1e-10  0.14     5 253   5.8e-7              0.90    43 351   7.1e-8
Radau   1e-8   1.5     22 061   9.2e-8              8.4    100 453   6.9e-8
Radau   1e-10  5.4     90 331   5.5e-10             21     300 261   5.3e-9
DOP853  1e-8   0.16     5 348   3.9e-6              1.1     44 564   1.9e-6
DOP853  1e-10  0.25     9 428   3.9e-8              1.8     73 469   4.7e-9
======  =====  ==================================  ==================================

Default: LSODA at rtol 1e-10, about 15 s (unloaded) to 90 s (loaded) of wall time per simulated
second: as fast as DOP853 or faster, 15 to 40 times faster than Radau, and with an error below
1e-6 of the signal's range, far below any co-simulation error worth measuring (at rtol 1e-8 its
error grows to 6e-5 on the unloaded rig, whose F_upper varies by only 3 %). These rigs are not
stiff at these tolerances: LSODA stays with its Adams method all the way, and Radau pays for its
implicit stages and Jacobians with many more evaluations. LSODA switches to BDF by itself where
a system is stiff (a large contact damping, for example), which the explicit DOP853 cannot.
Pass ``method="Radau"`` or a smaller rtol for a more accurate reference.
"""
from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import numpy as np
from fmpy import read_model_description
from scipy.integrate import solve_ivp

from ..physics import carriage, feed_profiles, guideway
from ..physics import roller_friction as friction
from ..physics import roller_contact as rc

#: model identifier -> the function that builds its physics from the FMU's parameters
BUILDERS = {
    "FeedKinematics": feed_profiles.from_parameters,
    "VerticalDynamics": carriage.from_parameters,
    "ContactEHL": guideway.from_parameters,
    "ContactDryHertz": guideway.from_parameters,
    "FrictionMixedEHL": friction.mixed_from_parameters,
    "FrictionCoulomb": friction.coulomb_from_parameters,
}
#: model identifier -> parameters that shape the FMU's step only (not the equations): left out
STEP_SETTINGS = {"ContactEHL": ("interpolate_inputs",)}
CONTACTS = ("ContactEHL", "ContactDryHertz")
FRICTIONS = ("FrictionMixedEHL", "FrictionCoulomb")


@dataclass
class Reference:
    """A reference run: ``columns`` maps "<instance>.<variable>" to values at ``time`` [s].

    ``wall_time`` [s] is that of the integration alone, ``nfev`` its right-hand side evaluations.
    """

    time: np.ndarray
    columns: dict[str, np.ndarray]
    units: dict[str, str]
    wall_time: float
    nfev: int
    method: str
    rtol: float


def check(system) -> None:
    """Raise ValueError naming the component if the reference cannot model ``system``."""
    _Model(system)


def simulate(system, times=None, rtol: float = 1e-10, method: str = "LSODA") -> Reference:
    """Integrate ``system`` (a checked ``cosim.system.System``) from experiment.start.

    ``times`` [s], increasing and not before the start, are the output times; by default the
    macro-step grid start, start + step, ..., stop. ``method`` is a ``solve_ivp`` method.
    Raises ValueError naming the component for a component or a wiring that the reference
    cannot model, RuntimeError when the integration fails.
    """
    exp = system.experiment
    if times is None:
        times = exp.start + exp.step * np.arange(int(round((exp.stop - exp.start) / exp.step)) + 1)
    times = np.asarray(times, dtype=float)
    if times.ndim != 1 or times.size < 2 or np.any(np.diff(times) <= 0) or times[0] < exp.start:
        raise ValueError(f"times must increase, from the start time {exp.start} s on, got {times!r}")
    model = _Model(system)
    y0 = model.initial_state(exp.start)
    t0 = time.perf_counter()
    sol = solve_ivp(model.rhs, (exp.start, times[-1]), y0, method=method, t_eval=times,
                    rtol=rtol, atol=model.atol(rtol))
    wall = time.perf_counter() - t0
    if not sol.success:
        raise RuntimeError(f"{system.name}: {method} failed at rtol {rtol}: {sol.message}")
    columns = model.outputs(sol.t, sol.y)
    units = {k: system.unit(*k.split(".", 1)) for k in columns}
    return Reference(sol.t, columns, units, wall, int(sol.nfev), method, rtol)


# -- reading the system ----------------------------------------------------------------------
def _typed(variable, value):
    """A start value (a string) or a scenario's value as the Python type of the variable."""
    if variable.type == "Real":
        return float(value)
    if variable.type in ("Integer", "Enumeration"):
        return int(value)
    if variable.type == "Boolean":
        return value if isinstance(value, bool) else value in ("true", "1")
    return value


class _Component:
    """One component: its kind (model identifier), parameter and input values, its physics
    (what ``BUILDERS`` returns); :class:`_Model` adds its slots and wiring."""

    def __init__(self, system, name: str):
        comp = system.components[name]
        md = read_model_description(str(comp.fmu))
        ids = (md.coSimulation.modelIdentifier if md.coSimulation else None, md.modelName)
        kind = next((i for i in ids if i in BUILDERS), None)
        if kind is None:
            raise ValueError(f"component {name!r}: FMU {comp.fmu.name} (model identifier "
                             f"{ids[0]!r}) cannot be modelled by the monolithic reference; it "
                             f"knows {', '.join(BUILDERS)}")
        variables = {v.name: v for v in md.modelVariables}
        values = {n: _typed(v, v.start) for n, v in variables.items()
                  if v.causality in ("parameter", "input") and v.start is not None}
        values.update({n: _typed(variables[n], v) for n, v in comp.parameters.items()})
        self.name, self.kind, self.values = name, kind, values
        self.inputs = [n for n, v in variables.items() if v.causality == "input"]
        params = {n: values[n] for n, v in variables.items()
                  if v.causality == "parameter" and n not in STEP_SETTINGS.get(kind, ())}
        try:
            self.physics = BUILDERS[kind](**params)
        except (TypeError, ValueError) as exc:
            raise self.error(f"its parameters cannot be modelled: {exc}") from exc

    def error(self, message: str) -> ValueError:
        return ValueError(f"component {self.name!r} ({self.kind}): {message}")


class _Model:
    """The wired system: state layout, right-hand side and outputs.

    The right-hand side reads every signal by slot from one list of floats: the state, then the
    feed velocities, then the constant (unconnected) inputs.
    """

    def __init__(self, system):
        self.comps = {name: _Component(system, name) for name in system.components}
        self.sources = {(c.target, c.input): (c.source, c.output) for c in system.connections}

        def of(*kinds):
            return [c for c in self.comps.values() if c.kind in kinds]

        self.feeds, self.bodies = of("FeedKinematics"), of("VerticalDynamics")
        self.contacts, self.frictions = of(*CONTACTS), of(*FRICTIONS)
        self.slot: dict[str, int] = {}  # "<instance>.<variable>" -> slot of a state or velocity
        for b in self.bodies:
            b.iy = self._new_slot(b, "y")
            self._new_slot(b, "y_dot")
        for c in self.contacts:
            c.model = "dry" if c.kind == "ContactDryHertz" else c.physics[0].contact.model
            c.ih = self._new_slot(c, "h_upper") if c.model == "extrapolated" else None
            if c.ih is not None:
                self._new_slot(c, "h_lower")
        self.n = len(self.slot)
        for f in self.feeds:
            if f.physics is None:
                raise f.error("profile 'input' (the velocity from the u_cmd input) is not "
                              "supported; choose an analytic or a table profile")
            self._new_slot(f, "u")
        self.velocities = [f.physics.velocity_at for f in self.feeds]
        self.consts: list[float] = []
        self._wire()

    def _new_slot(self, comp, variable: str) -> int:
        self.slot[f"{comp.name}.{variable}"] = len(self.slot)
        return len(self.slot) - 1

    # -- wiring ------------------------------------------------------------------------------
    def _input_slot(self, comp: _Component, name: str, kind: str, output: str,
                    required: bool = False) -> int:
        """Slot of input ``name``: fed by ``output`` of a ``kind`` component, or unconnected
        (unless ``required``) and then constant at its value."""
        src = self.sources.get((comp.name, name))
        if src is None and not required:
            self.consts.append(float(comp.values.get(name, 0.0)))
            return len(self.slot) + len(self.consts) - 1
        if src is None or self.comps[src[0]].kind != kind or src[1] != output:
            got = "unconnected" if src is None else f"fed by {'.'.join(src)}"
            raise comp.error(f"input {name} is {got}; the monolithic reference needs it "
                             f"{'' if required else 'constant or '}fed by the {output} output of "
                             f"a {kind} component")
        return self.slot[".".join(src)]

    def _wire(self):
        for c in self.contacts:
            c.iy = self._input_slot(c, "y", "VerticalDynamics", "y", required=True)
            c.iv = self._input_slot(c, "y_dot", "VerticalDynamics", "y_dot")
            c.iu = self._input_slot(c, "u", "FeedKinematics", "u")
            c.force = self._force_function(c)
        for b in self.bodies:
            src = self.sources.get((b.name, "F_contact"))
            if src is None or self.comps[src[0]].kind not in CONTACTS or src[1] != "F_contact":
                got = "unconnected" if src is None else f"fed by {'.'.join(src)}"
                raise b.error(f"input F_contact is {got}; the monolithic reference needs it fed "
                              f"by the F_contact output of a {' or '.join(CONTACTS)} component")
            if (b.name, "F_ext") in self.sources:
                raise b.error(f"input F_ext is fed by {'.'.join(self.sources[(b.name, 'F_ext')])}; "
                              "the monolithic reference supports only a constant F_ext")
            b.contact = self.contacts.index(self.comps[src[0]])
        producers = [k for k in BUILDERS if k not in FRICTIONS]
        for f in self.frictions:
            f.ins = {}
            for name in f.inputs:
                src = self.sources.get((f.name, name))
                if src is not None and self.comps[src[0]].kind not in producers:
                    raise f.error(f"input {name} is fed by {'.'.join(src)}; the monolithic "
                                  f"reference supports inputs from {', '.join(producers)} only")
                f.ins[name] = src or float(f.values.get(name, 0.0))
        self.body_terms = [(b.iy, b.contact, b.physics[0].gravity, b.physics[1],
                            b.values["F_ext"], b.physics[0].mass) for b in self.bodies]

    @staticmethod
    def _force_function(c: _Component):
        """force(signals, rates) -> the net contact force [N] of ``c``; writes its film rates."""
        g, kernel = c.physics
        iy, iv, iu, ih, damping = c.iy, c.iv, c.iu, c.ih, c.values["damping"]
        contact, film_rate = kernel.contact, kernel.film_rate
        if c.model == "extrapolated":
            def force(sig, rates):
                hu, hl = sig[ih], sig[ih + 1]
                f, _, fu, fl = contact(sig[iy], hu, hl)
                speed = abs(sig[iu])
                rates[ih], rates[ih + 1] = film_rate(hu, fu, speed), film_rate(hl, fl, speed)
                return f + damping * sig[iv]
        elif c.model == "pan_hamrock":
            def force(sig, rates):
                fu, fl, _, _ = guideway.quasi_static_state(g, sig[iy], sig[iu])
                return kernel.gain * float(fu - fl) + damping * sig[iv]
        else:
            def force(sig, rates):
                return contact(sig[iy], 0.0, 0.0)[0] + damping * sig[iv]
        return force

    # -- integration -------------------------------------------------------------------------
    def _signals(self, t: float, s) -> list:
        return s.tolist() + [v(t) for v in self.velocities] + self.consts

    def initial_state(self, start: float) -> np.ndarray:
        """The state at the start time [s] (module doc)."""
        s = np.zeros(self.n)
        for b in self.bodies:
            s[b.iy], s[b.iy + 1] = b.values["y_start"], b.values["y_dot_start"]
        sig = self._signals(start, s)
        for c in self.contacts:
            if c.ih is not None:
                _, _, hu, hl = guideway.quasi_static_state(c.physics[0], sig[c.iy], sig[c.iu])
                s[c.ih], s[c.ih + 1] = hu, hl
        return s

    def atol(self, rtol: float) -> np.ndarray:
        """rtol x the preload approach delta0 [m] of the contact (y, films) or delta0 omega0."""
        atol = np.empty(self.n)
        for b in self.bodies:
            body, _ = b.physics
            g, kernel = self.contacts[b.contact].physics
            omega0 = math.sqrt(kernel.contact(0.0, 0.0, 0.0)[1] / body.mass)
            atol[b.iy], atol[b.iy + 1] = rtol * g.delta0, rtol * g.delta0 * omega0
        for c in self.contacts:
            if c.ih is not None:
                atol[c.ih: c.ih + 2] = rtol * c.physics[0].delta0
        return atol

    def rhs(self, t: float, s) -> list:
        """d(state)/dt at the time t [s]."""
        sig = self._signals(t, s)
        rates = [0.0] * self.n
        forces = [c.force(sig, rates) for c in self.contacts]
        for iy, k, gravity, load, f_ext, mass in self.body_terms:
            rates[iy] = sig[iy + 1]
            rates[iy + 1] = gravity + (load(t) + f_ext - forces[k]) / mass
        return rates

    # -- outputs -----------------------------------------------------------------------------
    def outputs(self, t: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        """Every output of every component at the times t [s], in the system's order."""
        n = t.size
        feeds = {f.name: f.physics.evaluate(t) for f in self.feeds}
        sig = [*states, *(feeds[f.name][1] for f in self.feeds),
               *(np.full(n, c) for c in self.consts)]
        out = {name: {} for name in self.comps}
        for f in self.feeds:
            out[f.name] = dict(zip(("x", "u", "a"), feeds[f.name]))
        for c in self.contacts:
            out[c.name] = self._contact_outputs(c, sig)
        for b in self.bodies:
            body, load = b.physics
            force = out[self.contacts[b.contact].name]["F_contact"]
            f_e = np.fromiter(map(load, t), float, n)
            out[b.name] = {"y": sig[b.iy], "y_dot": sig[b.iy + 1],
                           "y_ddot": body.gravity + (f_e + b.values["F_ext"] - force) / body.mass}
        for f in self.frictions:
            ins = {name: out[src[0]][src[1]] if isinstance(src, tuple) else np.full(n, src)
                   for name, src in f.ins.items()}
            if f.kind == "FrictionMixedEHL":
                values = friction.mixed_ehl_friction(ins["F_upper"], ins["F_lower"], ins["h_upper"],
                                                     ins["h_lower"], ins["u"], f.physics)
                out[f.name] = dict(zip(("F_friction", "F_boundary", "F_viscous"), values))
            else:
                out[f.name] = {"F_friction": friction.coulomb_friction(
                    ins["F_upper"], ins["F_lower"], ins["u"], f.physics)}
        return {f"{name}.{k}": np.asarray(v, dtype=float)
                for name, values in out.items() for k, v in values.items()}

    @staticmethod
    def _contact_outputs(c: _Component, sig) -> dict[str, np.ndarray]:
        g, _ = c.physics
        y, v, u = sig[c.iy], sig[c.iv], sig[c.iu]
        if c.model == "pan_hamrock":
            state = guideway.quasi_static_state(g, y, u)
            fu, fl, hu, hl = state
            k = guideway.quasi_static_stiffness(g, y, u, state=state)
        else:
            hu, hl = (sig[c.ih], sig[c.ih + 1]) if c.ih is not None else (0.0 * y, 0.0 * y)
            fu, fl = guideway.row_loads(g, y, hu, hl)
            k = guideway.frozen_film_stiffness(g, y, hu, hl)
        damping = c.values["damping"]
        rates = (guideway.film_rates(g, y, hu, hl, u) if c.model == "extrapolated"
                 else (0.0 * y, 0.0 * y))
        law_gain = 0.0 if c.model == "pan_hamrock" else float(guideway.net_force(
            g, rc.contact_force(rc.MICRON, g.k), 0.0))
        full = functools.partial(np.full, y.shape)
        return {"F_contact": guideway.net_force(g, fu, fl) + damping * v, "F_upper": fu,
                "F_lower": fl, "h_upper": hu, "h_lower": hl, "K_contact": k,
                "C_contact": full(damping), "law_force_1um": full(law_gain),
                "law_exponent": full(rc.EXPONENT), "law_sine": full(math.sin(g.contact_angle)),
                "law_approach_upper": g.delta0 + hu, "law_approach_lower": g.delta0 + hl,
                "law_rate_upper": rates[0], "law_rate_lower": rates[1]}
