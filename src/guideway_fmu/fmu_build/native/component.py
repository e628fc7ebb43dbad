"""A component's C unit: its instance struct and its methods translated from the Python edition.

The instance (``self``) is typed by example: the component is instantiated with its start
values and its model built, and what it holds then fixes the struct: each parameter and input
(Real: double, Integer: long, Boolean: bool), each ``internal_state`` attribute and the model
``build_model`` returns, flattened to its numbers. Strings, None, functions and classes the
model holds are part of its shape, fixed in the C. Other instance attributes (the lists base.py
keeps of inputs) are constants. A String parameter is kept as text (values.Text): the physics may
read numbers from its words, as many as its start value has.

A String parameter declared with ``choices`` (base.py: a law chosen by name) makes one variant
per choice: the component built with that value, its model laid out in a struct of its own
(``s->v<k>``) and its methods translated with the value as a constant; the parameters, inputs
and internal state stay shared. The C dispatches on the value at run time; a value outside the
choices is refused with base.py's sentence, and a choice whose law the translator refuses (it
reads a file, say) is refused at run time naming the reason, so the other laws stay native.

The methods translated are base.py's services as the component defines or inherits them:
``build_model``, ``check_inputs``, ``initialise``, ``advance``, ``evaluate`` and
``setup_experiment``; ``self.model()`` is the built model and ``self.parameter_values()`` the
parameters by name, the two services base.py gives from FMI state the C layer keeps.
"""
from __future__ import annotations

import uuid

import numpy as np

from ...components.base import CHOICE, NOT_FINITE, STEP_SIZE, GuidewaySlave
from ...components.runtime import Fmi2Causality, Fmi2Slave
from .expressions import Expressions, c_string
from .intrinsics import table
from .source import TranslationError
from .statements import Statements
from .translate import TranslatorCore, _is_object, from_python, func_of
from .values import (
    Array,
    Const,
    Dict,
    Obj,
    Scalar,
    Slot,
    Text,
    Tuple,
    Vector,
    literal,
    same_shape,
)
from .vectors import CAPACITY, Vectors

_C_TYPES = {"Real": "double", "Integer": "long", "Boolean": "bool"}
_TYPE_CODES = {"Real": "GW_REAL", "Integer": "GW_INTEGER", "Boolean": "GW_BOOLEAN"}
_CAUSALITY_CODES = {Fmi2Causality.parameter: "GW_PARAMETER", Fmi2Causality.input: "GW_INPUT",
                    Fmi2Causality.output: "GW_OUTPUT"}


class Translator(Statements, Expressions, Vectors, TranslatorCore):
    """The translator with its statements, expressions and run-time arrays."""


ENTRIES = (("gw_build", "build_model", []), ("gw_check_inputs", "check_inputs", []),
           ("gw_initialise", "initialise", []), ("gw_advance", "advance", ["t", "h"]),
           ("gw_evaluate", "evaluate", []),
           ("gw_setup_experiment", "setup_experiment", ["start", "stop", "tolerance"]))
#: bytes a String parameter's text holds, its end included: CAPACITY numbers written by
#: repr(float) (at most 24 characters and a space each) fit
STRING_SIZE = 8192


