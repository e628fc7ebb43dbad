"""The translator: Python functions, called with known structures, written as one C function.

Every call is inlined, so a value's structure (which fields an object has, which function a
name holds, whether an optional object is None) is known where it is used and only numbers are
left to run time. Python's reference semantics are kept where the physics relies on them: an
object is passed by reference, a number is copied into the callee's own variable, a variable
assigned again (in a loop, on both arms of an ``if``) is stored into the C variables it already
has. Variables are declared at the top of the C function; ``raise`` writes the message into
the context and jumps to the function's failure exit.
"""
from __future__ import annotations

import ast
import builtins
import dataclasses
import functools
import inspect
import os
import math
import sys
import sysconfig
import types

import numpy as np

from .vectors import CAPACITY
from .source import MissingAttribute, TranslationError, definition, returns
from .values import (
    Array,
    Choice,
    Const,
    Dict,
    Func,
    Joined,
    Message,
    Obj,
    Scalar,
    Slot,
    Text,
    Tuple,
    Vector,
    describe,
    is_number,
    leaves,
)

PACKAGE = __package__.split(".")[0]


class Frame:
    """One inlined call: its locals, the frame it closes over, its module's globals."""

    def __init__(self, translator, node, path: str, module_globals: dict, parent=None,
                 cells: dict | None = None):
        self.node, self.path, self.globals, self.parent = node, path, module_globals, parent
        self.locals: dict = dict(cells or {})
        self.single_return = False
        self.result = None
        self.label = translator.fresh("ret")
        self.owner = None  # the class whose body defines the function (super())
        self.carried: set[str] = set()  # names a run-time loop around carries between iterations

    def lookup(self, name: str):
        frame = self
        while frame is not None:
            if name in frame.locals:
                return frame.locals[name]
            frame = frame.parent
        if name in self.globals:
            return from_python(self.globals[name])
        if hasattr(builtins, name):
            return Const(getattr(builtins, name))
        raise KeyError(name)


class Emitter:
    """C lines with indentation, and the declarations of the function being written."""

    def __init__(self):
        self.lines: list[str] = []
        self.declarations: list[str] = []
        self.depth = 1
        self.counter = 0
        self.vectors = 0  # run-time arrays declared

    def emit(self, line: str) -> None:
        self.lines.append("    " * self.depth + line)

    def fresh(self, hint: str) -> str:
        self.counter += 1
        return f"{''.join(c if c.isalnum() else '_' for c in hint)[:24]}_{self.counter}"

    def declare(self, ctype: str, hint: str, length: int | None = None) -> str:
        """A new local C variable, zero at the start, or an array of ``length`` (not cleared:
        every array is written before it is read)."""
        name = self.fresh(hint)
        self.declarations.append(f"    {ctype} {name} = 0;" if length is None else
                                 f"    {ctype} {name}[{length}];")
        return name

    def vector(self, hint: str) -> str:
        """A new run-time array of vectors.CAPACITY doubles (not cleared), in the context's
        scratch on the heap (gw_scratch), not on the stack."""
        name = self.fresh(hint)
        self.declarations.append(f"    double *{name} = gw_vectors + {self.vectors * CAPACITY};")
        self.vectors += 1
        return name

    def body(self) -> str:
        """The function's declarations and lines, with its run-time arrays' scratch first."""
        head = [] if not self.vectors else [
            f"    double *gw_vectors = gw_scratch(ctx, {self.vectors * CAPACITY});",
            '    if (!gw_vectors) { gw_msg_clear(ctx); gw_msg_text(ctx, "no memory for the '
            'run-time arrays"); goto gw_fail; }']
        return "\n".join(head + self.declarations + self.lines)

    def capture(self) -> list[str]:
        """Start writing into a new list of lines; returns the previous one (for :meth:`restore`)."""
        previous, self.lines = self.lines, []
        return previous

    def restore(self, previous: list[str]) -> list[str]:
        captured, self.lines = self.lines, previous
        return captured


