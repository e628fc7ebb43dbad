"""Builtins, ``math`` and ``numpy`` functions of scalars, as C.

A call whose arguments are all known is evaluated by the Python function itself when the C is
written (so constants fold exactly as Python computes them); otherwise it becomes the C99
function of the same meaning. NaN follows the Python function: ``np.maximum`` passes a NaN on,
the builtin ``max`` keeps its first argument unless another compares greater.
"""
from __future__ import annotations

import ast
import builtins
import math

import numpy as np
import scipy.linalg
import scipy.special
from scipy.optimize import RootResults, brentq

from .source import MissingAttribute
from .translate import from_python
from .values import (
    Array,
    Const,
    Dict,
    Listed,
    Masked,
    Obj,
    Scalar,
    Text,
    Tuple,
    Vector,
    Word,
    Words,
    describe,
    is_number,
)

# Python function -> C function of one double
_UNARY = {
    math.sqrt: "sqrt", math.exp: "exp", math.log: "log", math.sin: "sin", math.cos: "cos",
    math.tan: "tan", math.atan: "atan", math.asin: "asin", math.acos: "acos", math.tanh: "tanh",
    math.sinh: "sinh", math.cosh: "cosh", math.expm1: "expm1", math.log1p: "log1p",
    math.log10: "log10", math.fabs: "fabs",
    np.sqrt: "sqrt", np.exp: "exp", np.log: "log", np.sin: "sin", np.cos: "cos", np.tan: "tan",
    np.arctan: "atan", np.tanh: "tanh", np.expm1: "expm1", np.log1p: "log1p", np.abs: "fabs",
    np.sign: "gw_sign", np.log10: "log10", np.cbrt: "cbrt", np.arcsin: "asin",
    np.arccos: "acos", np.sinh: "sinh", np.cosh: "cosh", np.floor: "floor", np.ceil: "ceil",
    np.degrees: "gw_degrees", np.radians: "gw_radians", math.degrees: "gw_degrees",
    math.radians: "gw_radians", scipy.special.ellipk: "gw_ellipk", scipy.special.ellipe: "gw_ellipe",
}
# Python function -> C function of two doubles
_BINARY = {math.atan2: "atan2", math.hypot: "hypot", math.pow: "pow", math.copysign: "copysign",
           np.arctan2: "atan2", np.hypot: "hypot", np.power: "pow",
           np.maximum: "gw_npmax", np.minimum: "gw_npmin", np.fmax: "fmax", np.fmin: "fmin",
           np.mod: "gw_mod"}
# Python predicate -> C predicate of one double
_TESTS = {math.isfinite: "isfinite", math.isnan: "isnan", math.isinf: "isinf",
          np.isfinite: "isfinite", np.isnan: "isnan", np.isinf: "isinf"}


def _known(function, args, kwargs):
    return all(isinstance(a, Const) for a in [*args, *kwargs.values()])


def _fold(function, args, kwargs):
    return from_python(function(*[a.value for a in args], **{k: v.value for k, v in kwargs.items()}))


def _numeric(function, make):
    """The handler of ``function``: folded when its arguments are known, else ``make``."""
    def handler(tr, args, kwargs):
        if _known(function, args, kwargs):
            return _fold(function, args, kwargs)
        if function in _ELEMENTWISE and any(isinstance(a, (Array, Vector)) for a in args):
            return tr.elementwise(lambda *row: handler(tr, list(row), kwargs), *args)
        return make(tr, [tr.scalar(a) if not isinstance(a, (Tuple, Dict)) else a for a in args],
                    kwargs)
    return handler


def _unary(c_name):
    return lambda tr, args, kwargs: Scalar("double", f"{c_name}((double){args[0].code})")


#: math's functions that report a finite argument's infinite result as OverflowError (CPython's
#: mathmodule.c: the others report it, and a NaN from a number, as ValueError)
_CAN_OVERFLOW = {math.exp, math.expm1, math.sinh, math.cosh}


def _math_unary(function, c_name):
    """A function of the math module: C's, failing where Python's math fails (a NaN result of a
    number: ValueError, math domain error; an infinite one of a finite number: OverflowError,
    math range error, or ValueError for those that cannot overflow)."""
    def make(tr, args, kwargs):
        x = tr.variable(tr.scalar(_to_double(tr, args, kwargs)), tr.frame)
        value = tr.variable(Scalar("double", f"{c_name}({x.code})"), tr.frame)
        tr.emit(f"if (isnan({value.code}) && !isnan({x.code})) {{")
        tr.fail([Const("math domain error")], ValueError)
        tr.emit("}")
        tr.emit(f"if (isinf({value.code}) && isfinite({x.code})) {{")
        overflow = function in _CAN_OVERFLOW
        tr.fail([Const("math range error" if overflow else "math domain error")],
                OverflowError if overflow else ValueError)
        tr.emit("}")
        return value
    return make