class Unit:
    """The C of one component class (module doc); ``text`` is the unit, ``guid`` its GUID,
    ``refused`` the choices translated to a run-time refusal (choice -> reason)."""

    def __init__(self, cls: type[GuidewaySlave], guid: str | None = None):
        self.cls, self.guid = cls, guid or str(uuid.uuid4())
        example = cls(instance_name="native", resources=None)
        self.variables = list(example.vars.values())
        self.outputs = [v.name for v in self.variables if v.causality == Fmi2Causality.output]
        self.fields: list[tuple[str, str, str]] = []  # (C type, field, default C literal)
        self.shared: dict = {}  # what every variant's self holds alike: variables, state
        self.selector: tuple[str, tuple[str, ...]] | None = None  # (parameter, its choices)
        self.owner: Obj | None = None  # the self whose methods assign the fields being laid out
        self.texts: list[tuple[str, str]] = []  # String variables: (name, start), kept as text
        for variable in self.variables:
            kind = type(variable).__name__
            if variable.causality == Fmi2Causality.output:
                continue
            if kind == "String":
                self.texts.append((variable.name, getattr(example, variable.name)))
                if example.choices(variable.name) and self.selector is None:
                    self.selector = (variable.name, example.choices(variable.name))
                else:
                    self.shared[variable.name] = Text(f"s->gw_text_{variable.name}",
                                                      variable.name)
                continue
            if kind not in _C_TYPES:
                raise TranslationError(f"{cls.__name__}: the {kind} variable {variable.name} "
                                       "is not translated yet")
            self.shared[variable.name] = self.field(
                self.fields, "s->", _C_TYPES[kind], variable.name, getattr(example, variable.name))
        for name in cls.internal_state:
            self.shared[name] = self.layout(self.fields, "s->", getattr(example, name), name)
        self.variants: list[tuple[str | None, list, dict | None]] = []  # (choice, fields, entries)
        self.refused: dict[str, str] = {}
        for k, choice in enumerate(self.selector[1] if self.selector else (None,)):
            self.variants.append(self._variant(k, choice))
        if all(entries is None for _, _, entries in self.variants):
            raise TranslationError(f"{cls.__name__}: no {self.selector[0]} is translated: "
                                   + "; ".join(f"{c}: {r}" for c, r in self.refused.items()))

    def _variant(self, k: int, choice: str | None) -> tuple[str | None, list, dict | None]:
        """(choice, its struct fields, its translated entries by C name) of the component built
        with the selector at ``choice`` (None: no selector); entries None when refused."""
        example = self.cls(instance_name="native", resources=None)
        fields: list[tuple[str, str, str]] = []
        prefix = "s->" if choice is None else f"s->v{k}."
        try:
            if choice is not None:
                setattr(example, self.selector[0], choice)
            example.model()
            obj = self.owner = Obj(self.cls, {})
            obj.fields.update({k: _owned_by(v, obj) for k, v in self.shared.items()})
            if choice is not None:
                obj.fields[self.selector[0]] = Const(choice)
            for name in self.cls.internal_state:  # shared, so every variant's is of one shape
                if not same_shape(self.layout([], "", getattr(example, name), name),
                                  self.shared[name]):
                    raise TranslationError(f"{self.cls.__name__}: the internal state {name} "
                                           f"differs in shape with {self.selector[0]} {choice!r}")
            obj.fields["_model"] = self.layout(fields, prefix, example._model, "model", slots=True)
            for name, value in vars(example).items():
                if name not in obj.fields and name != "vars":
                    obj.fields[name] = from_python(value) if not _is_object(value) else \
                        Const(value)
            return choice, fields, {f"{entry}_{k}": self.entry(f"{entry}_{k}", obj, method, args)
                                    for entry, method, args in ENTRIES}
        except (TranslationError, ValueError, OSError) as exc:
            if choice is None:
                raise
            self.refused[choice] = str(exc)
            return choice, [], None

    # -- the instance struct ------------------------------------------------------------
    def field(self, fields: list, prefix: str, ctype: str, hint: str, example) -> Scalar:
        """A new field of ``fields`` (reached as ``prefix`` + its name) holding ``example``,
        assignable by :attr:`owner` (the variant's ``self``)."""
        name = "".join(c if c.isalnum() else "_" for c in hint)
        taken = {f[1] for f in fields}
        unique, k = name, 1
        while unique in taken:
            k += 1
            unique = f"{name}_{k}"
        value = example.item() if isinstance(example, (np.generic, np.ndarray)) else example
        default = ("1" if value else "0") if ctype == "bool" else \
            f"{int(value)}L" if ctype == "long" else literal(float(value))
        fields.append((ctype, unique, default))
        return Scalar(ctype, f"{prefix}{unique}", self.owner)

    def layout(self, fields: list, prefix: str, value, path: str, slots: bool = False):
        """The fields (added to ``fields``) holding a value of ``value``'s shape (module doc);
        ``slots``: a 1-D numpy array becomes a Slot, laid out for the first value stored (of
        its example's length, or a run-time array: vectors.py)."""
        def inner(v, p):
            return self.layout(fields, prefix, v, p, slots)

        if isinstance(value, np.ndarray) and value.ndim == 0:
            value = value.item()
        if isinstance(value, (bool, np.bool_)):
            return self.field(fields, prefix, "bool", path, value)
        if isinstance(value, (int, np.integer)):
            return self.field(fields, prefix, "long", path, value)
        if isinstance(value, (float, np.floating)):
            return self.field(fields, prefix, "double", path, value)
        if isinstance(value, (tuple, list)):
            return Tuple([inner(v, f"{path}_{i}") for i, v in enumerate(value)])
        if isinstance(value, np.ndarray) and value.ndim == 1 and value.dtype.kind in "fib":
            fixed = lambda: Array([inner(v, f"{path}_{i}") for i, v in enumerate(value)])  # noqa: E731
            if not slots:
                return fixed()
            owner = self.owner
            return Slot(value, lambda stored: self._vector_field(fields, prefix, path, owner)
                        if isinstance(stored, Vector) else fixed())
        if isinstance(value, dict) and all(isinstance(k, str) for k in value):
            return Dict({k: inner(v, f"{path}_{k}") for k, v in value.items()})
        if _is_object(value):
            return Obj(type(value), {k: inner(v, f"{path}_{k}") for k, v in vars(value).items()})
        if callable(value) and getattr(value, "__closure__", None):
            return func_of(value, cell_value=lambda v, name: inner(v, f"{path}_{name}"))
        if isinstance(value, np.ndarray):
            raise TranslationError(f"{self.cls.__name__}: the {value.ndim}-dimensional array "
                                   f"{path} is not translated yet")
        return Const(value)

    def _vector_field(self, fields: list, prefix: str, hint: str, owner) -> Vector:
        """Struct fields of a run-time array: CAPACITY doubles and a length."""
        data = self.field(fields, prefix, "double", hint, 0.0)
        fields[-1] = (fields[-1][0], f"{fields[-1][1]}[{CAPACITY}]", None)
        length = self.field(fields, prefix, "long", f"{hint}_length", 0)
        return Vector("double", data.code, Scalar("long", length.code, owner))

    # -- the translated methods ---------------------------------------------------------
    def translator(self) -> Translator:
        methods = {(GuidewaySlave, "model"): lambda tr, obj, a, k: obj.fields["_model"],
                   (GuidewaySlave, "parameter_values"): self._parameter_values}
        return Translator(table(), methods)

    def _parameter_values(self, tr, obj, args, kwargs):
        return Dict({v.name: obj.fields[v.name] for v in self.variables
                     if v.causality == Fmi2Causality.parameter})

    def entry(self, name: str, obj: Obj, method: str, parameters: list[str]) -> str:
        """The C function ``name`` running ``obj.method(*parameters)`` (double arguments by C
        name); gw_build stores the model, gw_evaluate the outputs in ``out``."""
        tr = self.translator()
        value = None
        if getattr(self.cls, method) is not getattr(Fmi2Slave, method, None):  # overridden
            bound = tr.attribute(obj, method)
            value = tr.call(bound, [Scalar("double", p) for p in parameters], {})
        if method == "build_model" and value is not None:
            tr.store(obj.fields["_model"], value, "the model")
        if method == "evaluate":
            self._store_outputs(tr, value)
        arguments = "".join(f", double {p}" for p in parameters)
        arguments += ", double *out" if method == "evaluate" else ""
        body = tr.out.body()
        return (f"static int {name}(gw_ctx *ctx, gw_self *s{arguments}) {{\n"
                f"    (void)ctx; (void)s;{''.join(f' (void){p};' for p in parameters)}\n"
                f"{body}\n    return 0;\n    goto gw_fail;\ngw_fail:\n    return 1;\n}}\n")

    def _store_outputs(self, tr, value):
        if not isinstance(value, Dict):
            raise TranslationError(f"{self.cls.__name__}.evaluate must return a dict, "
                                   f"not {type(value).__name__}")
        for i, name in enumerate(self.outputs):
            item = value.items.get(name, Const(0.0))
            tr.emit(f"out[{i}] = {tr.scalar(item).code};")

    def _dispatch(self, entry: str, args: list[str]) -> str:
        """The C entry ``entry`` calling the variant the selector chose; an unknown choice (in
        base.py's words) or a refused one fails gw_build, and the other entries do nothing."""
        out = ", double *out" if entry == "gw_evaluate" else ""
        params = "".join(f", double {a}" for a in args) + out
        passed = "".join(f", {a}" for a in args) + (", out" if out else "")
        cases = [f"    case {k}: return {entry}_{k}(ctx, s{passed});"
                 for k, (_, _, entries) in enumerate(self.variants) if entries is not None]
        fallback = "    default: return 0;"
        if entry == "gw_build":
            name, choices = self.selector
            head, tail = CHOICE.format(name=name, choices=choices, value="@").split("'@'")
            cases += [f"    case {k}: gw_msg_clear(ctx); gw_msg_text(ctx, "
                      f"{c_string(self.refusal(choice))}); return 1;"
                      for k, (choice, _, entries) in enumerate(self.variants) if entries is None]
            fallback = (f"    default: gw_msg_clear(ctx); gw_msg_text(ctx, {c_string(head)}); "
                        "gw_msg_text(ctx, \"'\");\n        gw_msg_text(ctx, GW_SELECTOR(s)); "
                        f"gw_msg_text(ctx, \"'\"); gw_msg_text(ctx, {c_string(tail)}); return 1;")
        return (f"static int {entry}(gw_ctx *ctx, gw_self *s{params}) {{\n"
                "    switch (s->gw_choice) {\n" + "\n".join([*cases, fallback]) + "\n    }\n}\n")

    def refusal(self, choice: str) -> str:
        """What the native edition says of a ``choice`` it does not translate."""
        return (f"{self.selector[0]} {choice!r} is not in the native edition of "
                f"{self.cls.__name__} ({self.refused[choice]}); the python edition has it")

    @property
    def text(self) -> str:
        struct = [f"    {ctype} {name};" for ctype, name, _ in self.fields]
        defaults = [f"    s->{name} = {default};" for _, name, default in self.fields
                    if default is not None]
        entries: list[str] = []
        for k, (choice, fields, translated) in enumerate(self.variants):
            if choice is None:
                struct += [f"    {ctype} {name};" for ctype, name, _ in fields]
                defaults += [f"    s->{name} = {default};" for _, name, default in fields
                             if default is not None]
                entries += [text.replace(f"{entry}_0(", f"{entry}(", 1)
                            for entry, text in zip((e for e, _, _ in ENTRIES), translated.values())]
                continue
            if fields:
                struct.append("    struct {\n" + "\n".join(
                    f"        {ctype} {name};" for ctype, name, _ in fields) + f"\n    }} v{k};")
                defaults += [f"    s->v{k}.{name} = {default};" for _, name, default in fields
                             if default is not None]
            entries += list((translated or {}).values())
        rows = []
        for variable in self.variables:
            kind = type(variable).__name__
            if variable.causality == Fmi2Causality.output:
                rows.append(f"    {{{variable.value_reference}, GW_REAL, GW_OUTPUT, 0, "
                            f"{self.outputs.index(variable.name)}, {c_string(variable.name)}}},")
            elif kind == "String":
                rows.append(f"    {{{variable.value_reference}, GW_STRING, GW_PARAMETER, "
                            f"offsetof(gw_self, gw_text_{variable.name}), -1, "
                            f"{c_string(variable.name)}}},")
            else:
                field = self.shared[variable.name].code[3:]
                rows.append(f"    {{{variable.value_reference}, {_TYPE_CODES[kind]}, "
                            f"{_CAUSALITY_CODES[variable.causality]}, "
                            f"offsetof(gw_self, {field}), -1, {c_string(variable.name)}}},")
        names = ", ".join(f'"{n}"' for n in self.outputs) or "0"
        selector = [f"#define GW_STRING_SIZE {STRING_SIZE}"]
        struct += [f"    char gw_text_{name}[GW_STRING_SIZE];" for name, _ in self.texts]
        defaults += [f'    snprintf(s->gw_text_{name}, GW_STRING_SIZE, "%s", {c_string(start)});'
                     for name, start in self.texts]
        if self.selector:
            name, choices = self.selector
            struct.append("    long gw_choice;")
            defaults.append("    gw_choose(s);")
            entries += [self._dispatch(entry, args) for entry, _, args in ENTRIES]
            selector += [f"#define GW_N_CHOICES {len(choices)}",
                         f"#define GW_SELECTOR(s) ((s)->gw_text_{name})",
                         "static const char *const gw_choices[] = {"
                         + ", ".join(c_string(c) for c in choices) + "};"]
        return "\n".join([
            (f"/* {self.cls.__name__}: translated by guideway_fmu.fmu_build.native from "
             f"{self.cls.__module__} (do not edit) */"),
            '#include "gw_runtime.h"',
            f'#define GW_CLASS "{self.cls.__name__}"',
            f'#define GW_GUID "{{{self.guid}}}"',
            f"#define GW_N_OUTPUTS {len(self.outputs)}",
            f"#define GW_N_VARIABLES {len(self.variables)}",
            *_message_parts("GW_MSG_STEP_SIZE", STEP_SIZE, "step_size"),
            *_message_parts("GW_MSG_NOT_FINITE", NOT_FINITE, "outputs"),
            *selector,
            "typedef struct {\n" + "\n".join(struct) + "\n} gw_self;",
            f"static const char *const gw_output_names[] = {{{names}}};",
            *(GW_CHOOSE if self.selector else []),
            *entries,
            "static void gw_defaults(gw_self *s) {\n" + "\n".join(defaults) + "\n}",
            '#include "fmi2_slave.c"',
            "static const gw_variable gw_variables[] = {\n" + "\n".join(rows) + "\n};",
        ])


