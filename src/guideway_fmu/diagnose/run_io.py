"""Reading and checking a measured run (format: docs/measured-run.md, version 1).

:func:`load_run` returns a :class:`MeasuredRun` or raises FileNotFoundError / ValueError with one
message naming the file and the row, column, section or key that is wrong. Rows are numbered as
lines of data.csv, the header being row 1.
"""
from __future__ import annotations

import csv
import math
import tomllib
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..physics.roller_guide.carriage import STANDARD_GRAVITY
from . import plausible
FORMAT = "guideway-measured-run/1"
KINDS = ("horizontal_drive", "vertical_response")
#: data.csv columns of the format and their units
VOCABULARY = {
    "time": "s", "feed_position": "m", "feed_velocity": "m/s", "feed_acceleration": "m/s2",
    "drive_force": "N", "friction_force": "N", "normal_force": "N",
    "vertical_displacement": "m", "vertical_acceleration": "m/s2",
}
GUIDEWAY_TYPES = ("roller", "ball")
#: [guideway] keys that must be > 0 (rows and elements_per_row: whole numbers >= 1; preload >= 0)
POSITIVE_GUIDEWAY = ("element_radius", "roller_length", "reduced_modulus")
#: Pa, [guideway] reduced_modulus where a rig file states none: steel on steel, the format's
#: default (not a paper's E')
REDUCED_MODULUS = 2.0e11
#: conventions of a friction_force channel: the force resisting the motion (opposite to
#: feed_velocity), or the force a sensor feels (along the motion); the workflow works along it
FRICTION_SIGNS = ("opposes_motion", "along_motion")
#: [model] key -> component name -> {section: keys it needs}
COMPONENTS = {
    "friction": {
        "coulomb": {},
        "mixed_ehl": {"guideway": ("rows", "elements_per_row", "element_radius", "roller_length",
                                   "preload"),
                      "lubricant": ("viscosity", "pressure_viscosity"),
                      "surface": ("roughness_rms",)},
    },
    "contact": {
        "dry_hertz": {"guideway": ("rows", "elements_per_row", "element_radius", "roller_length",
                                   "contact_angle_deg", "preload")},
        "ehl": {"guideway": ("rows", "elements_per_row", "element_radius", "roller_length",
                             "contact_angle_deg", "preload"),
                "lubricant": ("viscosity", "pressure_viscosity")},
    },
}
MIN_SAMPLES = 50


@dataclass
class MeasuredRun:
    """A checked measured run: rig.toml's tables and data.csv's columns (SI units)."""

    path: Path
    kind: str
    moving_mass: float  # kg
    model: dict  # [model]: component kind -> name
    inputs: list
    outputs: list
    time: np.ndarray  # s
    columns: dict  # vocabulary name -> samples
    sections: dict = field(default_factory=dict)  # guideway, lubricant, surface, load tables
    description: str = ""
    warnings: list = field(default_factory=list)
    friction_sign: str | None = None  # [channels] friction_sign as stated, or as found
    friction_sign_stated: bool = False
    channel_delay: float = 0.0  # s, the compared channel's delay behind the motion, undone
    oriented: bool = False  # friction_force already turned along the motion (orient_friction)

    @property
    def channel_sign(self) -> float:
        """-1 where the compared channel was turned to the workflow's convention (friction_force
        opposing the motion), else 1: the factor back to the record's own values."""
        return -1.0 if self.friction_sign == "opposes_motion" else 1.0

    def orient_friction(self, velocity) -> None:
        """Turn a friction_force channel along the motion, by the stated [channels]
        friction_sign or, without it, by the sign the data show: the level of friction_force
        along sgn(v) over the samples moving faster than a tenth of the top speed."""
        if "friction_force" not in self.columns or self.oriented:
            return
        self.oriented = True
        if self.friction_sign is None:
            v = np.asarray(velocity, dtype=float)
            moving = np.abs(v) > 0.1 * np.max(np.abs(v))
            along = float(np.mean(self.columns["friction_force"][moving] * np.sign(v[moving])))
            self.friction_sign = "along_motion" if along >= 0.0 else "opposes_motion"
        if self.friction_sign == "opposes_motion":
            self.columns["friction_force"] = -self.columns["friction_force"]

    @property
    def channel(self) -> str:
        """The compared channel: the first entry of [channels] outputs."""
        return self.outputs[0]

    def normal_force(self) -> float:
        """Mean external vertical load [N]: the channel where present, else [load], else 0."""
        if "normal_force" in self.columns:
            return float(np.mean(self.columns["normal_force"]))
        return float(self.sections.get("load", {}).get("normal_force", 0.0))

    def normal_load(self) -> float:
        """Total load [N] pressing the carriage onto the rail: the [guideway] preload, the
        moving mass's weight and the external load (:meth:`normal_force`)."""
        return (float(self.sections.get("guideway", {}).get("preload", 0.0))
                + self.moving_mass * STANDARD_GRAVITY + self.normal_force())


