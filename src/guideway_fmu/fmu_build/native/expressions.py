"""Expressions of the translated subset: arithmetic and comparisons on numbers (folded when
known), structures, attribute and item access, calls, f-strings, comprehensions."""
from __future__ import annotations

import ast
import operator

from .translate import Frame, Func, _Definition, _Super, from_python
from .values import (
    Array,
    Choice,
    Const,
    Dict,
    Joined,
    Listed,
    Masked,
    Message,
    Obj,
    Scalar,
    Span,
    Text,
    Tuple,
    Vector,
    Word,
    Words,
    describe,
    is_number,
    literal,
)

_FOLD = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
         ast.Div: operator.truediv, ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod,
         ast.Pow: operator.pow, ast.BitAnd: operator.and_, ast.BitOr: operator.or_,
         ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le,
         ast.Gt: operator.gt, ast.GtE: operator.ge}
_C = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Eq: "==", ast.NotEq: "!=",
      ast.Lt: "<", ast.LtE: "<=", ast.Gt: ">", ast.GtE: ">=", ast.BitAnd: "&&", ast.BitOr: "||"}
_FORMATS = {"g", "e", "f", "G", "E"}


class Expressions:
    """Mixin of the translator (translate.TranslatorCore)."""

    def expr(self, node: ast.expr):
        outer, self.node = self.node, node if hasattr(node, "lineno") else self.node
        try:
            handler = getattr(self, f"expr_{type(node).__name__}", None)
            if handler is None:
                raise self.error(f"the expression {type(node).__name__} is not translated")
            return handler(node)
        finally:
            self.node = outer

    def expr_Constant(self, node):
        return Const(node.value)

    def expr_Name(self, node):
        try:
            return self.frame.lookup(node.id)
        except KeyError:
            raise self.error(f"name {node.id} is not defined") from None

    def expr_Tuple(self, node):
        items = []
        for element in node.elts:
            if isinstance(element, ast.Starred):
                items.extend(self.iterate(self.expr(element.value)))
            else:
                items.append(self.expr(element))
        return Tuple(items)

    expr_List = expr_Tuple

    def expr_Dict(self, node):
        items = {}
        for key, value in zip(node.keys, node.values):
            if key is None:
                spread = self.expr(value)
                if not isinstance(spread, Dict):
                    raise self.error(f"** of {describe(spread)}")
                items.update(spread.items)
                continue
            k = self.expr(key)
            if not isinstance(k, Const):
                raise self.error("a dict key must be known when the C is written")
            items[k.value] = self.expr(value)
        return Dict(items)

    def expr_Attribute(self, node):
        return self.attribute(self.expr(node.value), node.attr)

    def expr_Subscript(self, node):
        container, key = self.expr(node.value), self.expr(node.slice)
        if isinstance(key, Const) and isinstance(container, (Tuple, Dict)):
            try:
                if isinstance(container, Tuple):
                    item = container.items[key.value]
                    return Tuple(item) if isinstance(key.value, slice) else item
                return container.items[key.value]
            except (IndexError, KeyError, TypeError):
                raise self.error(f"index {key.value!r} of {describe(container)}") from None
        if isinstance(container, Const) and isinstance(key, Const):
            return from_python(container.value[key.value])
        if isinstance(container, Vector) and (isinstance(key, Span) or (
                isinstance(key, Const) and isinstance(key.value, slice))):
            return self.vector_slice(container, key)
        if isinstance(container, Vector):
            return self.vector_item(container, key)
        if isinstance(container, Array) and isinstance(key, Array) and \
                len(key.items) == len(container.items):
            return Masked(list(container.items), [self.truth(k) for k in key.items])
        raise self.error(f"indexing {describe(container)} by {describe(key)} is not translated")

    def expr_Slice(self, node):
        parts = [self.expr(p) if p is not None else Const(None)
                 for p in (node.lower, node.upper, node.step)]
        if not all(isinstance(p, Const) for p in parts):
            if isinstance(parts[2], Const) and parts[2].value is None and all(
                    isinstance(p, Const) and p.value is None or isinstance(p, Scalar) and
                    p.ctype == "long" or isinstance(p, Const) and isinstance(p.value, int)
                    for p in parts[:2]):
                return Span(*parts[:2])  # of a run-time array
            raise self.error("a slice must be known when the C is written, or whole-number "
                             "bounds without a step")
        return Const(slice(*(p.value for p in parts)))

    def expr_NamedExpr(self, node):
        self.bind(node.target.id, self.expr(node.value))
        return self.frame.locals[node.target.id]

    def expr_Lambda(self, node):
        defaults = self.argument_defaults(node.args)
        return Func(_Definition(node, self.frame.path, self.frame.globals, None, {},
                                self.frame.owner, defaults), None, self.frame)

    def expr_Call(self, node):
        func_node = node.func
        if isinstance(func_node, ast.Name) and func_node.id == "super" and not node.args:
            receiver = self.frame.lookup(self.frame.node.args.args[0].arg)
            return _Super(self.frame.owner, receiver)
        func = self.expr(func_node)
        args = []
        for arg in node.args:
            if isinstance(arg, ast.Starred):
                args.extend(self.iterate(self.expr(arg.value)))
            else:
                args.append(self.expr(arg))
        kwargs = {}
        for keyword in node.keywords:
            value = self.expr(keyword.value)
            if keyword.arg is None:
                if not isinstance(value, Dict):
                    raise self.error(f"** of {describe(value)}")
                kwargs.update(value.items)
            else:
                kwargs[keyword.arg] = value
        return self.call(func, args, kwargs)

    def expr_IfExp(self, node):
        test = self.truth(self.expr(node.test))
        if isinstance(test, Const):
            return self.expr(node.body if test.value else node.orelse)
        previous = self.out.capture()
        first = self.expr(node.body)
        lines_first = self.out.capture()
        second = self.expr(node.orelse)
        lines_second = self.out.restore(previous)
        if not lines_first and not lines_second and _numbers(first, second):
            a, b = self.scalar(first), self.scalar(second)
            ctype = "double" if "double" in (a.ctype, b.ctype) else a.ctype
            return Scalar(ctype, f"({test.code} ? {a.code} : {b.code})")
        if not self._fits(first, second) or isinstance(first, (Obj, Func, Choice)):
            flag = self.out.declare("bool", "cond")
            self.emit(f"{flag} = {test.code};")
            self.emit(f"if ({flag}) {{")
            self.out.lines.extend("    " + line for line in lines_first)
            self.emit("} else {")
            self.out.lines.extend("    " + line for line in lines_second)
            self.emit("}")
            return Choice(flag, first, second)
        previous = self.out.capture()  # the target's variables; each arm stores into them
        target = self.variable(first if isinstance(first, Scalar) or not _numbers(first, second)
                               else self.scalar(first), self.frame)
        self.out.restore(previous)
        for keyword, lines, value in (("if", lines_first, first), ("} else", lines_second, second)):
            self.emit(f"{keyword} ({test.code}) {{" if keyword == "if" else "} else {")
            self.out.lines.extend("    " + line for line in lines)
            self.out.depth += 1
            self.store(target, value, "a conditional expression")
            self.out.depth -= 1
        self.emit("}")
        return target

    def expr_BoolOp(self, node):
        """``and`` / ``or``: a known operand decides or drops out; the rest are a C condition
        (in a condition, Python's operand value and its truth agree). An operand that needs
        statements (a check that may fail) runs only where Python evaluates it."""
        is_and = isinstance(node.op, ast.And)
        operands, value = [], Const(is_and)
        for operand in node.values:
            previous = self.out.capture()
            value = self.expr(operand)
            lines = self.out.restore(previous)
            truth = self.truth(value)
            operands.append((lines, truth))
            if isinstance(truth, Const) and truth.value != is_and:  # False decides an and
                break
        if all(not lines for lines, _ in operands[1:]):
            self.out.lines.extend(operands[0][0])
            terms = [t.code for _, t in operands if not isinstance(t, Const)]
            if isinstance(operands[-1][1], Const) and operands[-1][1].value != is_and:
                return value if not terms else Const(not is_and)
            if not terms:
                return value
            return Scalar("bool", "(" + (" && " if is_and else " || ").join(terms) + ")")
        flag = self.out.declare("bool", "and" if is_and else "or")
        self.emit(f"{flag} = {1 if is_and else 0};")
        opened = 0
        for k, (lines, truth) in enumerate(operands):
            if k:
                self.emit(f"if ({'' if is_and else '!'}{flag}) {{")
                self.out.depth += 1
                opened += 1
            self.out.lines.extend("    " * self.out.depth + line for line in lines)
            self.emit(f"{flag} = {truth.code if isinstance(truth, Scalar) else int(truth.value)};")
        for _ in range(opened):
            self.out.depth -= 1
            self.emit("}")
        return Scalar("bool", flag)

    def expr_UnaryOp(self, node):
        value = self.expr(node.operand)
        if isinstance(node.op, ast.Not):
            truth = self.truth(value)
            return Const(not truth.value) if isinstance(truth, Const) else \
                Scalar("bool", f"(!{truth.code})")
        if isinstance(node.op, ast.Invert):  # numpy's: logical not of booleans, ~ of integers
            return self.invert(value)
        if isinstance(value, Const) and is_number(value.value):
            return Const(-value.value if isinstance(node.op, ast.USub) else +value.value)
        if isinstance(value, Vector):
            return self.vector_map(lambda v: self.binary(ast.Mult(), Const(
                -1.0 if isinstance(node.op, ast.USub) else 1.0), v), value)
        if isinstance(value, Array):
            return Array([self.binary(ast.Mult(), Const(-1.0 if isinstance(node.op, ast.USub)
                                                        else 1.0), v) for v in value.items])
        s = self.scalar(value)
        if isinstance(node.op, ast.USub):
            return Scalar("double" if s.ctype == "double" else "long", f"(-{s.code})")
        return s

    def invert(self, value):
        if isinstance(value, Array):
            return Array([self.invert(v) for v in value.items])
        if isinstance(value, Vector):
            return self.vector_map(self.invert, value)
        if isinstance(value, Const) and isinstance(value.value, (bool, int)):
            return Const(not value.value if isinstance(value.value, bool) else ~value.value)
        s = self.scalar(value)
        if s.ctype == "double":
            raise self.error("~ of a float")
        return Scalar("bool", f"(!{s.code})") if s.ctype == "bool" else Scalar("long", f"(~{s.code})")

    def expr_BinOp(self, node):
        return self.binary(node.op, self.expr(node.left), self.expr(node.right))

    def binary(self, op, left, right):
        if isinstance(left, (Array, Vector)) or isinstance(right, (Array, Vector)):
            return self.elementwise(lambda a, b: self.binary(op, a, b), left, right)
        if isinstance(left, Tuple) and isinstance(op, ast.Mult) and isinstance(right, Const):
            return Tuple(left.items * right.value)
        if isinstance(left, Const) and isinstance(right, Const):
            try:
                return from_python(_FOLD[type(op)](left.value, right.value))
            except Exception as exc:  # noqa: BLE001 - reported as the translation's error
                raise self.error(f"{type(exc).__name__} folding constants: {exc}") from None
        if isinstance(left, Tuple) and isinstance(op, ast.Add) and isinstance(right, Tuple):
            return Tuple(left.items + right.items)
        a, b = self.scalar(left), self.scalar(right)
        double = "double" in (a.ctype, b.ctype)
        kind = type(op)
        if kind is ast.Div:
            return Scalar("double", f"((double){a.code} / {b.code})")
        if kind is ast.Pow:
            if isinstance(right, Const) and right.value == 2:
                return Scalar("double" if double else "long", f"({a.code} * {a.code})")
            return Scalar("double", f"pow({a.code}, {b.code})")
        if kind is ast.Mod:
            return Scalar("double", f"gw_mod({a.code}, {b.code})") if double else \
                Scalar("long", f"gw_lmod({a.code}, {b.code})")
        if kind is ast.FloorDiv:
            return Scalar("double", f"floor({a.code} / {b.code})") if double else \
                Scalar("long", f"gw_ldiv({a.code}, {b.code})")
        if kind in (ast.BitAnd, ast.BitOr):
            if a.ctype != "bool" or b.ctype != "bool":
                raise self.error("& and | are translated on booleans only")
            return Scalar("bool", f"({a.code} {_C[kind]} {b.code})")
        if kind not in _C:
            raise self.error(f"the operator {kind.__name__} is not translated")
        return Scalar("double" if double else "long", f"({a.code} {_C[kind]} {b.code})")

    def elementwise(self, function, *operands):
        """``function`` applied element by element, numbers broadcast (numpy's rule for 1-D)."""
        if any(isinstance(o, Vector) for o in operands):
            return self.vector_map(function, *operands)
        lengths = {len(o.items) for o in operands if isinstance(o, Tuple)}
        if len(lengths) != 1:
            raise self.error(f"arrays of lengths {sorted(lengths)} do not broadcast")
        n = lengths.pop()
        columns = [o.items if isinstance(o, Tuple) else [o] * n for o in operands]
        return Array([function(*row) for row in zip(*columns)])

    def expr_Compare(self, node):
        left = self.expr(node.left)
        terms = []
        for op, right_node in zip(node.ops, node.comparators):
            right = self.expr(right_node)
            term = self.compare(op, left, right)
            if isinstance(term, (Array, Vector)):
                if len(node.ops) > 1:
                    raise self.error("chained comparisons of arrays are not translated")
                return term
            if isinstance(term, Const):
                if not term.value:
                    return Const(False)
            else:
                terms.append(term.code)
            left = right
        return Scalar("bool", "(" + " && ".join(terms) + ")") if terms else Const(True)

    def compare(self, op, left, right):
        kind = type(op)
        if kind not in (ast.Is, ast.IsNot, ast.In, ast.NotIn) and (
                isinstance(left, (Array, Vector)) or isinstance(right, (Array, Vector))):
            return self.elementwise(lambda a, b: self.compare(op, a, b), left, right)
        if kind in (ast.Is, ast.IsNot) and isinstance(left, Choice):
            return _either(left.condition, self.compare(op, left.first, right),
                           self.compare(op, left.second, right))
        if kind in (ast.Is, ast.IsNot):
            same = _identical(left, right)
            if same is None:
                raise self.error(f"'is' between {describe(left)} and {describe(right)}")
            return Const(same == (kind is ast.Is))
        if kind in (ast.In, ast.NotIn):
            if not isinstance(left, Const):
                raise self.error(f"'in' with {describe(left)}")
            if isinstance(right, Dict):
                found = left.value in right.items
            elif isinstance(right, Tuple) and all(isinstance(i, Const) for i in right.items):
                found = any(i.value == left.value for i in right.items)
            elif isinstance(right, Const):
                found = left.value in right.value
            else:
                raise self.error(f"'in' over {describe(right)}")
            return Const(found == (kind is ast.In))
        if isinstance(left, Const) and isinstance(right, Const):
            return Const(_FOLD[kind](left.value, right.value))
        if kind in (ast.Eq, ast.NotEq) and (_is_tuple(left) or _is_tuple(right)):
            equal = self.tuples_equal(left, right)
            if isinstance(equal, Const):
                return Const(equal.value == (kind is ast.Eq))
            return equal if kind is ast.Eq else Scalar("bool", f"(!{equal.code})")
        if kind in (ast.Eq, ast.NotEq) and isinstance(left, Const) != isinstance(right, Const):
            known = left if isinstance(left, Const) else right
            if not is_number(known.value):  # a number is never equal to a string or None
                return Const(kind is ast.NotEq)
        a, b = self.scalar(left), self.scalar(right)
        return Scalar("bool", f"({a.code} {_C[kind]} {b.code})")

    def tuples_equal(self, left, right):
        """``left == right`` of tuples (a known tuple or a Tuple of values): item by item."""
        left, right = (from_python(v.value) if isinstance(v, Const) else v for v in (left, right))
        if not (type(left) is Tuple and type(right) is Tuple) or \
                len(left.items) != len(right.items):
            return Const(False)
        codes = []
        for a, b in zip(left.items, right.items):
            term = self.compare(ast.Eq(), a, b)
            if isinstance(term, Const):
                if not term.value:
                    return Const(False)
            else:
                codes.append(term.code)
        return Scalar("bool", "(" + " && ".join(codes) + ")") if codes else Const(True)

    def truth(self, value):
        """A condition: Const(bool) when known, else a Scalar bool."""
        if isinstance(value, Const):
            return Const(bool(value.value))
        if isinstance(value, Scalar):
            return value if value.ctype == "bool" else Scalar("bool", f"({value.code} != 0)")
        if isinstance(value, (Tuple, Dict)):
            return Const(bool(value.items))
        if isinstance(value, Choice):
            return _either(value.condition, self.truth(value.first), self.truth(value.second))
        return Const(True)

    def iterate(self, value):
        """The items of a sequence known when the C is written."""
        if isinstance(value, Tuple):
            return list(value.items)
        if isinstance(value, Dict):
            return [from_python(k) for k in value.items]
        if isinstance(value, Const):
            try:
                return [from_python(v) for v in value.value]
            except TypeError:
                pass
        raise self.error(f"iterating over {describe(value)} is not translated (the sequence "
                         "must be known when the C is written)")

    # -- strings ------------------------------------------------------------------------
    def expr_JoinedStr(self, node):
        parts = []
        for part in node.values:
            if isinstance(part, ast.Constant):
                parts.append(Const(part.value))
                continue
            value = self.expr(part.value)
            spec = "" if part.format_spec is None else self.expr(part.format_spec)
            if isinstance(spec, Message) or (isinstance(spec, Const) and not isinstance(
                    spec.value, str)):
                raise self.error("a format spec must be known when the C is written")
            spec = spec if isinstance(spec, str) else spec.value
            conversion = chr(part.conversion) if part.conversion > 0 else ""
            if isinstance(value, Const):
                text = repr(value.value) if conversion == "r" else str(value.value) \
                    if conversion == "s" else format(value.value, spec)
                parts.append(Const(text))
            elif isinstance(value, Message):
                parts.extend(value.parts)
            elif isinstance(value, (Text, Word)):
                parts.append((value, spec, conversion))
            elif type(value) in (Tuple, Array, Listed) and not spec:  # str is repr here
                parts.extend(self.tuple_repr(value))
            elif isinstance(value, Vector) and not spec:
                parts.append(value)
            else:
                parts.append((self.scalar(value), spec, conversion))
        if all(isinstance(p, Const) for p in parts):
            return Const("".join(p.value for p in parts))
        return Message(parts)

    def tuple_repr(self, value: Tuple) -> list:
        """The message parts of repr(tuple) of numbers and text: (a, b) or (a,); of a list
        (``tolist()``) [a, b]; of a 1-D array array([a, b]) with each number as Python writes
        it (numpy pads and shortens them)."""
        if isinstance(value, (Array, Listed)):
            inner = self.tuple_repr(Tuple(value.items))[1:-1]
            return [Const("array([" if isinstance(value, Array) else "["), *inner,
                    Const("])" if isinstance(value, Array) else "]")]
        parts = [Const("(")]
        for k, item in enumerate(value.items):
            if k:
                parts.append(Const(", "))
            if isinstance(item, Const):
                parts.append(Const(repr(item.value)))
            elif type(item) is Tuple:
                parts.extend(self.tuple_repr(item))
            else:
                parts.append((self.scalar(item), "", "r"))
        parts.append(Const(",)" if len(value.items) == 1 else ")"))
        return parts

    def message_part(self, part) -> None:
        if isinstance(part, Const):
            text = part.value if isinstance(part.value, str) else repr(part.value)
            self.emit(f"gw_msg_text(ctx, {c_string(text)});")
            return
        if isinstance(part, Message):
            for sub in part.parts:
                self.message_part(sub)
            return
        if isinstance(part, Joined):
            first = self.out.declare("bool", "first")
            self.emit(f"{first} = 1;")
            for condition, item in part.items:
                if condition is not None:
                    self.emit(f"if ({condition.code}) {{")
                self.emit(f"if (!{first}) gw_msg_text(ctx, {c_string(part.separator)});")
                self.emit(f"{first} = 0;")
                self.message_part(item)
                if condition is not None:
                    self.emit("}")
            return
        if isinstance(part, Vector):  # as tuple_repr writes a 1-D array of known length
            self.emit('gw_msg_text(ctx, "array([");')
            with self.counting(part.length) as k:
                self.emit(f'if ({k}) gw_msg_text(ctx, ", ");')
                self.message_part(self.element(part, k))
            self.emit('gw_msg_text(ctx, "])");')
            return
        if isinstance(part, Scalar):
            part = (part, "", "")
        value, spec, conversion = part  # str and repr of a number are the same text
        if isinstance(value, (Text, Word)):  # repr quotes it, as Python does plain ASCII text
            quote = 'gw_msg_text(ctx, "\'");' if conversion == "r" else ""
            if isinstance(value, Text):
                code = value.code
            else:
                code = self.out.declare("char", "word", 128)
                self.emit(f"gw_word({value.text.code}, {value.index}, {code}, sizeof {code});")
            self.emit(f"{quote} gw_msg_text(ctx, {code}); {quote}".strip())
            return
        if value.ctype == "bool":
            self.emit(f"gw_msg_text(ctx, {value.code} ? \"True\" : \"False\");")
        elif value.ctype == "long":
            self.emit(f"gw_msg_long(ctx, {value.code});")
        elif not spec:
            self.emit(f"gw_msg_repr(ctx, {value.code});")
        elif spec[-1] in _FORMATS and spec[:-1].lstrip(".").isdigit() | (spec[:-1] == ""):
            self.emit(f"gw_msg_format(ctx, \"%{spec}\", {value.code});")
        else:
            raise self.error(f"the format spec {spec!r} is not translated")

    # -- comprehensions -----------------------------------------------------------------
    def expr_DictComp(self, node):
        items = {}
        for _ in self.comprehension(node.generators):
            key = self.expr(node.key)
            if not isinstance(key, Const):
                raise self.error("a dict key must be known when the C is written")
            items[key.value] = self.expr(node.value)
        return Dict(items)

    def expr_ListComp(self, node):
        """The items; under a condition known at run time only (a mask, an ``if``), each item
        is (condition, item), which only str.join takes. Over a run-time sequence (words, an
        array) a run-time array (vectors.py)."""
        first = node.generators[0]
        sequence = self.expr(first.iter)  # Python evaluates it in the enclosing scope
        if isinstance(sequence, (Words, Vector)):
            if len(node.generators) > 1 or first.ifs:
                raise self.error("a comprehension over a run-time sequence is translated with "
                                 "one for and no if only")
            outer = self.frame
            self.frame = Frame(self, outer.node, outer.path, outer.globals, parent=outer)
            self.frame.owner = outer.owner
            try:
                if isinstance(sequence, Words):
                    return self.vector_of_words(sequence, first.target, node.elt)
                return self.vector_map(lambda v: self._element(first.target, v, node.elt),
                                       sequence)
            finally:
                self.frame = outer
        items = []
        for when in self.comprehension(node.generators, sequence):
            item = self.expr(node.elt)
            items.append(item if when is None else (when, item))
        return Tuple(items)

    expr_GeneratorExp = expr_ListComp

    def _element(self, target, value, element):
        self.assign(target, value)
        return self.expr(element)

    def comprehension(self, generators, first=None):
        """Bind each combination of the generators' items in turn (unrolled), in the
        comprehension's own scope; ``first``: the first generator's sequence, evaluated."""
        outer = self.frame
        self.frame = Frame(self, outer.node, outer.path, outer.globals, parent=outer)
        self.frame.owner = outer.owner
        try:
            yield from self._combinations(generators, first=first)
        finally:
            self.frame = outer

    def _combinations(self, generators, when=None, first=None):
        """Bind each item in turn; yields the run-time condition of the combination (a bool
        Scalar: its mask and ``if`` clauses that are not known when the C is written) or None."""
        sequence = self.expr(generators[0].iter) if first is None else first
        first, rest = generators[0], generators[1:]
        if isinstance(sequence, Masked):
            pairs = list(zip(sequence.items, sequence.mask))
        else:
            pairs = [(item, Const(True)) for item in self.iterate(sequence)]
        for item, mask in pairs:
            self.assign(first.target, item)
            conditions = [mask, *(self.truth(self.expr(c)) for c in first.ifs)]
            if any(isinstance(c, Const) and not c.value for c in conditions):
                continue
            codes = [c.code for c in conditions if not isinstance(c, Const)]
            if when is not None:
                codes.insert(0, when.code)
            condition = Scalar("bool", "(" + " && ".join(codes) + ")") if codes else None
            if rest:
                yield from self._combinations(rest, condition)
            else:
                yield condition


