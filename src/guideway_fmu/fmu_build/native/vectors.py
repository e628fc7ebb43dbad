"""Arrays whose length is known at run time only: the numbers a String parameter's words give
(a factor table), and what numpy makes of them.

A :class:`~.values.Vector` is a C array of ``CAPACITY`` numbers and a length; numpy's
element-by-element operations, reductions, indexing by a known position, ``np.linspace`` with
a run-time count, ``np.interp`` and ``np.diff`` become C loops over it. More numbers than the
capacity, and arrays of different lengths meeting, are refused at run time with numpy's words
or the capacity named. A model holding a Vector keeps it in its struct (component.py lays out
a numpy array as a :class:`~.values.Slot` that takes the first value stored into it).
"""
from __future__ import annotations

import ast
import contextlib

from .values import Array, Const, Scalar, Tuple, Vector, Words, describe

CAPACITY = 256  # numbers a run-time array holds at most


class Vectors:
    """The translator's operations on run-time arrays (a mixin of the translator)."""

    def new_vector(self, ctype: str, length: str) -> Vector:
        """A fresh local array of ``ctype`` numbers (kept as doubles) and ``length`` (a C
        expression; more than CAPACITY is refused)."""
        data = self.out.vector("array")
        n = self.out.declare("long", "length")
        self.emit(f"{n} = {length};")
        self.emit(f"if ({n} > {CAPACITY}L) {{")
        self.fail([Const("an array of "), Scalar("long", n), Const(
            f" numbers is longer than the native edition holds ({CAPACITY}); take the python "
            "edition")], RuntimeError)
        self.emit("}")
        return Vector(ctype, data, Scalar("long", n))

    @contextlib.contextmanager
    def counting(self, length: Scalar):
        """Emit ``for (k = 0; k < length; ++k) { ... }`` around the block; yields k's C name."""
        k = self.out.declare("long", "k")
        self.emit(f"for ({k} = 0; {k} < {length.code}; ++{k}) {{")
        self.out.depth += 1
        try:
            yield k
        finally:
            self.out.depth -= 1
            self.emit("}")

    def element(self, vector: Vector, k: str) -> Scalar:
        """Element k (a C expression); a bool array keeps 0 and 1 as doubles."""
        if vector.ctype == "bool":
            return Scalar("bool", f"({vector.data}[{k}] != 0.0)")
        return Scalar("double", f"{vector.data}[{k}]")

    def vector_map(self, function, *operands) -> Vector:
        """``function`` of the elements (numbers broadcast), into a new run-time array."""
        vectors = [o for o in operands if isinstance(o, Vector)]
        if any(isinstance(o, (Tuple, Words)) for o in operands):
            raise self.error("a run-time array meets an array of fixed length")
        length = vectors[0].length
        for other in vectors[1:]:
            self.emit(f"if ({other.length.code} != {length.code}) {{")
            self.fail([Const("operands could not be broadcast together with shapes ("),
                       length, Const(",) ("), other.length, Const(",) ")], ValueError)
            self.emit("}")
        out = self.new_vector("double", length.code)
        with self.counting(length) as k:
            row = [self.element(o, k) if isinstance(o, Vector) else o for o in operands]
            value = self.scalar(function(*row))
            out.ctype = value.ctype if value.ctype == "bool" else "double"
            self.emit(f"{out.data}[{k}] = (double){value.code};")
        return out

    def fold(self, length: Scalar, hint: str, first: str, step) -> Scalar:
        """A double set to the C expression ``first``, then to ``step(k, it)`` for k = 0 ..
        length - 1 (a reduction in index order)."""
        it = self.out.declare("double", hint)
        self.emit(f"{it} = {first};")
        with self.counting(length) as k:
            self.emit(f"{it} = {step(k, it)};")
        return Scalar("double", it)

    def vector_reduce(self, vector: Vector, is_all: bool) -> Scalar:
        result = self.out.declare("bool", "all" if is_all else "any")
        self.emit(f"{result} = {1 if is_all else 0};")
        with self.counting(vector.length) as k:
            item = self.element(vector, k)
            test = f"!{item.code}" if is_all else item.code  # a double array: != 0 is true
            self.emit(f"if ({test}) {{ {result} = {0 if is_all else 1}; break; }}")
        return Scalar("bool", result)

    def vector_item(self, vector: Vector, index) -> Scalar:
        """``vector[index]`` at a known position (negative from the end), IndexError outside."""
        if not (isinstance(index, Const) and isinstance(index.value, int)):
            raise self.error(f"indexing a run-time array by {describe(index)} is not translated")
        position = (f"{index.value}L" if index.value >= 0 else
                    f"({vector.length.code} - {-index.value}L)")
        self.emit(f"if ({position} < 0 || {position} >= {vector.length.code}) {{")
        self.fail([Const(f"index {index.value} is out of bounds for axis 0 with size "),
                   vector.length], IndexError)
        self.emit("}")
        value = self.out.declare(vector.ctype, "item")
        self.emit(f"{value} = {self.element(vector, position).code};")
        return Scalar(vector.ctype, value)

    def vector_of_words(self, words: Words, target: ast.AST, element: ast.AST) -> Vector:
        """``[element for target in words]``: one number a word, in a loop."""
        out = self.new_vector("double", words.count.code)
        with self.counting(out.length) as k:
            self.assign(target, words.word(k))
            value = self.scalar(self.expr(element))
            self.emit(f"{out.data}[{k}] = {value.code};")
        return out

    def linspace(self, start: Scalar, stop: Scalar, num: Scalar) -> Vector:
        """np.linspace(start, stop, num) with num known at run time (intrinsics._linspace has
        numpy's arithmetic)."""
        out = self.new_vector("double", num.code)
        n, delta, step = out.length.code, self.out.declare("double", "delta"), \
            self.out.declare("double", "step")
        self.emit(f"{delta} = (double){stop.code} - (double){start.code};")
        self.emit(f"{step} = {delta} / (double)({n} - 1);")
        with self.counting(out.length) as k:
            self.emit(f"{out.data}[{k}] = ({n} > 1 && {step} == 0.0 ? ((double){k} / "
                      f"(double)({n} - 1)) * {delta} : (double){k} * ({n} > 1 ? {step} : "
                      f"{delta})) + (double){start.code};")
        self.emit(f"if ({n} > 1) {out.data}[{n} - 1] = (double){stop.code};")
        return out

    def diff(self, vector: Vector) -> Vector:
        out = self.new_vector(vector.ctype, f"({vector.length.code} > 0 ? "
                                            f"{vector.length.code} - 1 : 0)")
        with self.counting(out.length) as k:
            self.emit(f"{out.data}[{k}] = {vector.data}[{k} + 1] - {vector.data}[{k}];")
        return out

    def store_vector(self, target: Vector, value) -> None:
        """Copy the run-time array ``value`` into ``target`` (a struct's)."""
        if not isinstance(value, Vector):
            raise self.error(f"a run-time array cannot become {describe(value)}")
        self.emit(f"{target.length.code} = {value.length.code};")
        with self.counting(value.length) as k:
            self.emit(f"{target.data}[{k}] = {value.data}[{k}];")

    def vector_slice(self, vector: Vector, key) -> Vector:
        """``vector[start:stop]`` (Python's rules: negative bounds from the end, clipped)."""
        bounds = (key.value.start, key.value.stop) if isinstance(key, Const) else \
            tuple(b.value if isinstance(b, Const) else b for b in (key.start, key.stop))
        if isinstance(key, Const) and key.value.step not in (None, 1):
            raise self.error("a slice of a run-time array with a step is not translated")
        n, ends = vector.length.code, []
        for bound, default in zip(bounds, ("0L", n)):
            end = self.out.declare("long", "end")
            code = default if bound is None else (f"{bound}L" if isinstance(bound, int) else
                                                  self.scalar(bound).code)
            self.emit(f"{end} = {code};")
            self.emit(f"if ({end} < 0) {end} += {n};")
            self.emit(f"if ({end} < 0) {end} = 0; else if ({end} > {n}) {end} = {n};")
            ends.append(end)
        out = self.new_vector(vector.ctype, f"({ends[1]} > {ends[0]} ? {ends[1]} - {ends[0]} : 0)")
        with self.counting(out.length) as k:
            self.emit(f"{out.data}[{k}] = {vector.data}[{ends[0]} + {k}];")
        return out

    def repeated(self, vector: Vector, count: Scalar, whole: bool) -> Vector:
        """np.tile(vector, count) (``whole``) or np.repeat(vector, count) as a run-time array."""
        n = vector.length.code
        out = self.new_vector(vector.ctype, f"({count.code} > 0 ? {n} * {count.code} : 0)")
        with self.counting(out.length) as k:
            source = f"{k} % {n}" if whole else f"{k} / {count.code}"
            self.emit(f"{out.data}[{k}] = {vector.data}[{source}];")
        return out

    def concatenated(self, vectors: list) -> Vector:
        """np.concatenate of 1-D run-time arrays, one after the other."""
        out = self.new_vector(vectors[0].ctype, " + ".join(v.length.code for v in vectors))
        at = self.out.declare("long", "at")
        self.emit(f"{at} = 0;")
        for vector in vectors:
            with self.counting(vector.length) as k:
                self.emit(f"{out.data}[{at} + {k}] = {vector.data}[{k}];")
            self.emit(f"{at} += {vector.length.code};")
        return out

    def fixed_to_vector(self, array: Array) -> Vector:
        out = self.new_vector("double", f"{len(array.items)}L")
        for k, item in enumerate(array.items):
            self.emit(f"{out.data}[{k}] = {self.scalar(item).code};")
        return out