def _message_parts(macro: str, sentence: str, field: str) -> list[str]:
    """C macros ``macro``_HEAD and _TAIL: base.py's ``sentence`` before and after its one
    ``{field!r}``, which the C writes between them."""
    head, tail = sentence.split("{" + field + "!r}")
    return [f"#define {macro}_HEAD {c_string(head)}", f"#define {macro}_TAIL {c_string(tail)}"]


def _owned_by(value, owner: Obj):
    """``value`` with its C variables assignable by ``owner``."""
    if isinstance(value, Scalar):
        return Scalar(value.ctype, value.code, owner)
    if isinstance(value, Tuple):
        return type(value)([_owned_by(v, owner) for v in value.items])
    if isinstance(value, Dict):
        return Dict({k: _owned_by(v, owner) for k, v in value.items.items()})
    if isinstance(value, Obj):
        return Obj(value.cls, {k: _owned_by(v, owner) for k, v in value.fields.items()})
    return value


#: the index among the choices of the choosing String parameter's text, or -1
GW_CHOOSE = ["""static void gw_choose(gw_self *s) {
    long k;
    s->gw_choice = -1;
    for (k = 0; k < GW_N_CHOICES; ++k)
        if (strcmp(GW_SELECTOR(s), gw_choices[k]) == 0) s->gw_choice = k;
}"""]