def _binary(c_name):
    return lambda tr, args, kwargs: Scalar(
        "double", f"{c_name}((double){args[0].code}, (double){args[1].code})")


def _test(c_name):
    return lambda tr, args, kwargs: Scalar("bool", f"{c_name}((double){args[0].code})")


def _rounding(c_name):
    """math.floor and math.ceil: a whole number, refused as int() refuses."""
    return lambda tr, args, kwargs: _int(tr, [Scalar("double", f"{c_name}({args[0].code})")], {})


def _to_double(tr, args, kwargs):
    return Scalar("double", f"((double){args[0].code})")


def _int(tr, args, kwargs):
    """int(x): a whole number; a float's infinity (OverflowError) and NaN (ValueError) refused
    in Python's words, beyond C's long a RuntimeError."""
    a = args[0]
    if a.ctype != "double":
        return a if a.ctype == "long" else Scalar("long", f"((long){a.code})")
    x = tr.variable(a, tr.frame)
    tr.emit(f"if (isinf({x.code})) {{")
    tr.fail([Const("cannot convert float infinity to integer")], OverflowError)
    tr.emit(f"}} else if (isnan({x.code})) {{")
    tr.fail([Const("cannot convert float NaN to integer")], ValueError)
    tr.emit(f"}} else if (fabs({x.code}) >= 9.2e18) {{")
    tr.fail([Const("an integer beyond the native edition's 64 bits: "), x], RuntimeError)
    tr.emit("}")
    return Scalar("long", f"((long)trunc({x.code}))")


def _abs(tr, args, kwargs):
    a = args[0]
    return Scalar("long", f"labs({a.code})") if a.ctype == "long" else \
        Scalar("double", f"fabs({a.code})")


def _extreme(c_double, c_long):
    def make(tr, args, kwargs):
        items = tr.iterate(args[0]) if len(args) == 1 else args
        items = [tr.scalar(i) for i in items]
        result = items[0]
        for item in items[1:]:
            both_long = result.ctype == item.ctype == "long"
            result = Scalar("long" if both_long else "double",
                            f"{c_long if both_long else c_double}({result.code}, {item.code})")
        return result
    return make


def _np_sum(tr, args, kwargs):
    """np.sum of a 1-D array (numpy's pairwise summation, gw_np_sum), of a tuple as an array."""
    value = args[0]
    if kwargs.get("axis", Const(None)).value not in (None, 0) or len(args) > 1:
        raise tr.error("np.sum is translated over the one axis of a 1-D array only")
    if isinstance(value, Tuple):
        if all(isinstance(i, Const) for i in value.items):
            return from_python(np.sum([i.value for i in value.items]))
        value = tr.fixed_to_vector(_asarray(tr, [value], {}))
    if isinstance(value, Array):
        value = tr.fixed_to_vector(value)
    if not isinstance(value, Vector):
        return _asarray(tr, [value], {})  # np.sum of a number: itself
    return Scalar("double", f"gw_np_sum({value.data}, {value.length.code})")


def _sum_method(tr, array, args, kwargs):
    return _np_sum(tr, [array, *args], kwargs)


def _reshape_method(tr, array, args, kwargs):
    """reshape of a 1-D array to (-1,) or (n,): itself."""
    shape = args[0] if len(args) == 1 else Tuple(list(args))
    shape = from_python(shape.value) if isinstance(shape, Const) else shape
    if kwargs or type(shape) is not Tuple or len(shape.items) != 1:
        raise tr.error("reshape is translated to one dimension only")
    return array


