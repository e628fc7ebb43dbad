"""What the translator knows about a Python value while it writes C.

A value is either known when the C is written (:class:`Const`: numbers, strings, None,
functions, classes, modules) or known only at run time, as C variables and expressions: a
:class:`Scalar` is one C double, long or bool; a :class:`Tuple`, :class:`Obj` or :class:`Dict`
is a structure whose leaves are values (objects and dicts with constant keys are flattened into
their fields, so no C struct is declared for them); a :class:`Func` is a Python function bound
to its receiver and its enclosing frame, inlined where it is called; a :class:`Message` is a
string formatted at run time (error messages).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field


@dataclass
class Scalar:
    """A run-time number: ``code`` is a C expression of type ``ctype`` (double, long, bool);
    ``owner`` is the frame that declared it when it is a variable that frame may assign."""

    ctype: str
    code: str
    owner: object = None


@dataclass
class Const:
    """A value known when the C is written."""

    value: object


@dataclass
class Tuple:
    items: list


class Array(Tuple):
    """A one-dimensional numpy array of known length: arithmetic, comparisons and numpy's
    functions act element by element, broadcasting a number."""


class Listed(Tuple):
    """``array.tolist()``: numbers that a message writes as a list, [a, b]."""


@dataclass
class Obj:
    """An instance of ``cls`` with its attributes by name (its ``__dict__``)."""

    cls: type
    fields: dict = field(default_factory=dict)


@dataclass
class Dict:
    """A dict whose keys are constants."""

    items: dict


@dataclass
class Func:
    """A Python function to inline: bound to ``receiver`` (a method) and closing over ``frame``."""

    function: object
    receiver: object = None
    frame: object = None


@dataclass
class Choice:
    """One of two values of different structure (an optional object and None, two functions),
    chosen at run time by the C bool ``condition``; reading an attribute of an optional object
    reads it of the object (Python would raise on None)."""

    condition: str
    first: object
    second: object

    def map(self, function):
        sides = [s for s in (self.first, self.second) if not (isinstance(s, Const) and s.value is None)]
        if len(sides) == 1:
            return function(sides[0])
        return Choice(self.condition, function(self.first), function(self.second))


@dataclass
class Message:
    """A string formatted at run time: its parts are constant text or (value, spec, conversion)."""

    parts: list


@dataclass
class Text:
    """A String parameter's text, held in the C (``code``: its char buffer); the physics may
    split it into words and read numbers from them, nothing else."""

    code: str
    name: str


@dataclass
class Word:
    """Word ``index`` (a C expression) of a :class:`Text` split as str.split() splits."""

    text: Text
    index: str


@dataclass
class Words:
    """``text.split()``: ``count`` (a long Scalar) words, known at run time."""

    text: Text
    count: Scalar

    def word(self, k: str) -> Word:
        return Word(self.text, k)


@dataclass
class Vector:
    """A 1-D array of run-time length: ``length`` (a long Scalar) numbers of ``ctype`` ("double"
    or "bool") in the C array ``data`` (doubles; vectors.py)."""

    ctype: str
    data: str
    length: Scalar


@dataclass
class Span:
    """``start:stop`` with a bound known at run time only (each a Scalar or Const None)."""

    start: object
    stop: object


@dataclass
class Slot:
    """A numpy array a model holds, laid out when the first value is stored into it: struct
    fields of its length (an :class:`Array`) or of a run-time array (a :class:`Vector`).
    ``make(value)`` lays it out for ``value``."""

    example: object
    make: object


@dataclass
class Masked:
    """``array[mask]`` with a mask known at run time only: the items where it holds, of a length
    unknown when the C is written, so only a message may list them (comprehension, str.join)."""

    items: list
    mask: list  # per item: a bool Scalar, or a Const


@dataclass
class Joined:
    """A message part: the present ``items`` ((condition or None, text part)) joined by
    ``separator``, as str.join over a comprehension with run-time conditions."""

    separator: str
    items: list


def literal(value) -> str:
    """The C literal of a Python number or bool."""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, int):
        return f"{value}L"
    if math.isnan(value):
        return "NAN"
    if math.isinf(value):
        return "INFINITY" if value > 0 else "(-INFINITY)"
    text = repr(float(value))
    return f"({text})" if text.startswith("-") else text


def is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, complex)


def ctype_of(value) -> str:
    """The C type of a Python number or bool constant."""
    return "bool" if isinstance(value, bool) else "long" if isinstance(value, int) else "double"


def scalar(value) -> Scalar:
    """A Scalar of a Scalar, or of a number constant."""
    if isinstance(value, Scalar):
        return value
    if isinstance(value, Const) and is_number(value.value):
        return Scalar(ctype_of(value.value), literal(value.value))
    raise TypeError(f"expected a number, got {describe(value)}")


def leaves(value) -> list:
    """The leaves of a structured value, in a fixed order."""
    if isinstance(value, Tuple):
        return [leaf for item in value.items for leaf in leaves(item)]
    if isinstance(value, (Obj, Dict)):
        items = value.fields if isinstance(value, Obj) else value.items
        return [leaf for key in items for leaf in leaves(items[key])]
    return [value]


def same_shape(a, b) -> bool:
    """Whether ``a`` and ``b`` are structures of the same shape with C leaves of the same types
    and equal constants."""
    if type(a) is not type(b):
        return False
    if isinstance(a, Scalar):
        return a.ctype == b.ctype or {a.ctype, b.ctype} <= {"double", "long"}
    if isinstance(a, Const):
        return a.value is b.value or (type(a.value) is type(b.value) and a.value == b.value)
    if isinstance(a, Tuple):
        return len(a.items) == len(b.items) and all(map(same_shape, a.items, b.items))
    if isinstance(a, Obj):
        return a.cls is b.cls and a.fields.keys() == b.fields.keys() and all(
            same_shape(a.fields[k], b.fields[k]) for k in a.fields)
    if isinstance(a, Dict):
        return a.items.keys() == b.items.keys() and all(
            same_shape(a.items[k], b.items[k]) for k in a.items)
    return a == b


def describe(value) -> str:
    """A short description of a value for the translator's errors."""
    if isinstance(value, Const):
        return f"the constant {value.value!r}"[:80]
    if isinstance(value, Scalar):
        return f"a run-time {value.ctype}"
    if isinstance(value, Obj):
        return f"a {value.cls.__name__} object"
    return f"a {type(value).__name__.lower()}"
