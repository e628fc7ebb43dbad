"""The shipped scenarios as TOML systems, how the project couples a carriage to its contact,
and the vertical rig that replays a record (:func:`vertical_rig`).

Written by the ``orchestration/make_*_scenarios.py`` scripts (edit those, not the files). They
name their FMUs by file name only, so every command finds them in one FMU folder (``--fmus``,
default the FMU cache's, built on demand: fmu_build.cache) from any working directory. Finding
a scenario imports nothing heavy: a wrong name is reported at once.
"""
from __future__ import annotations

from pathlib import Path

FOLDER = Path(__file__).resolve().parent


def coupling(carriage: str = "Carriage", contact: str = "Contact") -> list[tuple[str, str]]:
    """The connections (source, target) between a VerticalDynamics ``carriage`` and a roller
    ``contact`` in every vertical rig of the project: y and y_dot to the contact, its force
    back."""
    return [(f"{carriage}.y", f"{contact}.y"), (f"{carriage}.y_dot", f"{contact}.y_dot"),
            (f"{contact}.F_contact", f"{carriage}.F_contact")]


def couple_contact(builder, lubricated: bool, carriage: str = "Carriage", contact: str = "Contact"):
    """Couple a VerticalDynamics ``carriage`` and a roller ``contact`` in ``builder`` (a
    cosim.system.Builder): the connections of :func:`coupling`, and the stabilised coupling's
    tangent with the contact's force law (the contact's ``law_*`` outputs, roller_law.OpposedRows);
    a ``lubricated`` contact takes its inputs as they hold at the end of the step."""
    from ..physics.roller_guide.contact_model import OUTPUTS
    law = [name for name in OUTPUTS if name.startswith("law_")]
    for source, target in coupling(carriage, contact):
        builder.connect(source, target)
    builder.tangent(f"{contact}.F_contact", f"{contact}.y", f"{contact}.K_contact",
                    f"{carriage}.K_contact", f"{contact}.y_dot", f"{contact}.C_contact",
                    f"{carriage}.C_contact", model={n: f"{carriage}.{n}" for n in law},
                    settings={"interpolate_inputs": True} if lubricated else None)
    return builder


CONTACTS = ("ContactDryHertz", "ContactEHL")  # the vertical rig's contact FMUs, dry and lubricated
#: the vertical rig's drives (source, target): the replayed feed velocity to the contact, the
#: force table's force to the carriage
DRIVES = (("Feed.u", "Contact.u"), ("Load.F", "Carriage.F_ext"))


def vertical_rig_wiring() -> list[tuple[str, str]]:
    """The connections (source, target) :func:`vertical_rig` makes."""
    return [*DRIVES, *coupling()]


def vertical_rig(builder, fmus: Path, contact: str, replay: Path, load: Path, carriage: dict,
                 contact_parameters: dict):
    """Add the vertical rig to ``builder`` (a cosim.system.Builder) and return it: Feed
    (FeedKinematics replaying the table ``replay``) and Load (ForceTable, the ``load`` table's
    normal_force column) driving a Carriage (VerticalDynamics with the parameters ``carriage``)
    coupled (:func:`couple_contact`) to a Contact with ``contact_parameters``, the FMU
    ``contact`` (one of CONTACTS), all from the FMU folder ``fmus``. ValueError for another
    contact."""
    if contact not in CONTACTS:
        raise ValueError(f"vertical rig: contact {contact!r} is not one of {', '.join(CONTACTS)}")
    builder.component("Feed", fmus / "FeedKinematics.fmu", profile="replay",
                      table_file=str(replay))
    builder.component("Load", fmus / "ForceTable.fmu", table_file=str(load),
                      column="normal_force")
    builder.component("Carriage", fmus / "VerticalDynamics.fmu", **carriage)
    builder.component("Contact", fmus / f"{contact}.fmu", **contact_parameters)
    for source, target in DRIVES:
        builder.connect(source, target)
    return couple_contact(builder, lubricated=contact == "ContactEHL")


def names() -> list[str]:
    """The shipped scenarios' names (file stems), sorted."""
    return sorted(p.stem for p in FOLDER.glob("*.toml"))


def find(scenario: str | Path) -> Path:
    """The file of a scenario given by path or by a shipped scenario's name; ValueError naming
    the shipped ones when it is neither."""
    path = Path(scenario)
    if path.is_file():
        return path
    shipped = FOLDER / f"{path.name.removesuffix('.toml')}.toml"
    if path.parent == Path(".") and shipped.is_file():
        return shipped
    raise ValueError(f"scenario {str(scenario)!r} is neither a file nor a shipped scenario; "
                     f"shipped: {', '.join(names())}")


def is_shipped(path: Path) -> bool:
    """Whether ``path`` is one of the shipped scenario files."""
    return Path(path).resolve().parent == FOLDER


def fmu_folder(path: Path, fmus: str | Path | None, edition: str = "python") -> Path | None:
    """The FMU folder the scenario file ``path`` runs with: ``fmus`` when given, the FMU
    cache's set of ``edition`` (built where missing) for a shipped scenario, else None (the FMU
    paths in the file)."""
    if fmus is not None:
        return Path(fmus)
    if is_shipped(path):
        from ..fmu_build import cache
        return cache.folder(edition)
    return None
