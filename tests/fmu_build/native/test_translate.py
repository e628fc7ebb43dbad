"""The translator on small functions written for the purpose: each compiled C function is
compared with the Python function it was translated from, on inputs that take every branch."""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pytest
import scipy.linalg
import scipy.optimize
import scipy.special
from compiled import compiled

from guideway_fmu.fmu_build.native.source import TranslationError


def loop_carried(x, n):
    total, step = 0.0, x
    for i in range(int(n)):
        total += step * i
        step = step / 2.0
    return total + step


def branches_merge(x, y):
    if x > y:
        a, b = x, 1.0
    elif x < 0.0:
        a = -x
        b = 2.0
    else:
        b = 3.0
        a = y
    return a * b


@dataclass(frozen=True)
class Spring:
    stiffness: float
    preload: float = 0.0

    def force(self, d):
        return self.preload + self.stiffness * max(d, 0.0)


def optional_object(x, k):
    spring = Spring(k) if k > 0.0 else None
    if spring is None:
        def law(d):
            return -d
    else:
        law = spring.force
    return law(x) + (spring.stiffness if spring is not None else 0.0)


def comprehension_scope(x, y):
    v = 10.0
    parts = {name: v * 2.0 for name, v in (("a", x), ("b", y))}
    return parts["a"] + parts["b"] + v


def raises_with_message(x, y):
    if not 0.0 <= x < math.inf:
        raise ValueError(f"x must be finite and >= 0, got {x!r} (y = {y:.3g})")
    return math.sqrt(x) + y


def arrays(x, y):
    z = np.array([x, y, x * y])
    w = np.exp(-np.abs(z) / np.array([1.0, 2.0, 4.0]))
    return float(np.sum(np.sign(z) * w))


def while_loop(x, tolerance):
    guess, count = max(x, 1.0), 0
    while abs(guess * guess - x) > tolerance * x and count < 100:
        guess = 0.5 * (guess + x / guess)
        count += 1
    return guess + 1e-3 * count


def run_time_arrays(x, n):
    nodes = np.linspace(-1.0, 2.0, int(n))
    values = np.sin(nodes) * x
    rising = ~(np.diff(values) <= 0.0)
    if not np.any(rising):
        return -1.0
    return (float(np.interp(0.3 * x, nodes, values)) + values[-1] + values[0] * 1e-3
            + float(np.all(np.isfinite(values))) + 1e-4 * len(nodes) + 1e-5 * nodes.size)


def known_count_arrays(x, y):
    nodes = np.linspace(x, y, 5)
    flat = np.linspace(x, x, 3)  # a zero step: numpy's other branch
    return float(np.interp(0.5 * (x + y), nodes, nodes ** 2)) + float(np.sum(flat)) + nodes[2]


def shapes_and_tuples(x, y):
    v = np.array([x, y])
    if v.shape != (2,) or (x, y) == (1.5, y) or v.ndim != 1:
        return -x
    return x + y


class Bearing:
    def __init__(self, radius):
        self.radius = radius

    @functools.cached_property
    def area(self):
        return math.pi * self.radius ** 2


@functools.lru_cache(maxsize=4)
def _scaled(k):
    return 2.0 * k


def cached(x, y):
    return Bearing(x).area + _scaled(y)


def caught(x, y):
    try:
        if x < 0.0:
            raise ValueError("negative")
        value = math.sqrt(x)
    except (ValueError, TypeError):
        raise ValueError(f"x must be >= 0, got {x!r}") from None
    return value + y


def masked_message(x, y):
    d = np.array([x, y, x + y])
    bad = ~(d > 0.0)
    if np.any(bad):
        raise ValueError(f"not positive: {', '.join(f'{v:.3g}' for v in d[bad])} ({(x, y)!r})")
    return float(np.sum(d))


def guarded(x, y):
    """Checks in the arm or operand Python does not evaluate must not fail."""
    return ((math.log(x) if x > 0.0 else -1.0) + (1.0 if x > 0.0 and math.sqrt(x) > y else 0.0)
            + (2.0 if x <= 0.0 or math.log(x) > y else 0.0) + (math.sqrt(-x) if x < 0.0 else x))


def _held_or_computed(held, x, flag):
    if flag > 0.0:
        return held
    return held * x


def held_or_computed(x, flag):
    """Branches that return an array held elsewhere and a computed one: the computed one must
    not be written into the held one (read again after the merge)."""
    held = np.arange(1, int(abs(flag)) + 3) * 1.0  # of run-time length
    out = _held_or_computed(held, x, flag)
    return float(out[0] + 10.0 * held[0])


def repeated_and_ranged(x, n):
    """np.repeat and np.tile by a run-time count, np.arange(start, stop), np.max, .min()."""
    count = int(n)
    values = np.tile(np.repeat(np.array([x, -x, 2.0 * x]), count), 2) + np.arange(1, 3 * count * 2 + 1)
    return float(np.max(values) - 3.0 * values.min() + np.sum(values))