def _np_extreme(is_max: bool):
    """np.max or np.min of a 1-D array over its one axis: a NaN passes on, as numpy's does;
    an empty array is refused in numpy's words."""
    c_name = "gw_npmax" if is_max else "gw_npmin"

    def handler(tr, args, kwargs):
        value = args[0]
        if len(args) > 1 or kwargs.get("axis", Const(None)).value not in (None, 0):
            raise tr.error("np.max and np.min are translated over the one axis of a 1-D array only")
        if isinstance(value, (Tuple, Const)):
            value = _asarray(tr, [value], {})
        if isinstance(value, Array):
            items = [tr.scalar(i) for i in value.items]
            result = items[0]
            for item in items[1:]:
                result = Scalar("double", f"{c_name}({result.code}, {item.code})")
            return result
        if not isinstance(value, Vector):
            return value
        tr.emit(f"if ({value.length.code} < 1) {{")
        tr.fail([Const("zero-size array to reduction operation "
                       f"{'maximum' if is_max else 'minimum'} which has no identity")], ValueError)
        tr.emit("}")
        return tr.fold(value.length, "extreme", f"{value.data}[0]",
                       lambda k, it: f"{c_name}({it}, {value.data}[{k}])")
    return handler


def _tolist_method(tr, array, args, kwargs):
    if isinstance(array, Vector):
        raise tr.error("tolist of a run-time array is not translated")
    return Listed(list(array.items))


#: the methods of numpy arrays the translator knows, by name
ARRAY_METHODS = {"sum": _sum_method, "reshape": _reshape_method, "tolist": _tolist_method,
                 "max": lambda tr, array, args, kwargs: _np_extreme(True)(tr, [array, *args], kwargs),
                 "min": lambda tr, array, args, kwargs: _np_extreme(False)(tr, [array, *args], kwargs)}


def _sum(tr, args, kwargs):
    items = tr.iterate(args[0])
    start = args[1] if len(args) > 1 else Const(0)
    total = start
    for item in items:
        total = tr.binary(_ADD, total, item)
    return total


def _asarray(tr, args, kwargs):
    value = args[0]
    if isinstance(value, Vector):
        return value
    if isinstance(value, Tuple):
        return Array([_asarray(tr, [item], {}) for item in value.items])
    if isinstance(value, Const) and is_number(value.value):
        return Const(float(value.value))
    if isinstance(value, Scalar):
        return Scalar("double", f"((double){value.code})") if value.ctype != "double" else value
    raise tr.error(f"an array of {describe(value)} is not translated (scalars only)")


def _reduce_all(is_all):
    def handler(tr, args, kwargs):
        value = args[0]
        if isinstance(value, Vector):
            return tr.vector_reduce(value, is_all)
        items = tr.iterate(value) if isinstance(value, (Tuple, Dict)) else [value]
        terms = [tr.truth(i) for i in items]
        if any(isinstance(t, Const) and t.value != is_all for t in terms):
            return Const(not is_all)
        codes = [t.code for t in terms if isinstance(t, Scalar)]
        if not codes:
            return Const(is_all)
        return Scalar("bool", "(" + (" && " if is_all else " || ").join(codes) + ")")
    return handler


def _isinstance(tr, args, kwargs):
    value, classes = args
    classes = tuple(c.value for c in tr.iterate(classes)) if isinstance(classes, Tuple) else \
        classes.value
    return Const(any(issubclass(t, classes) for t in _types(value)))


def _types(value):
    """The Python types a value may have."""
    if isinstance(value, Const):
        return (type(value.value),)
    if isinstance(value, Scalar):
        return {"double": (float, np.float64), "long": (int,), "bool": (bool,)}[value.ctype]
    if isinstance(value, Obj):
        return (value.cls,)
    return (tuple,) if isinstance(value, Tuple) else (dict,)


def _type(tr, args, kwargs):
    types_ = _types(args[0])
    return Const(types_[0])


def _getattr(tr, args, kwargs):
    name = args[1]
    if not isinstance(name, Const):
        raise tr.error("getattr needs a name known when the C is written")
    try:
        return tr.attribute(args[0], name.value)
    except MissingAttribute:  # a construct not translated stays an error
        if len(args) > 2:
            return args[2]
        raise


def _len(tr, args, kwargs):
    value = args[0]
    if isinstance(value, Vector):
        return value.length
    if isinstance(value, (Tuple, Dict)):
        return Const(len(value.items))
    if isinstance(value, Const):
        return Const(len(value.value))
    raise tr.error(f"len of {describe(value)}")


def _zip(tr, args, kwargs):
    return Tuple([Tuple(list(items)) for items in zip(*[tr.iterate(a) for a in args])])


def _enumerate(tr, args, kwargs):
    return Tuple([Tuple([Const(i), item]) for i, item in enumerate(tr.iterate(args[0]))])


def _range(tr, args, kwargs):
    if not _known(range, args, kwargs):
        raise tr.error("range with a run-time bound is translated only as a for loop's sequence")
    return Const(range(*[a.value for a in args]))


