"""A Python function of numbers translated, compiled and loaded with ctypes, for the
translator's own tests: ``compiled(f, 2)(a, b)`` runs the C of ``f(a, b)``; a raise in ``f``
comes back as ValueError with the C's message."""
from __future__ import annotations

import ctypes
import shutil
import tempfile
from pathlib import Path

from guideway_fmu.fmu_build.native.build import HERE, compile_unit
from guideway_fmu.fmu_build.native.component import Translator
from guideway_fmu.fmu_build.native.intrinsics import table
from guideway_fmu.fmu_build.native.translate import func_of


def c_text(function, arity: int) -> str:
    """The C of ``entry(ctx, args, out)`` computing ``function(*args)`` into ``*out``."""
    from guideway_fmu.fmu_build.native.values import Scalar

    tr = Translator(table())
    value = tr.call(func_of(function), [Scalar("double", f"args[{i}]") for i in range(arity)], {})
    tr.emit(f"*out = {tr.scalar(value).code};")
    body = tr.out.body()
    return ('#include "gw_runtime.h"\n'
            "int entry(gw_ctx *ctx, const double *args, double *out) {\n"
            f"{body}\n    return 0;\n    goto gw_fail;\ngw_fail:\n    return 1;\n}}\n"
            "void repr(double x, char *out) { gw_repr(out, 40, x); }\n"
            "void release(gw_ctx *ctx) { free(ctx->scratch); }\n")


class _Context(ctypes.Structure):
    _fields_ = [("message", ctypes.c_char * 1024), ("length", ctypes.c_size_t),
                ("scratch", ctypes.c_void_p), ("scratch_size", ctypes.c_size_t)]


def compiled(function, arity: int):
    """``function`` of ``arity`` numbers as a compiled C function (module doc)."""
    folder = Path(tempfile.mkdtemp(prefix="native_translate_"))
    try:
        shutil.copy2(HERE / "gw_runtime.h", folder)
        unit = folder / "unit.c"
        unit.write_text(c_text(function, arity))
        library = ctypes.CDLL(str(compile_unit(unit, folder / "unit.so")))
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    entry = library.entry
    entry.argtypes = [ctypes.POINTER(_Context), ctypes.POINTER(ctypes.c_double),
                      ctypes.POINTER(ctypes.c_double)]

    def call(*args):
        context, out = _Context(), ctypes.c_double()
        failed = entry(ctypes.byref(context), (ctypes.c_double * arity)(*args), ctypes.byref(out))
        library.release(ctypes.byref(context))
        if failed:
            raise ValueError(context.message.decode())
        return out.value

    def repr_(x):
        text = ctypes.create_string_buffer(40)
        library.repr(ctypes.c_double(x), text)
        return text.value.decode()

    call.repr = repr_
    return call
