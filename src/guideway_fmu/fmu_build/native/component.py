"""A component's C unit: its instance struct and its methods translated from the Python edition.

The instance (``self``) is typed by example: the component is instantiated with its start
values and its model built, and what it holds then fixes the struct: each parameter and input
(Real: double, Integer: long, Boolean: bool), each ``internal_state`` attribute and the model
``build_model`` returns, flattened to its numbers. Strings, None, functions and classes the
model holds are part of its shape, fixed in the C: a parameter value that would build a model of
another shape is refused when the C is written (a String parameter that selects a law is not
translated yet). Other instance attributes (the lists base.py keeps of inputs) are constants.

The methods translated are base.py's services as the component defines or inherits them:
``build_model``, ``check_inputs``, ``initialise``, ``advance``, ``evaluate`` and
``setup_experiment``; ``self.model()`` is the built model and ``self.parameter_values()`` the
parameters by name, the two services base.py gives from FMI state the C layer keeps.
"""
from __future__ import annotations

import uuid

import numpy as np

from ...components.base import GuidewaySlave
from ...components.runtime import Fmi2Causality, Fmi2Slave
from .expressions import Expressions
from .intrinsics import table
from .source import TranslationError
from .statements import Statements
from .translate import TranslatorCore, _is_object, from_python, func_of
from .values import Array, Const, Dict, Obj, Scalar, Tuple, literal

_C_TYPES = {"Real": "double", "Integer": "long", "Boolean": "bool"}
_TYPE_CODES = {"Real": "GW_REAL", "Integer": "GW_INTEGER", "Boolean": "GW_BOOLEAN"}
_CAUSALITY_CODES = {Fmi2Causality.parameter: "GW_PARAMETER", Fmi2Causality.input: "GW_INPUT",
                    Fmi2Causality.output: "GW_OUTPUT"}


class Translator(Statements, Expressions, TranslatorCore):
    """The translator with its statements and expressions."""