def _shape(tr, value) -> tuple:
    """numpy's shape of a number (()) or a 1-D array ((n,))."""
    if isinstance(value, Tuple):
        return (len(value.items),)
    if isinstance(value, Scalar) or (isinstance(value, Const) and is_number(value.value)):
        return ()
    raise tr.error(f"the shape of {describe(value)} is not translated")


def _broadcast_to(tr, args, kwargs):
    value, shape = args
    if not (isinstance(shape, Const) and isinstance(shape.value, tuple) and len(shape.value) <= 1):
        raise tr.error("broadcast_to needs a 1-D shape known when the C is written")
    if not shape.value:
        return value
    return tr.elementwise(lambda v, _: v, value, Array([Const(0)] * shape.value[0]))


def _broadcast_arrays(tr, args, kwargs):
    shapes = {_shape(tr, a) for a in args} - {()}
    if len(shapes) > 1:
        raise tr.error(f"arrays of shapes {sorted(shapes)} do not broadcast")
    shape = shapes.pop() if shapes else ()
    return Tuple([_broadcast_to(tr, [a, Const(shape)], {}) for a in args])


def _stack(tr, args, kwargs):
    items = tr.iterate(args[0])
    if kwargs.get("axis", Const(0)).value != 0 or any(_shape(tr, i) for i in items):
        raise tr.error("np.stack is translated for numbers along axis 0 only")
    return Array(list(items))


def _like(fill):
    """np.zeros_like and np.ones_like (``fill``), or np.full_like (fill None: the argument)."""
    def handler(tr, args, kwargs):
        value = Const(fill) if fill is not None else args[1]
        if isinstance(args[0], Vector):
            return tr.vector_map(lambda _: value, args[0])
        shape = _shape(tr, args[0])
        return Array([value] * shape[0]) if shape else value
    return handler


def _divide(tr, args, kwargs):
    """np.divide: IEEE division (no exception at zero); with ``where``, ``out`` elsewhere."""
    a, b = args
    if any(isinstance(v, (Array, Vector)) for v in (a, b, kwargs.get("where"), kwargs.get("out"))):
        keys = [k for k in ("where", "out") if k in kwargs]
        return tr.elementwise(lambda x, y, *rest: _divide(tr, [x, y], dict(zip(keys, rest))),
                              a, b, *(kwargs[k] for k in keys))
    a, b = tr.scalar(a), tr.scalar(b)
    quotient = Scalar("double", f"((double){a.code} / (double){b.code})")
    if "where" not in kwargs:
        return quotient
    return _where(tr, [kwargs["where"], quotient, kwargs.get("out", Const(0.0))], {})


def _str(tr, args, kwargs):
    if isinstance(args[0], Text):
        return args[0]
    if _known(str, args, kwargs):
        return _fold(str, args, kwargs)
    raise tr.error(f"str of {describe(args[0])} is not translated")


def split(tr, text: Text, args, kwargs):
    """``text.split()``: its words, counted at run time."""
    if args or kwargs:
        raise tr.error("str.split is translated without arguments only")
    count = tr.out.declare("long", "words")
    tr.emit(f"{count} = gw_words({text.code});")
    return Words(text, Scalar("long", count))


def _float_of_word(tr, word: Word) -> Scalar:
    """float(word), refused as Python refuses it."""
    value, failed = tr.out.declare("double", "number"), tr.out.declare("int", "refused")
    tr.emit(f"{failed} = gw_word_double({word.text.code}, {word.index}, &{value});")
    tr.emit(f"if ({failed}) {{")
    tr.fail([Const("could not convert string to float: "), (word, "", "r")], ValueError)
    tr.emit("}")
    return Scalar("double", value)


def _float(tr, args, kwargs):
    if isinstance(args[0], Word):
        return _float_of_word(tr, args[0])
    return _numeric(float, _to_double)(tr, args, kwargs)


def _linspace(tr, args, kwargs):
    """np.linspace(start, stop, num) (numpy's arithmetic: Vectors.linspace); with num known, an
    array of that length."""
    start, stop, num = (list(args) + [kwargs.get("num")])[:3]
    if isinstance(num, Scalar) and num.ctype == "long":
        return tr.linspace(tr.scalar(start), tr.scalar(stop), num)
    if not (isinstance(num, Const) and isinstance(num.value, (int, np.integer)) and num.value >= 0):
        raise tr.error("np.linspace is translated for a whole number of nodes only")
    nodes = tr.linspace(tr.scalar(start), tr.scalar(stop), Scalar("long", f"{int(num.value)}L"))
    return Array([tr.variable(tr.element(nodes, str(k)), tr.frame) for k in range(num.value)])