def sliced_and_joined(x, n):
    """np.concatenate, slices of a run-time array with run-time bounds, np.dot, np.diag,
    np.outer and np.trace."""
    count = int(n)
    values = np.concatenate([np.arange(count) * x, np.array([1.0, -x])])
    head, tail = values[:count], values[count - 1:]
    matrix = np.diag(np.array([x, 2.0, 3.0])) + np.outer(np.array([1.0, x, 0.5]), np.array([x, 1.0, 2.0]))
    return float(np.dot(head, head) + 7.0 * np.sum(tail) + np.trace(matrix) + np.diag(matrix)[1]
                 + 3.0 * values[-count:][0] + tail.size)


def symmetric_eigenvalues(x, y):
    """scipy.linalg.eigh's eigenvalues of a symmetric 4 x 4 pair (a, b positive definite)."""
    a = np.array([[4.0, x, 0.5, 0.0], [x, 3.0, y, 0.1], [0.5, y, 2.0 + x, 0.2],
                  [0.0, 0.1, 0.2, 1.0]])
    b = np.diag(np.array([1.0, 2.0, 0.5, 3.0])) + 0.1 * np.outer(np.ones(4), np.ones(4))
    values = scipy.linalg.eigh(a, b, eigvals_only=True)
    return float(values[0] + 10.0 * values[1] + 100.0 * values[2] + 1000.0 * values[3])


def solved(x, y):
    """np.linalg.solve of a 3 x 3 system that needs row exchanges."""
    a = np.array([[1e-3 * x, 2.0, 1.0], [3.0, y, -1.0], [1.0, 1.0, 4.0 + x]])
    z = np.linalg.solve(a, np.array([1.0, x, y]))
    return float(z[0] + 10.0 * z[1] + 100.0 * z[2])


def elliptic(m, _):
    return float(scipy.special.ellipk(m) + 3.0 * scipy.special.ellipe(m))


def bracketed(x, y):
    """scipy.optimize.brentq with a closure, the iteration count and the converged flag."""
    root, info = scipy.optimize.brentq(lambda t: t**3 - x * t - y, -10.0, 10.0, xtol=1e-14,
                                       rtol=1e-14, maxiter=100, full_output=True, disp=False)
    return root if info.converged else math.nan


CASES = [(loop_carried, [(1.5, 0.0), (1.5, 1.0), (3.0, 7.0)]),
         (branches_merge, [(2.0, 1.0), (-2.0, 1.0), (0.5, 1.0)]),
         (optional_object, [(2e-6, 1e6), (2e-6, 0.0), (-1.0, 3.0)]),
         (comprehension_scope, [(1.0, 2.0), (-3.0, 0.25)]),
         (raises_with_message, [(4.0, 1.0), (0.0, -2.0)]),
         (arrays, [(0.3, -2.0), (0.0, 5.0)]),
         (while_loop, [(2.0, 1e-12), (1e6, 1e-9), (0.25, 1e-10)]),
         (run_time_arrays, [(1.0, 2.0), (2.5, 7.0), (-0.5, 40.0), (1.0, 1.0), (0.7, 256.0)]),
         (shapes_and_tuples, [(1.0, 2.0), (1.5, 2.0)]),
         (known_count_arrays, [(0.1, 0.7), (-3.0, 1e-3), (1e-300, 2e-300)]),
         (cached, [(0.5, 3.0)]),
         (caught, [(4.0, 1.0)]),
         (guarded, [(-1.0, 0.0), (0.0, 0.5), (4.0, 1.0), (4.0, 3.0)]),
         (held_or_computed, [(2.0, 1.0), (2.0, -1.0)]),
         (repeated_and_ranged, [(0.5, 1.0), (-2.0, 7.0)]),
         (sliced_and_joined, [(0.5, 1.0), (-2.0, 7.0), (3.0, 40.0)])]


@pytest.mark.parametrize("function, inputs, tolerance", [
    (solved, [(0.0, 1.0), (2.0, -3.0), (1e3, 1e-3)], 1e-13),  # LU's rounding against LAPACK's
    (symmetric_eigenvalues, [(0.0, 0.0), (1.0, -0.5), (-2.0, 1.5)], 1e-13),  # Jacobi's
    (elliptic, [(0.0, 0), (0.3, 0), (-2.0, 0), (0.9, 0), (1 - 1e-12, 0)], 1e-14),
    (bracketed, [(1.0, 0.5), (0.0, 8.0), (30.0, -1.0)], 1e-13)],  # Brent's iterates, to xtol
    ids=["solve", "eigh", "ellipk-ellipe", "brentq"])
def test_library_functions_agree_with_numpy_and_scipy_to_their_precision(function, inputs,
                                                                         tolerance):
    c = compiled(function, 2)
    for args in inputs:
        assert c(*args) == pytest.approx(function(*args), rel=tolerance, abs=0.0), args


def test_a_singular_solve_and_a_bracket_without_a_sign_change_fail_in_numpys_words():
    with pytest.raises(ValueError, match="LinAlgError: Singular matrix"):
        compiled(singular, 2)(1.0, 2.0)
    with pytest.raises(np.linalg.LinAlgError, match="Singular matrix"):
        singular(1.0, 2.0)
    with pytest.raises(ValueError, match="f\\(a\\) and f\\(b\\) must have different signs"):
        compiled(lambda_free_bracket, 2)(1.0, 2000.0)


