"""The kinds of test rig the discrepancy workflow diagnoses, as plug-ins: one :class:`Rig`
subclass per ``[rig] kind`` of the measured-run format, found by workflow.diagnose in RIGS.

A rig gives the workflow three steps over a run read once (run_io.load_run):

- ``decide(run, out, fmu_dir)``: check the record, fit its baseline and every candidate effect,
  score them on held-out samples with scoring.py (BIC, significance, confidence: one home for
  every rig) and return a naming: an object with ``effect`` (a candidate's effect, "none" or
  "unknown"), ``winner`` (its fit, with ``parameters``), ``ranked`` ((score, fit, held-out gap)
  best first), ``steps`` (more_effects.Step, the effects named in turn), ``confidence``,
  ``doubts``, ``corrections``, ``intervals``, ``not_told_apart``, ``experiment``, ``equation``,
  ``noise``, ``run`` and ``held``, which report.diagnosis_record turns into diagnosis.json;
- ``realise(naming, out, fmu_dir)``: write the named model (the baseline's for "none" and
  "unknown") as a scenario of the FMUs and co-simulate it; the result's ``gaps(naming)`` gives
  the held-out gaps before and after;
- ``report(out, naming, realised, seconds)``: write diagnosis.json, fit.csv, the plots and
  report.html with the rig's own sections; return diagnosis.json's content.

Rules for implementers: refuse a record with a ValueError naming the file and the row, column,
section or key; never name an effect whose fitted parameter lies outside its physical range;
state every number a fit gives with its interval where the rig can (scoring.jackknife_intervals);
write answers in the kinds of report.answer_kind (an effect, a wrong baseline parameter, no
discrepancy beyond the noise, a gap no candidate explains); measure the rig on records of a
generator written independently of its candidates.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from pathlib import Path

from .decide import decide
from .realise import realise
from .report import write_report, write_vertical_report
from .run_io import MeasuredRun
from .vertical import decide_vertical, realise_vertical

#: [rig] kind -> the Rig that diagnoses it
RIGS: dict[str, type["Rig"]] = {}


class Rig(ABC):
    """A kind of test rig (module docstring); subclassing with a ``kind`` registers it."""

    kind: str = ""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        RIGS[cls.kind] = cls

    @abstractmethod
    def decide(self, run: MeasuredRun, out: Path, fmu_dir: Path):
        """The naming of ``run`` (module docstring); ``out``: the report's folder."""

    @abstractmethod
    def realise(self, naming, out: Path, fmu_dir: Path):
        """The named model co-simulated through the FMUs of ``fmu_dir``, written into ``out``."""

    @abstractmethod
    def report(self, out: Path, naming, realised, seconds: float) -> dict:
        """Write the report into ``out``; return diagnosis.json's content."""


class HorizontalDrive(Rig):
    """A feed drive along the rail: the drive force or the friction force against the motion
    (decide.py, candidates.py, more_effects.py; realise.py)."""

    kind = "horizontal_drive"

    def decide(self, run, out, fmu_dir):
        return decide(run)

    def realise(self, naming, out, fmu_dir):
        return realise(naming, out, fmu_dir)

    def report(self, out, naming, realised, seconds):
        return write_report(out, naming, realised, seconds)


class VerticalResponse(Rig):
    """The carriage's vertical response to a normal load (vertical.py)."""

    kind = "vertical_response"

    def decide(self, run, out, fmu_dir):
        return decide_vertical(run, out / "model", fmu_dir)

    def realise(self, naming, out, fmu_dir):
        return realise_vertical(naming, out)

    def report(self, out, naming, realised, seconds):
        return write_vertical_report(out, naming, realised, seconds)