def _interp(tr, args, kwargs):
    x, xp, fp = args
    if isinstance(x, Vector):
        return tr.vector_map(lambda v: _interp(tr, [v, xp, fp], {}), x)
    if isinstance(xp, Vector) or isinstance(fp, Vector):
        xp, fp = (tr.fixed_to_vector(v) if isinstance(v, Array) else v for v in (xp, fp))
        tr.emit(f"if ({xp.length.code} != {fp.length.code} || {xp.length.code} < 1) {{")
        tr.fail([Const("fp and xp are not of the same length.")], ValueError)
        tr.emit("}")
        return Scalar("double", f"gw_interp({tr.scalar(x).code}, {xp.length.code}, {xp.data}, "
                                f"{fp.data})")
    if kwargs or not (isinstance(xp, Array) and isinstance(fp, Array)
                      and len(xp.items) == len(fp.items)):
        raise tr.error("np.interp is translated for node and value arrays of one length")
    if isinstance(x, Array):
        return tr.elementwise(lambda v: _interp(tr, [v, xp, fp], {}), x)
    n = len(xp.items)
    tables = []
    for values in (xp, fp):
        name = tr.out.declare("double", "table", n)
        for k, v in enumerate(values.items):
            tr.emit(f"{name}[{k}] = {tr.scalar(v).code};")
        tables.append(name)
    return Scalar("double", f"gw_interp({tr.scalar(x).code}, {n}L, {tables[0]}, {tables[1]})")


def _diff(tr, args, kwargs):
    value = args[0]
    if isinstance(value, Vector) and not kwargs:
        return tr.diff(value)
    if kwargs or not isinstance(value, Array):
        raise tr.error("np.diff is translated for a 1-D array only")
    return Array([tr.binary(ast.Sub(), b, a) for a, b in zip(value.items, value.items[1:])])


def _arange(tr, args, kwargs):
    """np.arange([start,] stop) of whole numbers known at run time only: a run-time array start,
    start + 1, ... stop - 1."""
    whole = all(isinstance(a, Const) and isinstance(a.value, (int, np.integer)) or
                isinstance(a, Scalar) and a.ctype == "long" for a in args)
    if not 1 <= len(args) <= 2 or kwargs or not whole or _known(np.arange, args, kwargs):
        if _known(np.arange, args, kwargs):
            return _fold(np.arange, args, kwargs)
        raise tr.error("np.arange is translated for whole-number bounds without a step only")
    start, stop = (tr.scalar(a) for a in ([Const(0), *args] if len(args) == 1 else args))
    count = f"({stop.code} - {start.code})"
    out = tr.new_vector("double", f"({count} > 0 ? {count} : 0)")
    with tr.counting(out.length) as k:
        tr.emit(f"{out.data}[{k}] = (double)({start.code} + {k});")
    return out


def _ravel(tr, args, kwargs):
    value = args[0]
    if isinstance(value, (Array, Masked)):
        return value
    if isinstance(value, Tuple):
        return _asarray(tr, [value], {})
    return Array([value])


def _repeat(whole: bool):
    """np.tile (``whole``) or np.repeat of a 1-D array by a count."""
    function = np.tile if whole else np.repeat

    def handler(tr, args, kwargs):
        if _known(function, args, kwargs):
            return _fold(function, args, kwargs)
        value, count = args
        if kwargs or not (isinstance(count, (Const, Scalar)) and _shape(tr, count) == ()):
            raise tr.error(f"np.{function.__name__} is translated for a 1-D array and a count only")
        value = _asarray(tr, [value], {})
        if isinstance(value, Array) and isinstance(count, Const):
            items = value.items * count.value if whole else \
                [item for item in value.items for _ in range(count.value)]
            return Array(items)
        if isinstance(value, Array):
            value = tr.fixed_to_vector(value)
        if not isinstance(value, Vector):
            raise tr.error(f"np.{function.__name__} of {describe(value)} is not translated")
        return tr.repeated(value, tr.scalar(count), whole)
    return handler


