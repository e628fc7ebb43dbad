"""Build the guideway FMUs with pythonfmu and document their variables.

Each FMU carries the modules of this package its component imports (found by
:mod:`modulefinder`) and the pythonfmu runtime it was built with, so it runs wherever the host
Python has numpy and scipy. A pythonfmu FMU puts its resources on the process-wide ``sys.path``,
so the copy is renamed ``guideway_fmu_<FMU>_<hash>`` (hash of the code it carries) and the slave
script ``<FMU>_<hash>.py``; the runtime sits inside that package (``_pythonfmu``, see
:mod:`guideway_fmu.components.runtime`). FMUs of different kinds or built from different code never import each
other's modules or runtime, and an FMU whose extracted folder was deleted by its host cannot break
the next one.
"""
from __future__ import annotations

import hashlib
import modulefinder
import os
import re
import shutil
import sys
import tempfile
import zipfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pythonfmu
from fmpy import read_model_description
from pythonfmu.builder import FmuBuilder

from ..components import registry, runtime
from ..fmi.archive import rewrite
from . import EDITIONS, error_patch, exit_patch, uri_patch
from .native import GENERATION_TOOL

LINUX = "binaries/linux64/"  # where an FMU keeps its Linux binary
RUNTIME = runtime.__name__  # shipped with every FMU, which imports it first (SLAVE_SCRIPT)
PACKAGE_DIR = Path(__file__).resolve().parents[1]
#: the modules that pack an FMU (the slave script, the runtime's move, the exit patch)
BUILDER = (Path(__file__).resolve(), Path(exit_patch.__file__).resolve())
SLAVE_SCRIPT = '''"""pythonfmu entry point of {name}."""
import sys
import traceback

try:
    from {package}.components.runtime import hold_namespace
    from {package}.{module} import {name}
except BaseException:
    print("FMU {name} cannot import its code; a C host needs the environment that "
          "`guideway-fmu host-env` prints:", file=sys.stderr)
    traceback.print_exc()
    raise
hold_namespace(globals())
'''


class _PackageFinder(modulefinder.ModuleFinder):
    """modulefinder that opens this package's modules only: an FMU ships the package's own
    files, and beside an installed package (site-packages) modulefinder would read every
    third-party package it imports, failing on namespace packages (mpl_toolkits)."""

    def find_module(self, name, path, parent=None):
        if parent is not None:
            inside = parent.__name__.split(".")[0] == PACKAGE_DIR.name
        elif path is not None:  # a package's own __init__
            inside = all(Path(p).is_relative_to(PACKAGE_DIR) for p in path)
        else:
            inside = name == PACKAGE_DIR.name
        if not inside:
            raise ImportError(name)  # recorded as not found, as outside the package's folder
        return super().find_module(name, path, parent)


def shipped_files(cls: type) -> list[Path]:
    """The package's source files an FMU of component class ``cls`` needs (its imports, closed)."""
    finder = _PackageFinder(path=[str(PACKAGE_DIR.parent)])
    for module in (cls.__module__, RUNTIME):
        finder.import_hook(module)
    files = {Path(m.__file__) for m in finder.modules.values() if m.__file__}
    return sorted(f for f in files if f.is_relative_to(PACKAGE_DIR))


def code_hash(files: list[Path], data: dict[str, Path] | None = None) -> str:
    """Short hash of the code an FMU ships (``files`` and the runtime's version), of the code
    that packs it (BUILDER) and of the ``data`` files it carries (name in its package -> file):
    FMUs of equal hashes are alike (the FMU cache, fmu_build.cache, keys them by it)."""
    digest = hashlib.sha256(pythonfmu.__version__.encode())
    for path in (*BUILDER, *files):
        digest.update(str(path.relative_to(PACKAGE_DIR)).encode())
        digest.update(path.read_bytes())
    for name, path in sorted((data or {}).items()):
        digest.update(name.encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:10]


def edition_of(name: str, edition: str) -> str:
    """The edition the FMU ``name`` is built in when ``edition`` is asked for: "native" for a
    component with a native edition (``native.COMPONENTS``), else "python". ValueError naming the
    editions for an unknown one."""
    if edition not in EDITIONS:
        raise ValueError(f"unknown FMU edition {edition!r}; known: {', '.join(EDITIONS)}")
    if edition == "native":
        from .native import COMPONENTS
        if name in COMPONENTS:
            return "native"
    return "python"


def fmu_hash(cls: type, edition: str = "python") -> str:
    """The code hash of the FMU of ``cls`` in ``edition`` (:func:`code_hash`; a native FMU's
    covers the translator and the C runtime too)."""
    if edition_of(cls.__name__, edition) == "native":
        from .native.build import native_hash
        return native_hash(cls)
    return code_hash(shipped_files(cls))