def from_python(value, layout=None):
    """The translator's value of a Python object known when the C is written."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    if isinstance(value, (np.floating, np.integer, np.bool_)):
        value = value.item()
    if isinstance(value, np.ndarray) and value.ndim == 1 and value.dtype.kind in "fib":
        return Array([from_python(v) for v in value])
    if isinstance(value, (tuple, list)):
        return Tuple([from_python(v) for v in value])
    if isinstance(value, dict) and all(isinstance(k, (str, int)) for k in value):
        return Dict({k: from_python(v) for k, v in value.items()})
    if _is_object(value):
        return Obj(type(value), {k: from_python(v) for k, v in vars(value).items()})
    if isinstance(value, types.FunctionType) and value.__closure__ and translatable(value):
        return func_of(value)  # a library's decorated function stays one, for its intrinsic
    return Const(value)


def _is_object(value) -> bool:
    """An instance of a class whose source the translator reads (an object the physics builds)."""
    return translatable(type(value)) and hasattr(value, "__dict__") and \
        not isinstance(value, (type, types.FunctionType, BaseException))


def _libraries() -> tuple[str, ...]:
    """Where installed libraries live: the interpreter's library folders and every
    site-packages (or dist-packages) folder on sys.path (a .pth file or a user site adds some)."""
    paths = {sysconfig.get_path(k) for k in ("stdlib", "platstdlib", "purelib", "platlib")}
    paths |= {p for p in sys.path if os.path.basename(os.path.normpath(p)) in (
        "site-packages", "dist-packages")}
    return tuple(os.path.join(p, "") for p in paths if p)


def translatable(cls: type) -> bool:
    """Whether objects of ``cls`` are translated: classes of this package or of other source
    outside the installed libraries (a user's model), not those of libraries."""
    name = getattr(cls, "__module__", None) or ""  # None for a function made by exec
    path = getattr(sys.modules.get(name), "__file__", None)
    return name.split(".")[0] == PACKAGE or (
        path is not None and not path.startswith(_libraries()))


def func_of(function, receiver=None, cell_value=None) -> Func:
    """A Python function object as a Func, its closure's cells as constants (or as
    ``cell_value(value, name)`` makes them)."""
    function = inspect.unwrap(function)
    node, path = definition(function)
    closure = dict(zip(function.__code__.co_freevars, function.__closure__ or ()))
    owner = closure.pop("__class__", None)
    cells = {name: cell_value(cell.cell_contents, name) if cell_value else
             from_python(cell.cell_contents) for name, cell in closure.items()}
    return Func(_Definition(node, path, function.__globals__, function, cells,
                            owner.cell_contents if owner else None), receiver)


@dataclasses.dataclass
class _Definition:
    """Where a function comes from: its node, file, globals, the function object (None for a
    function defined in translated code), its closure cells by name, the class whose body
    defines it (for ``super()``) and, defined in translated code, its default values."""

    node: ast.AST
    path: str
    globals: dict
    function: object
    cells: dict
    owner: type | None = None
    defaults: dict | None = None


class TranslatorCore:
    """Calls, attributes, assignment and returns (the statements and expressions are mixins)."""

    def __init__(self, intrinsics: dict, methods: dict | None = None):
        self.out = Emitter()
        self.intrinsics = intrinsics
        self.methods = methods or {}  # (class, name) -> handler(translator, receiver, args, kwargs)
        self.frame: Frame | None = None
        self.node: ast.AST | None = None
        self.left = False  # the statement just translated always leaves (Statements.block)
        self.catching: list[list[tuple[tuple[type, ...], str]]] = []  # open try statements

    # -- helpers ------------------------------------------------------------------------
    def fresh(self, hint: str) -> str:
        return self.out.fresh(hint)

    def emit(self, line: str) -> None:
        self.out.emit(line)

    def error(self, message: str, kind: type = TranslationError) -> TranslationError:
        where = f"{self.frame.path}:{getattr(self.node, 'lineno', '?')}" if self.frame else "?"
        return kind(f"{where}: {message}")

    # -- storage ------------------------------------------------------------------------
    def variable(self, value, owner):
        """Fresh C variables of ``value``'s structure, owned by ``owner``, holding its value."""
        if isinstance(value, Scalar):
            name = self.out.declare("double" if value.ctype == "double" else value.ctype, "v")
            self.emit(f"{name} = {value.code};")
            return Scalar(value.ctype, name, owner)
        if isinstance(value, Const) and is_number(value.value) and owner is not None:
            return self.variable(self.scalar(value), owner)
        if isinstance(value, Tuple):
            return type(value)([self.variable(v, owner) for v in value.items])
        if isinstance(value, Vector):  # a copy: a later assignment must not write the original
            copy = self.new_vector(value.ctype, value.length.code)
            self.store_vector(copy, value)
            return copy
        if isinstance(value, Dict):
            return Dict({k: self.variable(v, owner) for k, v in value.items.items()})
        if isinstance(value, Obj) and owner is not None and not isinstance(owner, Obj):
            return value  # objects are referenced, not copied
        return value

    def scalar(self, value) -> Scalar:
        from .values import scalar
        try:
            return scalar(value)
        except TypeError as exc:
            raise self.error(str(exc)) from None

    def owned(self, value, owner) -> bool:
        """Whether every number of ``value`` is a C variable ``owner`` may assign."""
        return all(not isinstance(leaf, Scalar) or leaf.owner is owner for leaf in leaves(value)) \
            and any(isinstance(leaf, Scalar) for leaf in leaves(value))

    def store(self, target, value, what: str) -> None:
        """Assign ``value`` into the variables of ``target`` (the same structure)."""
        if isinstance(target, Scalar):
            value = self.scalar(value)
            if target.ctype == "long" and value.ctype == "double":
                raise self.error(f"{what}: a whole number variable is given a float")
            self.emit(f"{target.code} = {value.code};")
        elif isinstance(target, Const):
            if not (isinstance(value, Const) and (value.value is target.value or (
                    type(value.value) is type(target.value) and value.value == target.value))):
                raise self.error(f"{what} holds {describe(target)} in the translated model and "
                                 f"cannot become {describe(value)}")
        elif isinstance(target, Tuple) and isinstance(value, Tuple) and \
                len(target.items) == len(value.items):
            for i, (t, v) in enumerate(zip(target.items, value.items)):
                self.store(t, v, f"{what}[{i}]")
        elif isinstance(target, Dict) and isinstance(value, Dict) and \
                target.items.keys() == value.items.keys():
            for key in target.items:
                self.store(target.items[key], value.items[key], f"{what}[{key!r}]")
        elif isinstance(target, Obj) and isinstance(value, Obj) and target.cls is value.cls:
            for key in target.fields:
                if key not in value.fields and isinstance(
                        getattr(value.cls, key, None), functools.cached_property):
                    self.attribute(value, key)  # computed where the example had it cached
                if key not in value.fields:
                    raise self.error(f"{what}.{key} is missing")
                if isinstance(target.fields[key], Slot):
                    target.fields[key] = target.fields[key].make(value.fields[key])
                self.store(target.fields[key], value.fields[key], f"{what}.{key}")
        elif isinstance(target, Vector):
            self.store_vector(target, value)
        elif isinstance(target, Func) and isinstance(value, Func) and \
                target.function.node is value.function.node:
            for name, cell in target.function.cells.items():
                self.store(cell, value.frame.lookup(name) if value.frame else
                           value.function.cells[name], f"{what} (closure variable {name})")
        else:
            raise self.error(f"{what}: {describe(target)} cannot be given {describe(value)}")

    def bind(self, name: str, value) -> None:
        """``name = value`` in the current frame: new variables, except for a name a run-time
        loop carries, whose variables are stored into (module doc)."""
        frame = self.frame
        current = frame.locals.get(name)
        if name in frame.carried and current is not None and self.owned(current, frame):
            if not self._fits(current, value):
                raise self.error(f"{name} changes from {describe(current)} to {describe(value)} "
                                 "in a loop")
            self.store(current, value, name)
            return
        frame.locals[name] = value if isinstance(value, (Message, Obj, Choice)) else \
            self.variable(value, frame)

    @staticmethod
    def _fits(current, value) -> bool:
        if isinstance(current, Scalar):
            return isinstance(value, Scalar) or (isinstance(value, Const) and is_number(value.value))
        from .values import same_shape
        if isinstance(current, Vector):  # any run-time array of its kind is copied in
            return isinstance(value, Vector) and value.ctype == current.ctype
        if isinstance(current, Tuple) and isinstance(value, Tuple):
            return len(current.items) == len(value.items) and all(
                TranslatorCore._fits(c, v) for c, v in zip(current.items, value.items))
        return same_shape(current, value)

    def set_field(self, obj: Obj, name: str, value) -> None:
        """``obj.name = value``: into the field's variables when the object owns them."""
        current = obj.fields.get(name)
        if current is not None and self.owned(current, obj):
            self.store(current, value, f"{obj.cls.__name__}.{name}")
        else:
            obj.fields[name] = self.variable(value, obj) if not isinstance(value, (Obj, Func)) \
                else value

    # -- attributes ---------------------------------------------------------------------
    def attribute(self, value, name: str):
        if isinstance(value, Obj):
            if isinstance(value.fields.get(name), Slot):  # read before stored: of its example
                value.fields[name] = value.fields[name].make(None)
            if name in value.fields:
                return value.fields[name]
            handler = self.methods.get((value.cls, name)) or next(
                (self.methods[(c, name)] for c in value.cls.__mro__ if (c, name) in self.methods),
                None)
            if handler is not None:
                return Const(_Bound(handler, value))
            return self.class_attribute(value.cls, name, value)
        if isinstance(value, Choice):
            return value.map(lambda side: self.attribute(side, name))
        if isinstance(value, _Super):
            mro = value.receiver.cls.__mro__ if isinstance(value.receiver, Obj) else \
                value.receiver.value.__mro__
            for cls in mro[mro.index(value.cls) + 1:]:
                if name in vars(cls):
                    return self.class_attribute(cls, name, value.receiver)
            raise self.error(f"super() has no attribute {name}", MissingAttribute)
        if isinstance(value, Const):
            if isinstance(value.value, type):
                return self.class_attribute(value.value, name, None)
            try:
                return from_python(getattr(value.value, name))
            except AttributeError:
                raise self.error(f"{describe(value)} has no attribute {name}",
                                 MissingAttribute) from None
        if isinstance(value, Dict) and name in ("items", "keys", "values", "get"):
            return Const(_Bound(_DICT_METHODS[name], value))
        if isinstance(value, Text) and name == "split":
            from .intrinsics import split
            return Const(_Bound(split, value))
        if isinstance(value, (Vector, Array)) and name in ("sum", "reshape", "max", "min", "tolist"):
            from .intrinsics import ARRAY_METHODS
            return Const(_Bound(ARRAY_METHODS[name], value))
        if isinstance(value, Vector) and name in ("shape", "ndim", "size"):
            return {"shape": Tuple([value.length]), "ndim": Const(1), "size": value.length}[name]
        if isinstance(value, (Array, Scalar)) and name in ("shape", "ndim", "size"):
            shape = (len(value.items),) if isinstance(value, Array) else ()
            return Const({"shape": shape, "ndim": len(shape), "size": math.prod(shape)}[name])
        raise self.error(f"attribute {name} of {describe(value)} is not translated")

    def class_attribute(self, cls: type, name: str, receiver):
        for owner in cls.__mro__:
            if name in vars(owner):
                attr = vars(owner)[name]
                break
        else:
            if not hasattr(cls, name):
                raise self.error(f"{cls.__name__} has no attribute {name}", MissingAttribute)
            return from_python(getattr(cls, name))
        if isinstance(attr, classmethod):
            return func_of(attr.__func__, Const(cls))
        if isinstance(attr, staticmethod):
            return func_of(attr.__func__)
        if isinstance(attr, property):
            return self.inline(func_of(attr.fget, receiver), [], {})
        if isinstance(attr, functools.cached_property) and isinstance(receiver, Obj):
            receiver.fields[name] = self.inline(func_of(attr.func, receiver), [], {})
            return receiver.fields[name]
        if isinstance(attr, types.FunctionType):
            return func_of(attr, receiver) if receiver is not None else Const(attr)
        return from_python(attr)

    # -- calls --------------------------------------------------------------------------
    def call(self, func, args: list, kwargs: dict):
        if isinstance(func, Choice):
            return self.choose(func.condition, lambda: self.call(func.first, args, kwargs),
                               lambda: self.call(func.second, args, kwargs))
        if isinstance(func, Func):
            return self.inline(func, args, kwargs)
        if isinstance(func, Obj):
            return self.inline(self.attribute(func, "__call__"), args, kwargs)
        if not isinstance(func, Const):
            raise self.error(f"{describe(func)} is not callable in translated code")
        target = func.value
        if isinstance(target, _Bound):
            return target.handler(self, target.receiver, args, kwargs)
        handler = self.intrinsics.get(_key(target))
        if handler is not None:
            return handler(self, args, kwargs)
        if isinstance(target, functools._lru_cache_wrapper):  # the cache is Python's business
            return self.call(Const(target.__wrapped__), args, kwargs)
        if isinstance(target, types.FunctionType):
            return self.inline(func_of(target), args, kwargs)
        if isinstance(target, type):
            return self.construct(target, args, kwargs)
        if isinstance(target, types.BuiltinMethodType) and isinstance(
                getattr(target, "__self__", None), str) and target.__name__ == "join":
            return self.join(target.__self__, self.iterate(args[0]))
        if isinstance(target, types.BuiltinFunctionType | types.BuiltinMethodType) and all(
                isinstance(a, Const) for a in [*args, *kwargs.values()]):
            return from_python(target(*[a.value for a in args],
                                      **{k: v.value for k, v in kwargs.items()}))
        raise self.error(f"call of {describe(func)} is not translated")

    def join(self, separator: str, items: list):
        """``separator.join(items)``: folded when every item is known text, else a message
        (items under a run-time condition: (condition, text), from a comprehension)."""
        if all(isinstance(i, Const) and isinstance(i.value, str) for i in items):
            return Const(separator.join(i.value for i in items))
        return Message([Joined(separator, [i if isinstance(i, tuple) else (None, i)
                                           for i in items])])

    def construct(self, cls: type, args: list, kwargs: dict):
        if issubclass(cls, BaseException):
            return Obj(cls, {"message": args[0] if args else Const("")})
        if cls in (tuple, list):
            return Tuple(list(self.iterate(args[0]))) if args else Tuple([])
        if not translatable(cls):
            raise self.error(f"objects of {cls.__qualname__} are not translated")
        obj = Obj(cls, {})
        if dataclasses.is_dataclass(cls) and "__init__" not in {k for c in cls.__mro__[1:]
                                                                 for k in vars(c)} - {"__init__"}:
            names = [f.name for f in dataclasses.fields(cls) if f.init]
            bound = self.bind_arguments(names, args, kwargs, cls.__name__)
            for f in [f for f in dataclasses.fields(cls) if f.init]:
                if f.name in bound:
                    value = bound[f.name]
                elif f.default is not dataclasses.MISSING:
                    value = from_python(f.default)
                elif f.default_factory is not dataclasses.MISSING:
                    value = from_python(f.default_factory())
                else:
                    raise self.error(f"{cls.__name__}: argument {f.name} missing")
                self.set_field(obj, f.name, value)
            if hasattr(cls, "__post_init__"):
                self.inline(func_of(cls.__post_init__, obj), [], {})
            return obj
        init = next((vars(c)["__init__"] for c in cls.__mro__ if "__init__" in vars(c)), None)
        if init is not None and init is not object.__init__:
            self.inline(func_of(init, obj), args, kwargs)
        return obj

    def bind_arguments(self, names: list[str], args: list, kwargs: dict, what: str) -> dict:
        if len(args) > len(names):
            raise self.error(f"{what} takes {len(names)} arguments, {len(args)} given")
        bound = dict(zip(names, args))
        for key, value in kwargs.items():
            if key not in names or key in bound:
                raise self.error(f"{what}: unexpected or repeated argument {key}")
            bound[key] = value
        return bound

    def inline(self, func: Func, args: list, kwargs: dict):
        """The value of ``func(*args, **kwargs)``, its body written here."""
        definition_ = func.function
        node = definition_.node
        parameters = node.args
        positional = [a.arg for a in parameters.posonlyargs + parameters.args]
        if func.receiver is not None:
            args = [func.receiver, *args]
        frame = Frame(self, node, definition_.path, definition_.globals,
                      parent=func.frame, cells=definition_.cells)
        frame.owner = definition_.owner
        star = parameters.vararg.arg if parameters.vararg else None
        extra_kw = parameters.kwarg.arg if parameters.kwarg else None
        given = dict(zip(positional, args))
        if star:
            frame.locals[star] = Tuple(list(args[len(positional):]))
        elif len(args) > len(positional):
            raise self.error(f"{getattr(node, 'name', 'lambda')} takes {len(positional)} "
                             f"positional arguments, {len(args)} given")
        names = positional + [a.arg for a in parameters.kwonlyargs]
        rest = {}
        for key, value in kwargs.items():
            if key in names and key not in given:
                given[key] = value
            elif extra_kw:
                rest[key] = value
            else:
                raise self.error(f"{getattr(node, 'name', 'lambda')}: unexpected argument {key}")
        if extra_kw:
            frame.locals[extra_kw] = Dict(rest)
        defaults = self.defaults(func)
        caller, self.frame = self.frame, frame
        try:
            for name in names:
                if name in given:
                    value = given[name]
                elif name in defaults:
                    value = defaults[name]
                else:
                    raise self.error(f"{getattr(node, 'name', 'lambda')}: argument {name} missing")
                frame.locals[name] = self.variable(value, frame) if isinstance(value, (
                    Scalar, Tuple)) else value
            if isinstance(node, ast.Lambda):
                return self.expr(node.body)
            found = returns(node)
            frame.single_return = len(found) == 1 and node.body[-1] is found[0]
            self.block(node.body)
            self.left = False
            if not frame.single_return and found:
                self.emit(f"{frame.label}: ;")
            return frame.result if frame.result is not None else Const(None)
        finally:
            self.frame = caller

    def defaults(self, func: Func) -> dict:
        definition_ = func.function
        if definition_.function is not None:
            sig = inspect.signature(definition_.function)
            return {n: from_python(p.default) for n, p in sig.parameters.items()
                    if p.default is not inspect.Parameter.empty}
        return dict(definition_.defaults or {})

    def returned(self, value) -> None:
        frame = self.frame
        if frame.single_return:
            frame.result = value
            return
        if frame.result is None:  # a number may meet a run-time one at a later return
            frame.result = self.variable(value, frame) if not isinstance(value, Const) or \
                is_number(value.value) else value
        else:
            self.store(frame.result, value, "the returned value")
        self.emit(f"goto {frame.label};")


@dataclasses.dataclass
class _Bound:
    """A method the translator provides, bound to its receiver."""

    handler: object
    receiver: object


@dataclasses.dataclass
class _Super:
    cls: type
    receiver: object


def _key(target):
    try:
        hash(target)
    except TypeError:
        return None
    return target


def _items(tr, d, args, kwargs):
    return Tuple([Tuple([from_python(k), v]) for k, v in d.items.items()])


def _keys(tr, d, args, kwargs):
    return Tuple([from_python(k) for k in d.items])


def _values(tr, d, args, kwargs):
    return Tuple(list(d.items.values()))


def _get(tr, d, args, kwargs):
    key = args[0]
    if not isinstance(key, Const):
        raise tr.error("dict.get with a run-time key is not translated")
    return d.items.get(key.value, args[1] if len(args) > 1 else Const(None))


_DICT_METHODS = {"items": _items, "keys": _keys, "values": _values, "get": _get}
