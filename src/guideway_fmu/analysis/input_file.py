"""Reading the TOML input files of the analysis commands (carriage, feed unit): every error
names the file, the table and the key."""
from __future__ import annotations

import numpy as np

from ..cosim.system import read_toml as read  # noqa: F401 - input_file.read: the parsed TOML, a ValueError naming the file


def table(path, data: dict, name: str, required: bool = True) -> dict:
    """The table ``[name]`` (empty if absent and not ``required``)."""
    found = data.get(name, {} if not required else None)
    if not isinstance(found, dict):
        raise ValueError(f"{path}: " + (f"table [{name}] is missing" if found is None
                                        else f"[{name}] must be a table"))
    return found


def tables(path, data: dict, keys: dict[str, tuple[str, ...]], optional=()) -> dict[str, dict]:
    """Every table of ``keys`` (name -> known keys; those in ``optional`` may be absent), with
    unknown tables and keys refused."""
    found = {name: table(path, data, name, required=name not in optional) for name in keys}
    stray = [name for name in data if name not in keys]
    if stray:
        raise ValueError(f"{path}: unknown table(s) {', '.join(f'[{n}]' for n in stray)}; "
                         f"known: {', '.join(f'[{n}]' for n in keys)}")
    refuse_unknown(path, {name: (found[name], known) for name, known in keys.items()})
    return found


def refuse_unknown(path, tables: dict[str, tuple[dict, tuple[str, ...]]]) -> None:
    """ValueError listing every key not among the known ones: ``{name: (table, known keys)}``."""
    unknown = [f"[{name}] key {key!r}" for name, (found, keys) in tables.items()
               for key in found if key not in keys]
    if unknown:
        raise ValueError(f"{path}: unknown {', '.join(unknown)}")


def number(path, table_name: str, found: dict, key: str, positive: bool = False,
           default: float | None = None) -> float:
    """The finite number ``[table_name] key`` (> 0 if ``positive``); ``default`` if absent and
    given."""
    value = found.get(key)
    if value is None and default is not None:
        return float(default)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value):
        raise ValueError(f"{path}: [{table_name}] key {key!r}: "
                         + ("missing" if value is None else f"must be a number, got {value!r}"))
    if positive and not value > 0:
        raise ValueError(f"{path}: [{table_name}] key {key!r}: must be > 0, got {value!r}")
    return float(value)


def whole(path, table_name: str, found: dict, key: str) -> int:
    """The whole number ``[table_name] key`` >= 1."""
    value = found.get(key)
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ValueError(f"{path}: [{table_name}] key {key!r}: must be a whole number >= 1, "
                         f"got {value!r}")
    return value


def vector(path, table_name: str, found: dict, key: str, size: int, meaning: str,
           default=None) -> np.ndarray:
    """The list of ``size`` finite numbers ``[table_name] key``; ``meaning`` says what they are."""
    value = found.get(key, default)
    if (not isinstance(value, (list, tuple)) or len(value) != size
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                       and np.isfinite(v) for v in value)):
        raise ValueError(f"{path}: [{table_name}] key {key!r}: must be {meaning}, got {value!r}")
    return np.array(value, dtype=float)