def _is_tuple(value) -> bool:
    return type(value) is Tuple or (isinstance(value, Const) and isinstance(value.value, tuple))


def c_string(text: str) -> str:
    """A C string literal of ``text``."""
    escaped = "".join(c if c.isprintable() and c not in '"\\' else f"\\{ord(c):03o}"
                      for c in text)
    return f'"{escaped}"'


def _numbers(*values) -> bool:
    return all(isinstance(v, Scalar) or (isinstance(v, Const) and is_number(v.value))
               for v in values)


def _either(condition: str, first, second):
    """The truth of a Choice from the truths of its sides."""
    if isinstance(first, Const) and isinstance(second, Const):
        if first.value == second.value:
            return Const(first.value)
        return Scalar("bool", condition if first.value else f"(!{condition})")
    a, b = (f.code if isinstance(f, Scalar) else str(int(bool(f.value))) for f in (first, second))
    return Scalar("bool", f"({condition} ? {a} : {b})")


def _identical(a, b):
    """Whether ``a is b`` when that is known: None is only None, a number never an object."""
    if isinstance(a, Const) and isinstance(b, Const):
        return a.value is b.value
    if isinstance(a, Const) and a.value is None or isinstance(b, Const) and b.value is None:
        return False
    if isinstance(a, Obj) and isinstance(b, Obj):
        return a is b
    return None


__all__ = ["Expressions", "c_string", "literal"]
