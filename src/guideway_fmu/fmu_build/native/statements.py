"""Statements of the translated subset: assignment, if, for, while, return, raise, nested def."""
from __future__ import annotations

import ast

from .source import assigned_names
from .translate import Frame, _Definition
from .values import (
    Choice,
    Const,
    Dict,
    Func,
    Message,
    Obj,
    Scalar,
    Tuple,
    describe,
    is_number,
)


class Statements:
    """Mixin of the translator (translate.TranslatorCore)."""

    def block(self, statements: list[ast.stmt]) -> None:
        """Translate ``statements`` up to one that always leaves (a return, raise, break or
        continue, also inside a branch decided when the C is written): what follows it never
        runs, and may not even translate (it may be written for another law). ``self.left``
        tells the caller; a run-time branch, loop or call clears it."""
        for statement in statements:
            self.statement(statement)
            if self.left:
                return

    def statement(self, node: ast.stmt) -> None:
        outer, self.node = self.node, node
        try:
            handler = getattr(self, f"stmt_{type(node).__name__}", None)
            if handler is None:
                raise self.error(f"the statement {type(node).__name__} is not translated")
            handler(node)
        finally:
            self.node = outer

    def stmt_Expr(self, node):
        if not (isinstance(node.value, ast.Constant) and isinstance(node.value.value, str)):
            self.expr(node.value)

    def stmt_Pass(self, node):
        pass

    def stmt_Assign(self, node):
        value = self.expr(node.value)
        for target in node.targets:
            self.assign(target, value)

    def stmt_AnnAssign(self, node):
        if node.value is not None:
            self.assign(node.target, self.expr(node.value))

    def stmt_AugAssign(self, node):
        current = self.expr(ast.Name(node.target.id, ast.Load())) if isinstance(
            node.target, ast.Name) else self.expr(_load(node.target))
        self.assign(node.target, self.binary(node.op, current, self.expr(node.value)))

    def assign(self, target, value) -> None:
        if isinstance(target, ast.Name):
            self.bind(target.id, value)
        elif isinstance(target, (ast.Tuple, ast.List)):
            items = list(self.iterate(value))
            if len(items) != len(target.elts):
                raise self.error(f"cannot unpack {len(items)} values into {len(target.elts)}")
            for element, item in zip(target.elts, items):
                self.assign(element, item)
        elif isinstance(target, ast.Attribute):
            obj = self.expr(target.value)
            if not isinstance(obj, Obj):
                raise self.error(f"cannot set attribute {target.attr} of {describe(obj)}")
            self.set_field(obj, target.attr, value)
        elif isinstance(target, ast.Subscript):
            container, key = self.expr(target.value), self.expr(target.slice)
            if isinstance(container, Dict) and isinstance(key, Const):
                current = container.items.get(key.value)
                if current is not None and isinstance(current, Scalar) and current.owner is container:
                    self.store(current, value, f"[{key.value!r}]")
                else:
                    container.items[key.value] = self.variable(value, container)
            else:
                raise self.error(f"item assignment into {describe(container)} is not translated")
        else:
            raise self.error(f"assignment to {type(target).__name__} is not translated")

    def stmt_Return(self, node):
        self.returned(self.expr(node.value) if node.value is not None else Const(None))
        self.left = True

    def stmt_Raise(self, node):
        if node.exc is None:
            raise self.error("a bare raise is not translated")
        exc = self.expr(node.exc)
        if isinstance(exc, Const) and isinstance(exc.value, type):
            exc = self.construct(exc.value, [], {})
        if not (isinstance(exc, Obj) and issubclass(exc.cls, BaseException)):
            raise self.error(f"raise of {describe(exc)}")
        message = exc.fields["message"]
        parts = message.parts if isinstance(message, Message) else [message]
        self.fail(parts, exc.cls)
        self.left = True

    def stmt_FunctionDef(self, node):
        if node.decorator_list:
            raise self.error(f"decorated nested function {node.name} is not translated")
        defaults = self.argument_defaults(node.args)
        definition_ = _Definition(node, self.frame.path, self.frame.globals, None, {},
                                  self.frame.owner, defaults)
        self.frame.locals[node.name] = Func(definition_, None, self.frame)

    def argument_defaults(self, arguments: ast.arguments) -> dict:
        positional = arguments.posonlyargs + arguments.args
        values = {a.arg: self.expr(d) for a, d in
                  zip(positional[len(positional) - len(arguments.defaults):], arguments.defaults)}
        values.update({a.arg: self.expr(d) for a, d in zip(arguments.kwonlyargs,
                                                           arguments.kw_defaults) if d is not None})
        return values

    # -- control flow -------------------------------------------------------------------
    def stmt_If(self, node):
        test = self.truth(self.expr(node.test))
        if isinstance(test, Const):
            self.block(node.body if test.value else node.orelse)
            return
        self.branches(test.code, lambda: self.block(node.body), lambda: self.block(node.orelse))

    def choose(self, condition: str, first, second):
        """The value of ``first()`` if the C ``condition`` holds, else of ``second()``."""
        name = self.fresh("$choice")
        self.branches(condition, lambda: self.bind(name, first()),
                      lambda: self.bind(name, second()))
        return self.frame.locals.pop(name)

    def branches(self, condition: str, first, second) -> None:
        """``if (condition) first(); else second();`` with the names either binds merged into
        the same variables, or into a Choice where their structures differ (translate.py
        module doc)."""
        frame = self.frame
        flag = self.out.declare("bool", "cond")
        self.emit(f"{flag} = {condition};")
        condition = flag
        before = dict(frame.locals)
        previous = self.out.capture()
        first()
        self.left = False
        after_first, frame.locals = frame.locals, dict(before)
        lines_first = self.out.capture()
        second()
        self.left = False
        after_second = frame.locals
        lines_second = self.out.restore(previous)
        merged = {}
        for name in set(after_first) | set(after_second):
            a, b = after_first.get(name), after_second.get(name)
            if a is b or b is None or a is None:
                merged[name] = a if b is None else b
                continue
            if isinstance(a, Const) and isinstance(b, Const) and (
                    a.value is b.value or (type(a.value) is type(b.value) and a.value == b.value)):
                merged[name] = a
                continue
            merged[name] = self.merge(name, a, b, lines_first, lines_second, condition)
        frame.locals = merged
        self.emit(f"if ({condition}) {{")
        self.out.lines.extend("    " + line for line in lines_first)
        if lines_second:
            self.emit("} else {")
            self.out.lines.extend("    " + line for line in lines_second)
        self.emit("}")

    def merge(self, name, a, b, lines_first, lines_second, condition):
        """One binding of ``name`` for both arms: variables both arms store into, or a Choice
        when the two structures differ."""
        if not self._fits(a, b) or isinstance(a, (Obj, Func, Choice)):
            return Choice(condition, a, b)
        frame = self.frame
        target = a if self.owned(a, frame) and self._fits(a, b) else None
        previous = self.out.capture()
        if target is None:
            target = self.variable(a, frame)
        self.out.lines, first_extra = [], self.out.lines
        self.store(target, b, name)
        second_extra = self.out.restore(previous)
        lines_first.extend(first_extra)
        lines_second.extend(second_extra)
        return target

    def stmt_While(self, node):
        if node.orelse:
            raise self.error("while ... else is not translated")
        self.loop_carried(node.body + [ast.Expr(node.test)])
        label = self.fresh("while")
        self.emit(f"for (;;) {{ /* {label} */")
        self.out.depth += 1
        test = self.truth(self.expr(node.test))
        self.emit(f"if (!({test.code if isinstance(test, Scalar) else int(bool(test.value))})) break;")
        self.block(node.body)
        self.left = False
        self.out.depth -= 1
        self.emit("}")

    def stmt_For(self, node):
        if node.orelse:
            raise self.error("for ... else is not translated")
        iterable = node.iter
        if isinstance(iterable, ast.Call) and isinstance(iterable.func, ast.Name) and \
                iterable.func.id == "range" and not iterable.keywords:
            bounds = [self.expr(a) for a in iterable.args]
            if any(isinstance(b, Scalar) for b in bounds) or (
                    len(bounds) < 3 and len(range(*(b.value for b in bounds))) > UNROLLED):
                return self.counted_loop(node, bounds)
        for item in list(self.iterate(self.expr(iterable))):
            if _breaks(node.body):
                raise self.error("break or continue in a loop over a constant sequence")
            self.assign(node.target, item)
            self.block(node.body)
            if self.left:  # a return or raise: no further pass runs
                return

    def counted_loop(self, node, bounds) -> None:
        if not isinstance(node.target, ast.Name):
            raise self.error("a counted loop needs one loop variable")
        start, stop = (bounds if len(bounds) == 2 else [Const(0), bounds[0]])[:2]
        if len(bounds) == 3:
            raise self.error("range with a step is not translated in a counted loop")
        self.loop_carried(node.body)
        counter = self.out.declare("long", node.target.id)
        start, stop = self.scalar(start), self.scalar(stop)
        limit = self.out.declare("long", "stop")
        self.emit(f"{limit} = {stop.code};")
        self.emit(f"for ({counter} = {start.code}; {counter} < {limit}; ++{counter}) {{")
        self.out.depth += 1
        self.frame.locals[node.target.id] = Scalar("long", counter)
        self.block(node.body)
        self.left = False
        self.out.depth -= 1
        self.emit("}")

    def loop_carried(self, body) -> None:
        """Give the names a loop body assigns, already bound, variables of this frame, so
        that every iteration reads what the one before stored."""
        frame = self.frame
        for name in assigned_names(body):
            value = frame.locals.get(name)
            if value is None or isinstance(value, (Obj, Func, Message, Choice)) or (
                    isinstance(value, Const) and not is_number(value.value)):
                continue
            if not self.owned(value, frame):
                frame.locals[name] = self.variable(value, frame)
            frame.carried.add(name)

    def stmt_Break(self, node):
        self.emit("break;")
        self.left = True

    def stmt_Continue(self, node):
        self.emit("continue;")
        self.left = True

    def stmt_With(self, node):
        for item in node.items:  # np.errstate: C arithmetic raises no floating-point errors
            if item.optional_vars is not None:
                raise self.error("with ... as is not translated")
        self.block(node.body)

    def stmt_Assert(self, node):
        pass  # asserts state what the code already guarantees; python -O drops them too

    def fail(self, parts: list, cls: type = ValueError) -> None:
        """Raise ``cls`` with the message ``parts``: written into the context, then on to the
        innermost handler of a try statement that catches it, else out by the failure exit (the
        message then starts with the class's name unless it is ValueError or RuntimeError, as
        base._report words it)."""
        target = next((label for handlers in reversed(self.catching)
                       for classes, label in handlers if issubclass(cls, classes)), None)
        if target is None and cls.__name__ not in ("ValueError", "RuntimeError"):
            parts = [Const(f"{cls.__name__}: "), *parts]
        self.emit("gw_msg_clear(ctx);")
        for part in parts:
            self.message_part(part)
        self.emit(f"goto {target or 'gw_fail'};")

    def stmt_Try(self, node):
        """try/except whose handlers leave (raise or return): a failure in the body that a
        handler catches goes to it (:meth:`fail`), exceptions being known where raised."""
        if node.orelse or node.finalbody:
            raise self.error("try ... else or finally is not translated")
        handlers = []
        for handler in node.handlers:
            caught = self.expr(handler.type) if handler.type is not None else Const(Exception)
            classes = tuple(c.value for c in (caught.items if isinstance(caught, Tuple)
                                              else [caught]) if isinstance(c, Const))
            if handler.name or not classes or not all(isinstance(c, type) for c in classes):
                raise self.error("an except clause is translated with exception classes and no "
                                 "name only")
            handlers.append((classes, self.fresh("caught")))
        done = self.fresh("tried")
        self.catching.append(handlers)
        try:
            self.block(node.body)
        finally:
            self.catching.pop()
        self.left = False
        self.emit(f"goto {done};")
        for handler, (_, label) in zip(node.handlers, handlers):
            self.emit(f"{label}: ;")
            before = dict(self.frame.locals)
            self.block(handler.body)
            if not self.left:
                raise self.error("an except clause that does not raise or return is not "
                                 "translated")
            self.left = False
            self.frame.locals = before
        self.emit(f"{done}: ;")


#: a for loop over a range known when the C is written is unrolled up to this many passes (its
#: counter may index a tuple), and a C loop beyond (a solver's iteration limit)
UNROLLED = 16


def _load(node):
    copy = ast.parse(ast.unparse(node), mode="eval").body
    return ast.copy_location(copy, node)


def _breaks(body) -> bool:
    for child in body:
        for node in ast.walk(child):
            if isinstance(node, (ast.Break, ast.Continue)):
                return True
    return False


__all__ = ["Frame", "Statements"]