def _need_file(path: Path) -> Path:
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such file (a measured run needs rig.toml and data.csv)")
    return path


def _text(path: Path) -> str:
    """The file's text; a file that is not UTF-8 raises ValueError naming the line and byte."""
    raw = _need_file(path).read_bytes()
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        raise ValueError(f"{path}: line {line}: byte {raw[exc.start]:#04x} is not UTF-8 text "
                         "(save the file as UTF-8)") from None


def _number(source, table, key, value, positive=False, non_negative=False):
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    if ok and positive:
        ok = value > 0
    if ok and non_negative:
        ok = value >= 0
    if not ok:
        want = "a number > 0" if positive else "a number >= 0" if non_negative else "a finite number"
        raise ValueError(f"{source}: [{table}] key '{key}' must be {want}, got {value!r}")
    return float(value)


def _table(source, data, name, required=True):
    value = data.get(name)
    if value is None:
        if required:
            raise ValueError(f"{source}: section [{name}] is missing")
        return None
    if not isinstance(value, dict):
        raise ValueError(f"{source}: [{name}] must be a table, got {type(value).__name__}")
    return value


def read_rig(path: Path) -> dict:
    """rig.toml as a checked dict (format, [rig], optional sections, [model], [channels])."""
    source = str(path)
    try:
        data = tomllib.loads(_text(path))
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{source}: not valid TOML: {exc}") from None
    if data.get("format") != FORMAT:
        raise ValueError(f"{source}: key 'format' must be {FORMAT!r}, got {data.get('format')!r}")
    rig = _table(source, data, "rig")
    if rig.get("kind") not in KINDS:
        raise ValueError(f"{source}: [rig] key 'kind' must be one of {KINDS}, got {rig.get('kind')!r}")
    rig["moving_mass"] = _number(source, "rig", "moving_mass", rig.get("moving_mass"), non_negative=True)
    sections = {}
    for name in ("guideway", "lubricant", "surface", "load"):
        table = _table(source, data, name, required=False)
        if table is not None:
            for key, value in table.items():
                if key != "type":
                    _number(source, name, key, value)
            sections[name] = table
    guideway = sections.get("guideway", {})
    for key in ("rows", "elements_per_row"):
        if key in guideway and not (isinstance(guideway[key], int) and guideway[key] >= 1):
            raise ValueError(f"{source}: [guideway] key '{key}' must be a whole number >= 1, "
                             f"got {guideway[key]!r}")
    for key in POSITIVE_GUIDEWAY:
        if key in guideway:
            _number(source, "guideway", key, guideway[key], positive=True)
    if "preload" in guideway:
        _number(source, "guideway", "preload", guideway["preload"], non_negative=True)
    if not 0.0 < guideway.get("contact_angle_deg", 45.0) < 90.0:
        raise ValueError(f"{source}: [guideway] key 'contact_angle_deg' must lie between 0 and "
                         f"90, got {guideway['contact_angle_deg']!r}")
    if "type" in guideway and guideway["type"] not in GUIDEWAY_TYPES:
        raise ValueError(f"{source}: [guideway] key 'type' must be one of {GUIDEWAY_TYPES}, "
                         f"got {guideway['type']!r}")
    model = _table(source, data, "model")
    for kind, name in model.items():
        if kind not in COMPONENTS:
            raise ValueError(f"{source}: [model] key '{kind}' is not a component kind "
                             f"(known: {', '.join(COMPONENTS)})")
        if name not in COMPONENTS[kind]:
            raise ValueError(f"{source}: [model] key '{kind}': unknown component {name!r} "
                             f"(known: {', '.join(COMPONENTS[kind])})")
        for section, keys in COMPONENTS[kind][name].items():
            if section not in sections:
                raise ValueError(f"{source}: [model] {kind} = {name!r} needs section [{section}], "
                                 f"which is missing")
            ball = sections.get("guideway", {}).get("type") == "ball"
            for key in keys:
                if key == "roller_length" and ball:
                    continue  # rollers only
                if key not in sections[section]:
                    raise ValueError(f"{source}: [model] {kind} = {name!r} needs key '{key}' in "
                                     f"[{section}], which is missing")
    if "friction" not in model:
        raise ValueError(f"{source}: [model] key 'friction' is missing (the friction component "
                         f"of the baseline)")
    channels = _table(source, data, "channels")
    for key in ("inputs", "outputs"):
        names = channels.get(key)
        if not isinstance(names, list) or not names:
            raise ValueError(f"{source}: [channels] key '{key}' must be a non-empty list of "
                             f"column names, got {names!r}")
        for name in names:
            if name not in VOCABULARY or name == "time":
                raise ValueError(f"{source}: [channels] key '{key}': {name!r} is not a channel "
                                 f"of the format (known: {', '.join(list(VOCABULARY)[1:])})")
    sign = channels.get("friction_sign")
    if sign is not None:
        if sign not in FRICTION_SIGNS:
            raise ValueError(f"{source}: [channels] key 'friction_sign' must be one of "
                             f"{FRICTION_SIGNS}, got {sign!r}")
        if "friction_force" not in channels["inputs"] + channels["outputs"]:
            raise ValueError(f"{source}: [channels] key 'friction_sign' goes with a "
                             f"friction_force channel, and none is listed")
    return {"rig": rig, "sections": sections, "model": dict(model), "channels": channels}