def _solve(tr, args, kwargs):
    """np.linalg.solve(a, b) of an n x n matrix and an n-vector known in size (gw_solve);
    LinAlgError("Singular matrix") as numpy raises it."""
    b = _asarray(tr, [args[1]], {})
    if kwargs or not isinstance(b, Array) or not b.items:
        raise tr.error("np.linalg.solve is translated for an n-vector of known size only")
    n = len(b.items)
    matrix, rhs = _matrix(tr, args[0], n, "np.linalg.solve"), tr.out.declare("double", "rhs", n)
    for i, item in enumerate(b.items):
        tr.emit(f"{rhs}[{i}] = {tr.scalar(item).code};")
    tr.emit(f"if (gw_solve({n}L, {matrix}, {rhs})) {{")
    tr.fail([Const("Singular matrix")], np.linalg.LinAlgError)
    tr.emit("}")
    return Array([tr.variable(Scalar("double", f"{rhs}[{k}]"), tr.frame) for k in range(n)])


def _concatenate(tr, args, kwargs):
    """np.concatenate of 1-D arrays along their one axis."""
    if _known(np.concatenate, args, kwargs):
        return _fold(np.concatenate, args, kwargs)
    if len(args) != 1 or kwargs.get("axis", Const(0)).value != 0:
        raise tr.error("np.concatenate is translated for 1-D arrays along axis 0 only")
    parts = [_asarray(tr, [item], {}) for item in tr.iterate(args[0])]
    if all(isinstance(p, Array) for p in parts):
        return Array([item for p in parts for item in p.items])
    if not all(isinstance(p, (Array, Vector)) for p in parts):
        raise tr.error("np.concatenate is translated for 1-D arrays only")
    return tr.concatenated([tr.fixed_to_vector(p) if isinstance(p, Array) else p for p in parts])


def _diag(tr, args, kwargs):
    """np.diag of arrays of known size: a square matrix of a 1-D array, the diagonal of one."""
    if _known(np.diag, args, kwargs):
        return _fold(np.diag, args, kwargs)
    value = _asarray(tr, [args[0]], {})
    if len(args) > 1 or kwargs or not isinstance(value, Array):
        raise tr.error("np.diag is translated for arrays of known size, k = 0, only")
    if all(isinstance(row, Array) for row in value.items):
        return Array([row.items[k] for k, row in enumerate(value.items)])
    n = len(value.items)
    return Array([Array([value.items[i] if i == j else Const(0.0) for j in range(n)])
                  for i in range(n)])


def _outer(tr, args, kwargs):
    a, b = (_asarray(tr, [v], {}) for v in args)
    if kwargs or not (isinstance(a, Array) and isinstance(b, Array)):
        raise tr.error("np.outer is translated for 1-D arrays of known size only")
    return Array([Array([tr.binary(ast.Mult(), x, y) for y in b.items]) for x in a.items])


def _trace(tr, args, kwargs):
    value = _asarray(tr, [args[0]], {})
    if kwargs or len(args) > 1 or not isinstance(value, Array):
        raise tr.error("np.trace is translated for a square matrix of known size only")
    return _sum(tr, [Tuple([row.items[k] for k, row in enumerate(value.items)])], {})


def _matrix(tr, value, n: int, what: str) -> str:
    """A C array of the n x n ``value`` of known size (row-major)."""
    value = _asarray(tr, [value], {})
    if not (isinstance(value, Array) and len(value.items) == n and all(
            isinstance(row, Array) and len(row.items) == n for row in value.items)):
        raise tr.error(f"{what} is translated for n x n matrices of known size only")
    name = tr.out.declare("double", "matrix", n * n)
    for i, row in enumerate(value.items):
        for j, item in enumerate(row.items):
            tr.emit(f"{name}[{i * n + j}] = {tr.scalar(item).code};")
    return name


def _eigh(tr, args, kwargs):
    """scipy.linalg.eigh(a, b, eigvals_only=True) of symmetric matrices of known size
    (gw_eigvalsh): the eigenvalues in ascending order; LinAlgError where b is not positive
    definite."""
    given = {**dict(zip(("a", "b"), args)), **kwargs}
    if set(given) - {"a", "b", "eigvals_only"} or not given.get("eigvals_only", Const(False)).value:
        raise tr.error("scipy.linalg.eigh is translated with eigvals_only=True only")
    a = _asarray(tr, [given["a"]], {})
    n = len(a.items) if isinstance(a, Array) else 0
    matrix = _matrix(tr, a, n, "scipy.linalg.eigh")
    other = _matrix(tr, given["b"], n, "scipy.linalg.eigh") if "b" in given else "NULL"
    values = tr.out.declare("double", "eigenvalues", n)
    tr.emit(f"if (gw_eigvalsh({n}L, {matrix}, {other}, {values})) {{")
    tr.fail([Const("the matrix b is not positive definite")], np.linalg.LinAlgError)
    tr.emit("}")
    return Array([tr.variable(Scalar("double", f"{values}[{k}]"), tr.frame) for k in range(n)])


