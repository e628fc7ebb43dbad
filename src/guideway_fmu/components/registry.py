"""Every FMU of the package, found by its component class.

A component module in one of this package's system subpackages (``roller_guide``,
``ball_guides``, ``wear``, ``rigs``, ...) defines one or more public :class:`GuidewaySlave`
subclasses, each one FMU named after its class; the modules beside the subpackages are the
machinery and define none. This registry finds them, so the build, ``fmus/README.md``
and the monolithic reference (``reference/``) know every FMU without a list: an FMU is added by
adding its module. ``role`` tells the roller guide's FMUs from those the discrepancy workflow
adds to a rig model.
"""
from __future__ import annotations

import functools
import importlib
import pkgutil

from .base import GuidewaySlave


@functools.cache
def components() -> dict[str, type[GuidewaySlave]]:
    """FMU model name -> component class, by model name."""
    found = {}
    systems = [i.name for i in pkgutil.iter_modules(importlib.import_module(__package__).__path__)
               if i.ispkg]
    for system in sorted(systems):
        package = importlib.import_module(f"{__package__}.{system}")
        for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda i: i.name):
            found.update(_slaves(importlib.import_module(f"{package.__name__}.{info.name}")))
    return dict(sorted(found.items()))


def _slaves(module) -> dict[str, type[GuidewaySlave]]:
    """The public component classes defined in ``module``."""
    return {name: cls for name, cls in vars(module).items()
            if isinstance(cls, type) and issubclass(cls, GuidewaySlave) and not name.startswith("_")
            and cls.__module__ == module.__name__}


def names(role: str | None = None) -> list[str]:
    """Model names of the FMUs, of one ``role`` ("guideway" or "diagnosis") or all."""
    return [n for n, cls in components().items() if role is None or cls.role == role]


def component(name: str) -> type[GuidewaySlave]:
    """The component class of the FMU ``name``; ValueError listing the known ones otherwise."""
    try:
        return components()[name]
    except KeyError:
        raise ValueError(f"unknown FMU {name!r}; known FMUs: {', '.join(components())}") from None
