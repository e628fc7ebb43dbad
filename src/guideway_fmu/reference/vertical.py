"""The vertical rig's equations fused into one right-hand side, for fits that simulate it often.

The system is the vertical rig of ``scenarios.vertical_rig`` (the vertical diagnosis's model): a
feed replay and a force table drive a VerticalDynamics carriage coupled to a roller contact (dry
or with its two film states), y and y_dot to the contact and its force back. Its models are the monolithic
reference's own (``monolithic._Block``: each component's continuous-time model from its FMU's
start values and the scenario's parameters), so the equations are those of ``physics/``; only
the assembly is fused. The right-hand side calls them on plain floats
(CarriageModel.acceleration, the contact's RowKernel.contact and film_rates, the replay's
velocity_at, the force table) in place of the generic assembly's dictionaries of inputs and
outputs: about a fifth of its cost.

The measured inputs are tables on the sample times, linear between them: their slopes jump at
every sample. A multistep method (LSODA, the generic reference's) carries its history across
those kinks, which keeps it at order 2-4 and about 12 steps per sample interval. A one-step
method restarted at every sample sees only smooth pieces: Hairer's DOP853 (``scipy.integrate.ode``,
Fortran) takes one 12-stage step per interval, about half the right-hand sides, and comes out
several times closer to the exact solution at the same tolerance.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import ode

from ..scenarios import vertical_rig_wiring
from .monolithic import _Block

#: the wiring the fused model stands for, scenarios.vertical_rig's: (target, input) -> (source,
#: output)
WIRING = {tuple(target.split(".")): tuple(source.split("."))
          for source, target in vertical_rig_wiring()}
DRIVES = ("Feed", "Load")  # the components that replay the record's tables
COLUMNS = ("Carriage.y", "Carriage.y_ddot")
FILM_MODELS = ("dry", "extrapolated")  # the contact's force is RowKernel.contact's for these
MAX_STEPS = 100_000  # DOP853 steps within one sample interval, at most


class FusedVertical:
    """The vertical system of FMUs ``system`` (a cosim.system.System wired as WIRING, its
    components named Feed, Load, Carriage and Contact, the contact undamped) as one right-hand
    side. ``like``: a FusedVertical of a system with the same Feed and Load components, whose
    tables are then not read again. Raises ValueError naming the connection, component or
    parameter that differs."""

    def __init__(self, system, like: FusedVertical | None = None):
        wiring = {(c.target, c.input): (c.source, c.output) for c in system.connections}
        for key, source in WIRING.items():
            if wiring.get(key) != source:
                raise ValueError(f"{system.name}: the fused vertical model needs "
                                 f"{'.'.join(source)} -> {'.'.join(key)}, got "
                                 f"{'.'.join(wiring[key]) if key in wiring else 'none'}")
        self.carriage = _Block(system, "Carriage").model
        self.contact = _Block(system, "Contact").model
        if self.contact.damping != 0.0:
            raise ValueError(f"{system.name}: component 'Contact' parameter damping: the fused "
                             f"vertical model takes an undamped contact, got "
                             f"{self.contact.damping}")
        if self.contact.film_model not in FILM_MODELS:
            raise ValueError(f"{system.name}: component 'Contact' parameter film_model: the "
                             f"fused vertical model takes 'extrapolated', got "
                             f"{self.contact.film_model!r}")
        self.kernel = self.contact.kernel
        self.drives = {name: (system.components[name].fmu, system.components[name].parameters)
                       for name in DRIVES}
        if like is not None and like.drives == self.drives:
            self.velocity, self.load = like.velocity, like.load
        else:
            self.velocity = _Block(system, "Feed").model.profile.velocity_at
            self.load = _Block(system, "Load").model.table
        self.t_start = system.experiment.start
        y, y_dot = self.carriage.initial_state(self.t_start, {})
        films = self.contact.initial_state(self.t_start, {"y": y, "y_dot": y_dot,
                                                           "u": self.velocity(self.t_start)})
        self.start = np.array([y, y_dot, *films], dtype=float)
        self.scales = np.asarray([*self.carriage.state_scales(), *self.contact.state_scales()],
                                 dtype=float)
        self.films = bool(self.contact.states)

    def rhs(self, t: float, x) -> tuple:
        """d(y, y_dot[, h_upper, h_lower])/dt at the time t [s]."""
        x = x.tolist()  # floats: the models' arithmetic is several times faster on them
        if self.films:
            y, y_dot, h_upper, h_lower = x
            force = self.kernel.contact(y, h_upper, h_lower)[0]
            return (y_dot, self.carriage.acceleration(t, force, self.load(t)),
                    *self.kernel.film_rates(y, h_upper, h_lower, self.velocity(t)))
        y, y_dot = x
        force = self.kernel.contact(y, 0.0, 0.0)[0]
        return y_dot, self.carriage.acceleration(t, force, self.load(t))

    def simulate(self, times, rtol: float, columns=COLUMNS) -> dict[str, np.ndarray]:
        """``columns`` (of COLUMNS) at the sample times ``times`` [s] (increasing, the first the
        system's start): DOP853 from sample to sample (module doc) at the relative tolerance
        ``rtol`` and the absolute tolerance rtol x the smallest nominal scale of the states
        (dop853 takes one: at least as tight on every state as the monolithic reference's rtol x
        each state's scale, at fewer right-hand sides than integrating the states over their
        scales, whose extra arithmetic costs a quarter of a right-hand side). Raises ValueError
        for times it cannot take, RuntimeError when the integration fails."""
        times = np.asarray(times, dtype=float)
        steps = np.diff(times)
        if times.ndim != 1 or times.size < 2 or times[0] != self.t_start or np.any(steps <= 0):
            raise ValueError(f"times must increase from the start time {self.t_start} s, got "
                             f"{times!r}")
        for name in columns:
            if name not in COLUMNS:
                raise ValueError(f"column {name!r}: the fused vertical model gives "
                                 f"{', '.join(COLUMNS)}")
        solver = ode(self.rhs).set_integrator(
            "dop853", rtol=rtol, atol=rtol * float(self.scales.min()),
            first_step=float(steps.max()), nsteps=MAX_STEPS)
        solver.set_initial_value(self.start, times[0])
        states = np.empty((times.size, self.start.size))
        states[0] = self.start
        for i in range(1, times.size):
            states[i] = solver.integrate(times[i])
            if not solver.successful():
                raise RuntimeError(f"fused vertical model: DOP853 failed at t = {solver.t} s "
                                   f"(rtol {rtol}, return code {solver.get_return_code()})")
        out = {"Carriage.y": states[:, 0].copy()}
        if "Carriage.y_ddot" in columns:
            out["Carriage.y_ddot"] = np.array([self.rhs(t, x)[1] for t, x in zip(times, states)])
        return {name: out[name] for name in columns}