def test_a_run_time_array_in_a_message_is_written_with_its_numbers():
    with pytest.raises(ValueError, match=r"^bad: array\(\[0\.0, 2\.5, 5\.0\]\)$"):
        compiled(listed_in_message, 2)(2.5, 3.0)


def listed_in_message(x, n):
    values = np.arange(int(n)) * x
    if n > 0:
        raise ValueError(f"bad: {values!r}")
    return x


def singular(x, y):
    return float(np.linalg.solve(np.array([[1.0, 2.0], [x, y]]), np.array([1.0, 1.0]))[0])


def lambda_free_bracket(x, y):
    return scipy.optimize.brentq(lambda t: t * t + x + y, -1.0, 1.0, disp=False)


@pytest.mark.parametrize("function, inputs", CASES, ids=[c[0].__name__ for c in CASES])
def test_compiled_function_returns_what_python_returns(function, inputs):
    c = compiled(function, 2)
    for args in inputs:
        assert c(*args) == pytest.approx(function(*args), rel=1e-15, abs=0.0), args


def test_raise_carries_the_python_message_word_for_word():
    c = compiled(raises_with_message, 2)
    for x, y in ((-1.0, 12345.678), (math.inf, 1e-7), (math.nan, 0.5)):
        with pytest.raises(ValueError) as python:
            raises_with_message(x, y)
        with pytest.raises(ValueError) as native:
            c(x, y)
        assert str(native.value) == str(python.value)


@pytest.mark.parametrize("x, y", [(-1.5, 2.0), (1.0, -3.25), (-1.0, -2.0), (1.0, -1.0)])
def test_a_message_lists_the_items_a_run_time_mask_selects_as_python_does(x, y):
    with pytest.raises(ValueError) as python:
        masked_message(x, y)
    with pytest.raises(ValueError) as native:
        compiled(masked_message, 2)(x, y)
    assert str(native.value) == str(python.value)


def math_errors(x, kind):
    if kind == 0.0:
        return math.sqrt(x)
    if kind == 1.0:
        return math.log(x)
    if kind == 2.0:
        return math.exp(x)
    if kind == 3.0:
        return float(int(x))
    return float(math.floor(x)) + np.sqrt(x)


@pytest.mark.filterwarnings("ignore:invalid value encountered in sqrt")
@pytest.mark.parametrize("x, kind", [(-1.0, 0.0), (0.0, 1.0), (-2.0, 1.0), (1000.0, 2.0),
                                     (math.inf, 3.0), (math.nan, 3.0), (math.inf, 4.0),
                                     (math.nan, 0.0), (math.inf, 2.0), (-4.0, 4.0)])
def test_math_fails_where_pythons_math_fails_in_its_words_and_numpy_does_not(x, kind):
    c = compiled(math_errors, 2)
    try:
        expected = math_errors(x, kind)
    except (ValueError, OverflowError) as exc:
        words = str(exc) if isinstance(exc, ValueError) else f"{type(exc).__name__}: {exc}"
        with pytest.raises(ValueError) as native:
            c(x, kind)
        assert str(native.value) == words
    else:
        assert c(x, kind) == pytest.approx(expected, nan_ok=True)


def test_an_exception_a_handler_catches_is_replaced_by_its_own_as_in_python():
    c = compiled(caught, 2)
    with pytest.raises(ValueError, match=r"^x must be >= 0, got -2\.0$"):
        c(-2.0, 1.0)


def test_a_run_time_array_longer_than_the_capacity_is_refused_naming_it():
    from guideway_fmu.fmu_build.native.vectors import CAPACITY
    c = compiled(run_time_arrays, 2)
    with pytest.raises(ValueError, match=f"an array of {CAPACITY + 1} numbers is longer than "
                                         f"the native edition holds \\({CAPACITY}\\)"):
        c(1.0, CAPACITY + 1.0)


def test_float_repr_matches_python_on_random_and_edge_doubles():
    repr_ = compiled(loop_carried, 2).repr
    rng = np.random.default_rng(5)
    samples = np.concatenate([rng.normal(size=300) * 10.0 ** rng.integers(-30, 30, 300),
                              rng.integers(-10**6, 10**6, 50).astype(float),
                              [0.0, -0.0, 1e16, 1e15, 1e-4, 1e-5, 0.1, 1 / 3, 5e-324,
                               1.7976931348623157e308, math.inf, -math.inf, math.nan]])
    for x in samples:
        assert repr_(float(x)) == repr(float(x))


def unsupported(x, y):
    return [x, y].index(y)


def type_changes_in_loop(x, n):
    value = 0.0
    for _ in range(int(n)):
        value = Spring(x)
    return value


@pytest.mark.parametrize("function, words", [
    (unsupported, f"test_translate.py:{unsupported.__code__.co_firstlineno + 1}: attribute index"),
    (type_changes_in_loop, "changes from a run-time double to a Spring object in a loop")])
def test_untranslatable_code_is_refused_naming_file_line_and_construct(function, words):
    with pytest.raises(TranslationError, match=words):
        compiled(function, 2)