class Unit:
    """The C of one component class (module doc); ``text`` is the unit, ``guid`` its GUID."""

    def __init__(self, cls: type[GuidewaySlave], guid: str | None = None):
        self.cls, self.guid = cls, guid or str(uuid.uuid4())
        self.example = cls(instance_name="native", resources=None)
        self.example.model()
        self.fields: list[tuple[str, str, str]] = []  # (C type, field, default C literal)
        self.self = Obj(cls, {})
        self.variables = list(self.example.vars.values())
        for variable in self.variables:
            kind = type(variable).__name__
            if variable.causality == Fmi2Causality.output:
                continue
            if kind not in _C_TYPES:
                raise TranslationError(f"{cls.__name__}: the {kind} variable {variable.name} "
                                       "is not translated yet")
            self.self.fields[variable.name] = self.field(
                _C_TYPES[kind], variable.name, getattr(self.example, variable.name))
        for name in cls.internal_state:
            self.self.fields[name] = self.layout(getattr(self.example, name), name)
        self.self.fields["_model"] = self.layout(self.example._model, "model")
        for name, value in vars(self.example).items():
            if name not in self.self.fields and name != "vars":
                self.self.fields[name] = from_python(value) if not _is_object(value) else \
                    Const(value)
        self.outputs = [v.name for v in self.variables if v.causality == Fmi2Causality.output]

    # -- the instance struct ------------------------------------------------------------
    def field(self, ctype: str, hint: str, example) -> Scalar:
        name = "".join(c if c.isalnum() else "_" for c in hint)
        taken = {f[1] for f in self.fields}
        unique, k = name, 1
        while unique in taken:
            k += 1
            unique = f"{name}_{k}"
        value = example.item() if isinstance(example, (np.generic, np.ndarray)) else example
        default = ("1" if value else "0") if ctype == "bool" else \
            f"{int(value)}L" if ctype == "long" else literal(float(value))
        self.fields.append((ctype, unique, default))
        return Scalar(ctype, f"s->{unique}", self.self)

    def layout(self, value, path: str):
        """The struct fields holding a value of ``value``'s shape (module doc)."""
        if isinstance(value, np.ndarray) and value.ndim == 0:
            value = value.item()
        if isinstance(value, (bool, np.bool_)):
            return self.field("bool", path, value)
        if isinstance(value, (int, np.integer)):
            return self.field("long", path, value)
        if isinstance(value, (float, np.floating)):
            return self.field("double", path, value)
        if isinstance(value, (tuple, list)):
            return Tuple([self.layout(v, f"{path}_{i}") for i, v in enumerate(value)])
        if isinstance(value, np.ndarray) and value.ndim == 1 and value.dtype.kind in "fib":
            return Array([self.layout(v, f"{path}_{i}") for i, v in enumerate(value)])
        if isinstance(value, dict) and all(isinstance(k, str) for k in value):
            return Dict({k: self.layout(v, f"{path}_{k}") for k, v in value.items()})
        if _is_object(value):
            return Obj(type(value), {k: self.layout(v, f"{path}_{k}")
                                     for k, v in vars(value).items()})
        if callable(value) and getattr(value, "__closure__", None):
            return func_of(value, cell_value=lambda v, name: self.layout(v, f"{path}_{name}"))
        if isinstance(value, np.ndarray):
            raise TranslationError(f"{self.cls.__name__}: the {value.ndim}-dimensional array "
                                   f"{path} is not translated yet")
        return Const(value)

    # -- the translated methods ---------------------------------------------------------
    def translator(self) -> Translator:
        methods = {(GuidewaySlave, "model"): lambda tr, obj, a, k: obj.fields["_model"],
                   (GuidewaySlave, "parameter_values"): self._parameter_values}
        return Translator(table(), methods)

    def _parameter_values(self, tr, obj, args, kwargs):
        return Dict({v.name: obj.fields[v.name] for v in self.variables
                     if v.causality == Fmi2Causality.parameter})

    def entry(self, name: str, method: str, parameters: list[str], finish=None,
              extra: str = "") -> str:
        """The C function ``name`` running ``self.method(*parameters)`` (double arguments by
        C name); ``finish(tr, value)`` writes what the C does with the returned value,
        ``extra`` declares its further C parameters."""
        tr = self.translator()
        overridden = getattr(self.cls, method) is not getattr(Fmi2Slave, method, None)
        if overridden:
            bound = tr.attribute(self.self, method)
            value = tr.call(bound, [Scalar("double", p) for p in parameters], {})
            if finish is not None:
                finish(tr, value)
        arguments = "".join(f", double {p}" for p in parameters) + extra
        body = "\n".join(tr.out.declarations + tr.out.lines)
        return (f"static int {name}(gw_ctx *ctx, gw_self *s{arguments}) {{\n"
                f"    (void)ctx; (void)s;{''.join(f' (void){p};' for p in parameters)}\n"
                f"{body}\n    return 0;\n    goto gw_fail;\ngw_fail:\n    return 1;\n}}\n")

    def _store_model(self, tr, value):
        tr.store(self.self.fields["_model"], value, "the model")

    def _store_outputs(self, tr, value):
        if not isinstance(value, Dict):
            raise TranslationError(f"{self.cls.__name__}.evaluate must return a dict, "
                                   f"not {type(value).__name__}")
        for i, name in enumerate(self.outputs):
            item = value.items.get(name, Const(0.0))
            tr.emit(f"out[{i}] = {tr.scalar(item).code};")

    @property
    def text(self) -> str:
        entries = [
            self.entry("gw_build", "build_model", [], self._store_model),
            self.entry("gw_check_inputs", "check_inputs", []),
            self.entry("gw_initialise", "initialise", []),
            self.entry("gw_advance", "advance", ["t", "h"]),
            self.entry("gw_evaluate", "evaluate", [], self._store_outputs, ", double *out"),
            self.entry("gw_setup_experiment", "setup_experiment", ["start", "stop", "tolerance"]),
        ]
        struct = "\n".join(f"    {ctype} {name};" for ctype, name, _ in self.fields)
        defaults = "\n".join(f"    s->{name} = {default};" for _, name, default in self.fields)
        rows = []
        for variable in self.variables:
            kind = type(variable).__name__
            if variable.causality == Fmi2Causality.output:
                rows.append(f"    {{{variable.value_reference}, GW_REAL, GW_OUTPUT, 0, "
                            f"{self.outputs.index(variable.name)}}},")
            else:
                field = self.self.fields[variable.name].code[3:]
                rows.append(f"    {{{variable.value_reference}, {_TYPE_CODES[kind]}, "
                            f"{_CAUSALITY_CODES[variable.causality]}, "
                            f"offsetof(gw_self, {field}), -1}},")
        names = ", ".join(f'"{n}"' for n in self.outputs) or "0"
        return "\n".join([
            (f"/* {self.cls.__name__}: translated by guideway_fmu.fmu_build.native from "
             f"{self.cls.__module__} (do not edit) */"),
            '#include "gw_runtime.h"',
            f'#define GW_CLASS "{self.cls.__name__}"',
            f'#define GW_GUID "{{{self.guid}}}"',
            f"#define GW_N_OUTPUTS {len(self.outputs)}",
            f"#define GW_N_VARIABLES {len(self.variables)}",
            f"typedef struct {{\n{struct}\n}} gw_self;",
            f"static const char *const gw_output_names[] = {{{names}}};",
            *entries,
            f"static void gw_defaults(gw_self *s) {{\n{defaults}\n}}",
            '#include "fmi2_slave.c"',
            "static const gw_variable gw_variables[] = {\n" + "\n".join(rows) + "\n};",
        ])
