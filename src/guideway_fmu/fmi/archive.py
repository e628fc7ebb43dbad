"""FMU files as zip archives: rewriting one entry by entry (the one loop behind the build's
finishing, the exit patch and FMU copies with other start values), refusing entries that would
land outside the folder they are extracted to, and copying an FMU with other start values in its
modelDescription.xml."""
from __future__ import annotations

import re
import stat
import uuid
import zipfile
from pathlib import Path
from typing import Callable
from xml.etree import ElementTree as ET


DESCRIPTION = "modelDescription.xml"


def rewrite(source: str | Path, target: str | Path,
            transform: Callable[[str, bytes], tuple[str, bytes]]) -> Path:
    """Write ``target`` with every entry of the zip archive ``source`` passed through
    ``transform(name, data) -> (name, data)``; ``target`` may be ``source`` (replaced once the
    new archive is complete). Returns ``target``."""
    source, target = Path(source), Path(target)
    partial = target.with_name(target.name + ".partial")
    try:
        with zipfile.ZipFile(source) as src, \
                zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as dst:
            for info in src.infolist():
                dst.writestr(*transform(info.filename, src.read(info)))
    except BaseException:
        partial.unlink(missing_ok=True)  # nothing half-written left beside the target
        raise
    partial.replace(target)
    return target


def check_entries(fmu: str | Path) -> None:
    """Raise ValueError naming ``fmu`` and the entry if an entry's name is absolute (a leading
    slash or backslash, a drive letter) or has a ``..`` component, or if the entry is a symbolic
    link or another special file: what extracting or repackaging it could write outside its folder."""
    with zipfile.ZipFile(fmu) as zf:
        for info in zf.infolist():
            why = _unsafe(info)
            if why:
                raise ValueError(f"{fmu}: archive entry {info.filename!r} {why}; the FMU is refused")


def _unsafe(info: zipfile.ZipInfo) -> str | None:
    name = info.filename
    if name.startswith(("/", "\\")) or re.match(r"[A-Za-z]:", name):
        return "is an absolute path"
    if ".." in re.split(r"[/\\]", name):
        return "has a '..' path component"
    mode = info.external_attr >> 16  # Unix st_mode where the archiver stored one, else 0
    if stat.S_ISLNK(mode):
        return "is a symbolic link"
    if stat.S_IFMT(mode) not in (0, stat.S_IFREG, stat.S_IFDIR):
        return "is a special file (neither a file nor a folder)"
    return None


def xml_value(kind: str, value) -> str:
    """``value`` as the XML text of an FMI or SSP value of type ``kind`` (Real, Integer,
    Enumeration, Boolean, String)."""
    if kind == "Boolean":
        return "true" if value else "false"
    return repr(float(value)) if kind == "Real" else str(value)


def with_start_values(fmu: str | Path, out: str | Path, values: dict) -> Path:
    """Copy ``fmu`` to ``out`` with the start attribute of each variable in ``values`` (name ->
    value) set to that value in its modelDescription.xml, and a guid of its own (derived from
    the original's and the values: hosts such as libcosim keep one extracted FMU per guid, so
    copies sharing it would all run with the first one's start values); every other entry is
    copied byte for byte. Raises ValueError naming the FMU and the variable if it has no such
    variable. An FMU that checks the guid at instantiation (compiled from C, say) no longer
    instantiates: one of the reasons it cannot carry other start values."""
    fmu, out = Path(fmu), Path(out)
    check_entries(fmu)
    return rewrite(fmu, out, lambda name, data: (
        name, _set_starts(fmu, data, values) if name == DESCRIPTION else data))


def _set_starts(fmu: Path, xml: bytes, values: dict) -> bytes:
    root = ET.fromstring(xml, ET.XMLParser(target=ET.TreeBuilder(insert_comments=True)))
    variables = {v.get("name"): v for v in root.iter("ScalarVariable")}
    for name, value in values.items():
        if name not in variables:
            raise ValueError(f"{fmu}: {DESCRIPTION} has no variable {name!r} to set the start of")
        typed = variables[name][0]
        typed.set("start", xml_value(typed.tag, value))
    starts = "\n".join(f"{name}={xml_value(variables[name][0].tag, values[name])}" for name in sorted(values))
    root.set("guid", str(uuid.uuid5(uuid.NAMESPACE_URL, f"{root.get('guid')}\n{starts}")))
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True)