def _dot(tr, args, kwargs):
    """np.dot of two 1-D arrays: the sum of their products (in index order; numpy's BLAS may
    add in another order, so the last bits may differ)."""
    if _known(np.dot, args, kwargs):
        return _fold(np.dot, args, kwargs)
    a, b = (_asarray(tr, [v], {}) for v in args)
    if kwargs or not all(isinstance(v, (Array, Vector)) for v in (a, b)):
        raise tr.error("np.dot is translated for two 1-D arrays only")
    if isinstance(a, Array) and isinstance(b, Array):
        if len(a.items) != len(b.items):
            raise tr.error(f"np.dot of arrays of {len(a.items)} and {len(b.items)} numbers")
        return _sum(tr, [Tuple([tr.binary(ast.Mult(), x, y) for x, y in zip(a.items, b.items)])], {})
    a, b = (tr.fixed_to_vector(v) if isinstance(v, Array) else v for v in (a, b))
    tr.emit(f"if ({a.length.code} != {b.length.code}) {{")
    tr.fail([Const("shapes ("), a.length, Const(",) and ("), b.length,
             Const(",) not aligned")], ValueError)
    tr.emit("}")
    return tr.fold(a.length, "dot", "0.0", lambda k, it: f"{it} + {a.data}[{k}] * {b.data}[{k}]")


def _folded(function):
    """A numpy constructor of a shape known when the C is written (np.zeros(5), np.eye(5))."""
    def handler(tr, args, kwargs):
        if not _known(function, args, kwargs):
            raise tr.error(f"np.{function.__name__} is translated for a shape known when the C "
                           "is written only")
        return _fold(function, args, kwargs)
    return handler


def _map(tr, args, kwargs):
    """map(f, *sequences) of sequences known when the C is written: a tuple of the calls."""
    function, sequences = args[0], [tr.iterate(a) for a in args[1:]]
    return Tuple([tr.call(function, list(items), {}) for items in zip(*sequences)])


def _dict(tr, args, kwargs):
    """dict(**keywords), or of (key, value) pairs whose keys are known when the C is written."""
    items = {}
    for pair in (tr.iterate(args[0]) if args else []):
        key, value = tr.iterate(pair)
        if not isinstance(key, Const):
            raise tr.error("a dict key must be known when the C is written")
        items[key.value] = value
    return Dict({**items, **kwargs})


def _clip(tr, args, kwargs):
    x, low, high = args
    return Scalar("double", f"gw_npmin(gw_npmax({x.code}, {low.code}), {high.code})")


def _setattr(tr, args, kwargs):
    obj, name, value = args
    if not (isinstance(obj, Obj) and isinstance(name, Const)):
        raise tr.error("object.__setattr__ needs an object and a known name")
    tr.set_field(obj, name.value, value)
    return Const(None)


def _bool(tr, args, kwargs):
    return tr.truth(args[0])


def _where(tr, args, kwargs):
    if any(isinstance(a, (Array, Vector)) for a in args):
        return tr.elementwise(lambda *row: _where(tr, list(row), kwargs), *args)
    condition = tr.truth(args[0])
    a, b = tr.scalar(args[1]), tr.scalar(args[2])
    if isinstance(condition, Const):
        return a if condition.value else b
    return Scalar("double", f"({condition.code} ? (double){a.code} : (double){b.code})")