def build(out_dir: str | Path = "fmus", names: list[str] | None = None,
          edition: str = "python", cross: bool = False) -> list[Path]:
    """Build the named FMUs (default: all, the extensions included) in ``edition`` into
    ``out_dir`` and write its README.md (every FMU in the folder); ``cross``: native FMUs carry
    win64 and darwin64 binaries too (fmu_build/native/build.py)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    classes = [registry.component(n) for n in (registry.names() if names is None else names)]
    built = pack_edition([(cls, out_dir / f"{cls.__name__}.fmu") for cls in classes], edition,
                         cross)
    write_readme(out_dir, sorted(out_dir.glob("*.fmu")))
    return built


def pack_edition(slaves: list[tuple[type, Path]], edition: str, cross: bool = False) -> list[Path]:
    """Build an FMU of each (component class, destination file) in ``edition``
    (:func:`edition_of` decides per class), in the order given; ``cross`` as for :func:`build`."""
    native = {cls for cls, _ in slaves if edition_of(cls.__name__, edition) == "native"}
    python = iter(pack([(cls, dest) for cls, dest in slaves if cls not in native]))
    if not native:
        return [next(python) for _ in slaves]
    from .native.build import CROSS, PLATFORM, build_native
    platforms = tuple(dict.fromkeys([PLATFORM, *CROSS])) if cross else (PLATFORM,)
    with ThreadPoolExecutor(os.cpu_count()) as compilers:  # the C compiler runs apart
        built = {cls: compilers.submit(build_native, cls, dest, platforms)
                 for cls, dest in slaves if cls in native}
        return [built[cls].result() if cls in native else next(python) for cls, _ in slaves]


def pack(slaves: list[tuple[type, Path]], data: dict[str, Path] | None = None,
         handle_state: bool = True) -> list[Path]:
    """Build an FMU of each (slave class of this package, destination file): its package copy
    ``guideway_fmu_<class>_<hash>`` holds the modules the class imports and the ``data`` files
    (path inside the package -> file), the runtime moved in and the binary patched (module doc);
    ``handle_state``: whether it declares canGetAndSetFMUstate."""
    built, tags = [], []
    with tempfile.TemporaryDirectory(prefix="guideway_fmu_build_") as tmp:
        tmp = Path(tmp)
        sys.path.insert(0, str(tmp))
        try:
            for cls, dest in slaves:
                name = cls.__name__
                files = shipped_files(cls)
                tag = code_hash(files, data)
                tags.append(tag)
                _forget([tag])  # an FMU of this code loaded in this process: import the copy
                package = tmp / f"guideway_fmu_{name}_{tag}"
                copies = {path.relative_to(PACKAGE_DIR): path for path in files}
                copies.update({Path(entry): path for entry, path in (data or {}).items()})
                for entry, path in copies.items():
                    target = package / entry
                    target.parent.mkdir(parents=True, exist_ok=True)
                    shutil.copy2(path, target)
                script = tmp / f"{name}_{tag}.py"
                module = cls.__module__.split(".", 1)[1]
                script.write_text(SLAVE_SCRIPT.format(name=name, package=package.name,
                                                      module=module))
                fmu = FmuBuilder.build_FMU(script, dest=dest, project_files=[package],
                                           canGetAndSetFMUstate=handle_state)
                built.append(_finish(Path(fmu), package.name))
        finally:
            sys.path.remove(str(tmp))
            _forget(tags)
    return built


def _forget(tags: list[str]) -> None:
    """Drop the modules of the packages and slave scripts with these code hashes from
    ``sys.modules`` (an FMU instance keeps its own; its next instantiation imports them anew)."""
    for module in [m for m in sys.modules if any(tag in m for tag in tags)]:
        del sys.modules[module]


def _finish(fmu: Path, package: str) -> Path:
    """Move the pythonfmu runtime the builder put in ``resources/pythonfmu`` (shared by every
    pythonfmu FMU of a process) into the FMU's own package as ``_pythonfmu``, and fix the Linux
    binary: safe at exit (:mod:`.exit_patch`), fmi2Error for a Python exception
    (:mod:`.error_patch`), resources under any path (:mod:`.uri_patch`); returns ``fmu``."""
    shared, private = "resources/pythonfmu/", f"resources/{package}/_pythonfmu/"

    def finish(name: str, data: bytes) -> tuple[str, bytes]:
        if name.startswith(shared):
            name = private + name[len(shared):]
        name, data = exit_patch.patch_entry(name, data)
        return name, (uri_patch.patch(error_patch.patch(data)) if name.startswith(LINUX)
                      else data)

    return rewrite(fmu, fmu, finish)


def ensure(out_dir: str | Path, names: list[str] | None = None) -> Path:
    """Build the FMUs among ``names`` (default: all) that ``out_dir`` lacks (in the python
    edition) or holds built from other code than this package's (in the edition they have: their
    code hash differs, the package changed since they were built); an FMU of that name that this
    build did not make (a user's replacement) is left alone. Returns out_dir."""
    out_dir = Path(out_dir)
    wanted = registry.names() if names is None else list(dict.fromkeys(names))
    stale: dict[tuple[str, bool], list[str]] = {}
    for name in wanted:
        fmu = out_dir / f"{name}.fmu"
        found = built_edition(fmu)
        edition = found[0] if found else "python"
        if found is None or found[1] not in (fmu_hash(registry.component(name), edition), FOREIGN):
            stale.setdefault((edition, found is not None and cross_built(fmu)), []).append(name)
            if found:
                print(f"rebuilding {fmu} ({edition} edition): it was built from other code than "
                      "this package's", file=sys.stderr)
    for (edition, cross), names_ in stale.items():
        build(out_dir, names_, edition, cross)  # with the platforms it had
    return out_dir


def cross_built(fmu: Path) -> bool:
    """Whether the FMU carries binaries for another platform than this one's (``--cross``)."""
    from .native.build import CROSS, PLATFORM
    with zipfile.ZipFile(fmu) as archive:
        return any(name.startswith(f"binaries/{platform}/") for name in archive.namelist()
                   for platform in CROSS if platform != PLATFORM)


FOREIGN = "foreign"  # built_tag of an FMU this build did not make
NATIVE_TOOL = re.compile(rf'generationTool="{re.escape(GENERATION_TOOL)} ([0-9a-f]{{10}})"')


def built_edition(fmu: Path) -> tuple[str, str] | None:
    """(edition, code hash) of an FMU this build made: python (its slave script
    ``resources/<name>_<hash>.py``) or native (the hash in its modelDescription's
    generationTool); ("python", FOREIGN) for an FMU of another origin; None when the file is
    missing."""
    if not fmu.is_file():
        return None
    script = re.compile(rf"resources/{re.escape(fmu.stem)}_([0-9a-f]{{10}})\.py")
    try:
        with zipfile.ZipFile(fmu) as archive:
            tags = [m.group(1) for m in map(script.fullmatch, archive.namelist()) if m]
            if len(tags) == 1:
                return "python", tags[0]
            if not tags and "modelDescription.xml" in archive.namelist():
                native = NATIVE_TOOL.search(archive.read("modelDescription.xml").decode(
                    "utf-8", "replace"))
                if native:
                    return "native", native.group(1)
    except zipfile.BadZipFile:
        pass
    return "python", FOREIGN


def built_tag(fmu: Path) -> str | None:
    """The code hash an FMU of this build carries (:func:`built_edition`), None when the file is
    missing, FOREIGN when it is an FMU of another origin."""
    found = built_edition(fmu)
    return found and found[1]


def write_readme(out_dir: Path, fmus: list[Path]) -> Path:
    """Write ``out_dir/README.md``: every FMU's variables with causality, unit, start and meaning."""
    lines = ["# FMUs", "",
             "Generated by `guideway-fmu build` from the FMUs' modelDescription.xml; do not edit.",
             "All FMUs are FMI 2.0 co-simulation. An FMU of the python edition (pythonfmu) runs in",
             "the host's Python interpreter, which must provide numpy and scipy (a C host needs the",
             "environment `guideway-fmu host-env` prints); one of the native edition is compiled C",
             "and needs nothing but its binary for the host's platform.", ""]
    for path in fmus:
        md = read_model_description(str(path))
        found = built_edition(path)
        edition = ("another origin" if not found or found[1] == FOREIGN
                   else f"{found[0]} edition")
        lines += [f"## {md.modelName}", "", md.description or "", "", f"Built: {edition}.", "",
                  "| variable | causality | type | unit | start | description |",
                  "| --- | --- | --- | --- | --- | --- |"]
        order = {"parameter": 0, "input": 1, "output": 2}
        for v in sorted(md.modelVariables, key=lambda v: order.get(v.causality, 3)):
            lines.append(f"| `{v.name}` | {v.causality} | {v.type} | {v.unit or ''} | "
                         f"{'' if v.start is None else v.start} | {v.description or ''} |")
        lines.append("")
    readme = out_dir / "README.md"
    readme.write_text("\n".join(lines))
    return readme
