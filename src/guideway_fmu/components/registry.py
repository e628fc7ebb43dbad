"""Every FMU of the package, found by its component class.

A component module of this package defines one or more public :class:`GuidewaySlave` subclasses,
each one FMU named after its class. This registry finds them, so the build, ``fmus/README.md``
and the monolithic reference (``reference/``) know every FMU without a list: an FMU is added by
adding its module. ``role`` tells the roller guide's FMUs from those the discrepancy workflow
adds to a rig model.
"""
from __future__ import annotations

import functools
import importlib
import pkgutil

from .base import GuidewaySlave

#: modules of this package that define no FMU
_MACHINERY = {"base", "build", "registry", "units"}


@functools.cache
def components() -> dict[str, type[GuidewaySlave]]:
    """FMU model name -> component class, modules in alphabetical order."""
    found = {}
    for info in pkgutil.iter_modules(importlib.import_module(__package__).__path__):
        if info.name in _MACHINERY:
            continue
        module = importlib.import_module(f"{__package__}.{info.name}")
        for name, cls in vars(module).items():
            if (isinstance(cls, type) and issubclass(cls, GuidewaySlave) and not name.startswith("_")
                    and cls.__module__ == module.__name__):
                found[name] = cls
    return found


def names(role: str | None = None) -> list[str]:
    """Model names of the FMUs, of one ``role`` ("guideway" or "diagnosis") or all."""
    return [n for n, cls in components().items() if role is None or cls.role == role]


def component(name: str) -> type[GuidewaySlave]:
    """The component class of the FMU ``name``; ValueError listing the known ones otherwise."""
    try:
        return components()[name]
    except KeyError:
        raise ValueError(f"unknown FMU {name!r}; known FMUs: {', '.join(components())}") from None