def _brentq(tr, args, kwargs):
    """scipy.optimize.brentq(f, a, b, xtol=, rtol=, maxiter=, full_output=, disp=False): Brent's
    method (gw_brent_step) with f inlined where the iteration evaluates it."""
    names = ("f", "a", "b", "args", "xtol", "rtol", "maxiter", "full_output", "disp")
    given = {**dict(zip(names, args)), **kwargs}
    if given.get("args", Const(())).value != () or given.get("disp", Const(True)).value:
        raise tr.error("brentq is translated with disp=False and no extra args only")
    f = given["f"]
    z = tr.out.declare("gw_brent", "brent", 1)
    for key, default in (("xtol", 2e-12), ("rtol", 4 * np.finfo(float).eps)):
        tr.emit(f"{z}->{key} = {tr.scalar(given.get(key, Const(default))).code};")
    for end in ("a", "b"):
        tr.emit(f"{z}->{end} = (double){tr.scalar(given[end]).code};")
        tr.emit(f"{z}->f{end} = {tr.scalar(tr.call(f, [Scalar('double', f'{z}->{end}')], {})).code};")
    tr.emit(f"if ({z}->fa * {z}->fb > 0.0) {{")
    tr.fail([Const("f(a) and f(b) must have different signs")], ValueError)
    tr.emit("}")
    done, count = tr.out.declare("bool", "converged"), tr.out.declare("long", "iterations")
    tr.emit(f"{done} = gw_brent_start({z});")
    limit = tr.scalar(given.get("maxiter", Const(100))).code
    tr.emit(f"for ({count} = 0; !{done} && {count} < {limit}; ++{count}) {{")
    tr.out.depth += 1
    tr.emit(f"{z}->fb = {tr.scalar(tr.call(f, [Scalar('double', f'{z}->b')], {})).code};")
    tr.emit(f"{done} = gw_brent_step({z});")
    tr.out.depth -= 1
    tr.emit("}")
    root = Scalar("double", f"{z}->b")
    if not given.get("full_output", Const(False)).value:
        return root
    return Tuple([root, Obj(RootResults, {"root": root, "converged": Scalar("bool", done),
                                          "iterations": Scalar("long", count)})])


_ADD = ast.Add()  # the operator _sum adds with
#: numpy's functions, which act element by element on an array
_ELEMENTWISE = {f for f in [*_UNARY, *_BINARY, *_TESTS, np.float64, np.clip]
                if isinstance(f, np.ufunc) or f in (np.clip,)}


def table() -> dict:
    """The intrinsic handlers by Python function."""
    handlers = {}
    for function, c_name in _UNARY.items():
        handlers[function] = _numeric(function, _math_unary(function, c_name)
                                      if getattr(function, "__module__", None) == "math" and function not in (
                                          math.fabs, math.degrees, math.radians)
                                      else _unary(c_name))
    for function, c_name in _BINARY.items():
        handlers[function] = _numeric(function, _binary(c_name))
    for function, c_name in _TESTS.items():
        handlers[function] = _numeric(function, _test(c_name))
    handlers.update({
        math.floor: _numeric(math.floor, _rounding("floor")),
        math.ceil: _numeric(math.ceil, _rounding("ceil")),
        builtins.float: _float, np.float64: _numeric(np.float64, _to_double),
        builtins.str: _str, np.linspace: _linspace, np.interp: _interp, np.diff: _diff,
        builtins.int: _numeric(int, _int), builtins.abs: _numeric(abs, _abs),
        builtins.max: _numeric(max, _extreme("gw_pymax", "gw_pymaxl")),
        builtins.min: _numeric(min, _extreme("gw_pymin", "gw_pyminl")),
        builtins.sum: _sum, np.sum: _np_sum, np.max: _np_extreme(True), np.min: _np_extreme(False),
        np.asarray: _asarray, np.array: _asarray,
        np.all: _reduce_all(True), builtins.all: _reduce_all(True),
        np.any: _reduce_all(False), builtins.any: _reduce_all(False),
        builtins.isinstance: _isinstance, builtins.type: _type, builtins.getattr: _getattr,
        builtins.len: _len, builtins.zip: _zip, builtins.enumerate: _enumerate,
        builtins.range: _range, builtins.bool: _bool, builtins.dict: _dict, builtins.map: _map, np.where: _where,
        np.broadcast_to: _broadcast_to, np.broadcast_arrays: _broadcast_arrays, np.stack: _stack,
        np.zeros_like: _like(0.0), np.ones_like: _like(1.0), np.full_like: _like(None),
        np.zeros: _folded(np.zeros), np.ones: _folded(np.ones), np.eye: _folded(np.eye), np.linalg.solve: _solve, np.concatenate: _concatenate, np.diag: _diag, np.outer: _outer,
        np.trace: _trace, np.dot: _dot, scipy.linalg.eigh: _eigh, np.ravel: _ravel, np.arange: _arange,
        np.divide: _divide, brentq: _brentq, np.repeat: _repeat(False), np.tile: _repeat(True),
        np.clip: _numeric(np.clip, _clip), object.__setattr__: _setattr,
    })
    return handlers
