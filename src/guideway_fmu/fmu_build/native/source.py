"""The syntax tree of a Python function, found in its module's parsed source."""
from __future__ import annotations

import ast
import functools
import inspect


class TranslationError(Exception):
    """The Python cannot be written as C: the message names the file, line and construct."""


class MissingAttribute(TranslationError):
    """The attribute does not exist (Python would raise AttributeError): getattr's default."""


@functools.cache
def module_tree(path: str) -> ast.Module:
    with open(path, encoding="utf-8") as handle:
        return ast.parse(handle.read(), path)


def definition(function) -> tuple[ast.AST, str]:
    """(the FunctionDef or Lambda node of ``function``, its file)."""
    function = inspect.unwrap(function)
    code = function.__code__
    path = inspect.getsourcefile(function)
    if path is None:
        raise TranslationError(f"{function.__qualname__}: no source to translate")
    name = code.co_name
    for node in ast.walk(module_tree(path)):
        if isinstance(node, (ast.FunctionDef, ast.Lambda)):
            first = min([node.lineno] + [d.lineno for d in getattr(node, "decorator_list", [])])
            if first == code.co_firstlineno and (
                    isinstance(node, ast.Lambda) if name == "<lambda>" else node.name == name):
                return node, path
    raise TranslationError(f"{path}:{code.co_firstlineno}: the source of "
                           f"{function.__qualname__} was not found")


def returns(node: ast.AST) -> list[ast.Return]:
    """The return statements of a function body, those of nested functions left out."""
    found, stack = [], list(node.body) if isinstance(node.body, list) else []
    while stack:
        child = stack.pop()
        if isinstance(child, ast.Return):
            found.append(child)
        if not isinstance(child, (ast.FunctionDef, ast.Lambda, ast.ClassDef)):
            stack.extend(ast.iter_child_nodes(child))
    return found


def assigned_names(statements: list[ast.stmt]) -> set[str]:
    """Names a block of statements binds (nested functions' own names left out)."""
    names, stack = set(), list(statements)
    while stack:
        child = stack.pop()
        if isinstance(child, ast.Name) and isinstance(child.ctx, ast.Store):
            names.add(child.id)
        if isinstance(child, ast.FunctionDef):
            names.add(child.name)
            continue
        if not isinstance(child, (ast.Lambda, ast.ClassDef)):
            stack.extend(ast.iter_child_nodes(child))
    return names
