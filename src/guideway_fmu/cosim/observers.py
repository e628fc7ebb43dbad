"""What watches a run: the execution (master.py) notifies observers, as libcosim does.

An observer is told when the run starts (after initialisation), after every accepted macro step
and when the loop ends (also when it fails). It reads what it needs from the bus
(``bus.values[(instance, variable)]``; ``bus.observe()`` refreshes the recorded-only variables);
it must not write to the FMUs. The recorder (recording.py) and the progress bar are observers;
``master.simulate(system, observers=...)`` takes more.
"""
from __future__ import annotations

from tqdm import tqdm

PROGRESS_EVERY = 2000  # macro steps between progress-bar updates


class Observer:
    """Base class: every notification does nothing."""

    def started(self, system, bus) -> None:
        """The run starts at system.experiment.start, every instance initialised."""

    def stepped(self, t: float, bus) -> None:
        """A macro step was accepted; the instances are at the time t [s]."""

    def finished(self, result) -> None:
        """The loop ended (``result.error`` is not set yet when it failed)."""


class ProgressBar(Observer):
    """A tqdm bar over the simulated time, updated every PROGRESS_EVERY steps."""

    def started(self, system, bus):
        exp = system.experiment
        self.start, self.steps, self.t = exp.start, 0, exp.start
        self.bar = tqdm(total=exp.stop - exp.start, unit="s", desc=system.name,
                        bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} s [{elapsed}<{remaining}]")

    def stepped(self, t, bus):
        self.steps, self.t = self.steps + 1, t
        if self.steps % PROGRESS_EVERY == 0:
            self.bar.update(t - self.start - self.bar.n)

    def finished(self, result):
        self.bar.update(self.t - self.start - self.bar.n)  # where it stopped, the stop or not
        self.bar.close()