def read_data(path: Path) -> tuple[np.ndarray, dict, list]:
    """data.csv as (time, {column: samples}, warnings) after checking every cell. The file is
    read line by line into a float array (8 bytes a cell), once its text is known to be UTF-8:
    a record of 1e6 rows held as lists of cells took over half a gigabyte, as one string in a
    text buffer 4 bytes a character."""
    source = str(path)
    lines = _text(path).count("\n") + 1
    with path.open(encoding="utf-8", newline="") as handle:
        return _parse(source, csv.reader(handle), lines)


def _parse(source: str, reader, lines: int) -> tuple[np.ndarray, dict, list]:
    """:func:`read_data` on the rows of ``reader`` (at most ``lines`` of them)."""
    header = [cell.strip() for cell in next(reader, [])]
    if not header:
        raise ValueError(f"{source}: empty file, expected a header row starting with 'time'")
    if header[0] != "time":
        raise ValueError(f"{source}: row 1: the first column must be 'time', got {header[:1]}")
    seen = set()
    for name in header:
        if name in seen:
            raise ValueError(f"{source}: row 1: column {name!r} appears twice")
        seen.add(name)
    notes = [f"{source}: column {name!r} is not in the format's vocabulary; ignored"
             for name in header if name not in VOCABULARY]
    keep = [i for i, name in enumerate(header) if name in VOCABULARY]
    values = np.empty((lines, len(keep)))
    count, blank = 0, 0  # rows read; blank rows since the last one with a cell
    for row, cells in enumerate(reader, start=2):
        if not any(cell.strip() for cell in cells):
            blank += 1
            continue
        if blank:  # a blank line is only allowed at the end
            raise ValueError(f"{source}: row {row - blank}: blank row (only the end of the "
                             f"file may be blank)")
        if len(cells) != len(header):
            raise ValueError(f"{source}: row {row}: {len(cells)} cells, the header has "
                             f"{len(header)}")
        for j, k in enumerate(keep):
            text = cells[k].strip()
            try:
                number = float(text)
            except ValueError:
                number = None
            if number is None or not math.isfinite(number):
                what = "empty cell" if not text else f"{text!r} is not a finite number"
                raise ValueError(f"{source}: row {row}, column '{header[k]}': {what}")
            values[count, j] = number
        count += 1
    if count < MIN_SAMPLES:
        raise ValueError(f"{source}: needs at least {MIN_SAMPLES} data rows, got {count}")
    values = values[:count]
    time = values[:, 0]
    bad = np.flatnonzero(np.diff(time) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise ValueError(f"{source}: row {i + 2}, column 'time': must increase strictly, got "
                         f"{time[i]!r} after {time[i - 1]!r}")
    columns = {header[k]: np.ascontiguousarray(values[:, j]) for j, k in enumerate(keep) if j > 0}
    return np.ascontiguousarray(time), columns, notes


def load_run(run_dir: str | Path) -> MeasuredRun:
    """Read and check ``run_dir``/rig.toml and ``run_dir``/data.csv (ignored columns and
    unusual magnitudes warn; units that cannot be SI are refused: plausible.py)."""
    run_dir = Path(run_dir)
    if not run_dir.is_dir():
        raise FileNotFoundError(f"{run_dir}: no such directory (a measured run is a directory "
                                f"with rig.toml and data.csv)")
    rig = read_rig(run_dir / "rig.toml")
    time, columns, notes = read_data(run_dir / "data.csv")
    for note in notes:
        warnings.warn(note, stacklevel=2)
    source = str(run_dir / "rig.toml")
    for key in ("inputs", "outputs"):
        for name in rig["channels"][key]:
            if name not in columns:
                raise ValueError(f"{source}: [channels] key '{key}': data.csv has no column "
                                 f"{name!r}")
    kind, channel = rig["rig"]["kind"], rig["channels"]["outputs"][0]
    if kind == "horizontal_drive":
        if channel not in ("drive_force", "friction_force"):
            raise ValueError(f"{source}: [channels] key 'outputs': a horizontal_drive rig is "
                             f"compared on 'drive_force' or 'friction_force', got {channel!r}")
    elif channel not in ("vertical_displacement", "vertical_acceleration"):
        raise ValueError(f"{source}: [channels] key 'outputs': a vertical_response rig is "
                         f"compared on 'vertical_displacement' or 'vertical_acceleration', got "
                         f"{channel!r}")
    motion = [c for c in ("feed_position", "feed_velocity") if c in rig["channels"]["inputs"]]
    if not motion:
        raise ValueError(f"{source}: [channels] key 'inputs' must contain 'feed_position' or "
                         f"'feed_velocity' (the motion that drives the model)")
    run = MeasuredRun(path=run_dir, kind=kind, moving_mass=rig["rig"]["moving_mass"],
                      model=rig["model"], inputs=list(rig["channels"]["inputs"]),
                      outputs=list(rig["channels"]["outputs"]), time=time, columns=columns,
                      sections=rig["sections"], description=str(rig["rig"].get("description", "")),
                      warnings=notes, friction_sign=rig["channels"].get("friction_sign"),
                      friction_sign_stated="friction_sign" in rig["channels"])
    for note in plausible.check(run):  # units: refused where impossible, else warned about
        warnings.warn(note, stacklevel=2)
        run.warnings.append(note)
    return run
