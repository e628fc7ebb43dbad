"""One home for every paper's parameter table (physics/papers/): the package source outside it
must not write one of their values again. The source is read with tokenize, so comments,
docstrings and strings do not count.

The rule. A distinctive value is a duplicate wherever it is written. A common one (zero, whole
numbers, halves and quarters up to 100, as counts, indices, exponents or degrees, and numbers
below 1 with one significant digit) is one only where it is the default or value of a
parameter, field, keyword or key under one of the names NAMES gives its constant:
``rollers_per_groove: int = 20``, ``self.parameter("rollers_per_groove", 20, ...)``,
``f(rollers_per_groove=20)``, ``{"rollers_per_groove": 20}``, ``x["rollers_per_groove"] = 20``;
a value wrapped in a call of its own (``math.radians(45.0)``) counts as the call's. Entries of a
table's tuples and dicts carry no name: only their distinctive values are looked for.
"""
import ast
import importlib
import io
import pkgutil
import tokenize
from pathlib import Path

import pytest

import guideway_fmu
from guideway_fmu.physics import papers

PACKAGE = Path(guideway_fmu.__file__).parent
PAPERS = Path(papers.__file__).parent

#: the names under which the package would write each common value of the tables; () where no
#: parameter takes it (the model builds it in, or nothing uses it)
NAMES = {
    "soleimanian2020.ROLLER_LENGTH": ("roller_length", "length"),
    "soleimanian2020.GROOVES": (),  # the four-row models build it in
    "soleimanian2020.ROLLERS_PER_GROOVE": ("rollers_per_groove",),
    "soleimanian2020.FEED_FREQUENCY": ("frequency",),
    "soleimanian2020.HESS_SOOM_ASPERITY_RADIUS": ("asperity_radius",),
    "soleimanian2020.HESS_SOOM_SPEED_AMPLITUDE": ("amplitude",),
    "wu2012.RAIL_LENGTH": (),
    "wu2012.RAIL_WIDTH": (),
    "wu2012.BALLS": (),
    "wu2012.ROWS": (),  # the 5-DOF carriage builds in two rows
    "wu2012.CONTACT_ANGLE_DEG": ("contact_angle", "nominal_angle"),
    "wu2012.POISSON_RATIO": ("poisson_ratio", "nu_ball", "nu_groove"),
    "wu2012.BALLS_PER_ROW": ("balls_per_row", "balls"),
    "zhang_wang_jiang.PRELOAD_DEFORMATION": ("preload_deformation", "initial_deformation"),
    "zhang_wang_jiang.BALLS_PER_ROW": ("balls_per_row",),
    "zhang_wang_jiang.CONTACT_ANGLE_DEG": ("contact_angle",),
    "zhang_wang_jiang.WEAR_COEFFICIENT": ("wear_coefficient",),
    "zhang_wang_jiang.FREQUENCY_RATIO": ("gamma",),
    "zhang_wang_jiang.HYSTERESIS": ("hysteresis",),
    "zhang_wang_jiang.POISSON_RATIO": ("poisson_ratio",),
    "lin2019.BALL_RADIUS": ("radius",),
    "lin2019.NORMAL_LOAD": ("normal",),
    "lin2019.VELOCITY": ("velocity",),
    "lin2019.FRICTION": ("friction",),
    "lin2019.DEVIATION_DEG": (),
    "lin2019.SIDE_FORCE_RATIO": ("side_ratio",),
    "zhang2019.CONTACT_ANGLE_DEG": ("contact_angle",),
}

#: (file under the package, value) -> why an equal number there is a different fact
ALLOWED = {
    ("diagnose/run_io.py", 2e11): "the measured-run format's default reduced modulus, steel on "
                                  "steel (docs/measured-run.md), not the paper's E'",
    ("physics/roller_guide/carriage.py", 43e-3): "SPEED_SCALE, 0.043 m/s, a velocity scale of the "
                                                 "tolerances, not the load zone",
    ("physics/roller_guide/ehl/flow_factors.py", 0.56): "a coefficient of Patir and Cheng's flow "
                                                        "factors, not a conformity",
    ("physics/wear/raceway_wear.py", 0.1): "Guide.friction, the creep's mu: the wear paper "
                                           "states none, the project takes 0.1",
    ("components/ball_guides/feed_unit_errors.py", 12.0): "the example feed unit's balls per row "
                                                          "(the paper prints none), not the LG20's",
}


def _numbers(label, value):
    """(label, number, scalar) of every number in a table constant."""
    if isinstance(value, bool):
        return []
    if isinstance(value, (int, float)):
        return [(label, float(value), True)]
    if isinstance(value, (tuple, list)):
        return [(f"{label}[{i}]", float(v), False) for i, v in enumerate(value)]
    if isinstance(value, dict):
        return ([(f"{label} key", float(k), False) for k in value]
                + [item for k, v in value.items() for item in _numbers(f"{label}[{k!r}]", v)])
    return []


def table_values() -> dict[float, list[tuple[str, bool]]]:
    """|value| -> [(module.CONSTANT, scalar)] over the UPPERCASE constants of physics/papers/."""
    values: dict[float, list[tuple[str, bool]]] = {}
    for info in pkgutil.iter_modules(papers.__path__):
        module = importlib.import_module(f"{papers.__name__}.{info.name}")
        for name, value in vars(module).items():
            if name.isupper():
                for label, number, scalar in _numbers(f"{info.name}.{name}", value):
                    if number != 0.0:
                        values.setdefault(abs(number), []).append((label, scalar))
    return values


def common(value: float) -> bool:
    """Zero, whole numbers, halves and quarters up to 100, numbers below 1 with one significant
    digit: they mean nothing by themselves."""
    if value <= 100 and (4 * value).is_integer():
        return True
    return value < 1 and float(f"{value:.12e}".split("e")[0]).is_integer()


def _name(token) -> str:
    name = ast.literal_eval(token.string) if token.type == tokenize.STRING else token.string
    return name.lower()  # a module constant goes by its name in capitals


def named(tokens, i: int) -> str | None:
    """The parameter, field, keyword or key whose default or value the number tokens[i] is."""
    j = i - 1
    if tokens[j].string in ("-", "+"):
        j -= 1
    if (tokens[j].string == "(" and tokens[j - 1].type == tokenize.NAME
            and tokens[i + 1].string == ")"):  # wrapped alone in a call: radians(45.0)
        j -= 2
        while tokens[j].string == "." and tokens[j - 1].type == tokenize.NAME:
            j -= 2
    t = tokens[j]
    if t.string == ":" and tokens[j - 1].type == tokenize.STRING:  # {"name": value}
        return _name(tokens[j - 1])
    if (t.string == "," and tokens[j - 1].type == tokenize.STRING
            and tokens[j - 2].string == "("):  # f("name", value, ...)
        return _name(tokens[j - 1])
    if t.string != "=":
        return None
    k, depth = j - 1, 0
    while k >= 0:  # back to the start of the statement or argument
        s = tokens[k].string
        if s in ")]}":
            depth += 1
        elif s in "([{":
            if depth == 0:
                break
            depth -= 1
        elif depth == 0 and (s in (",", ";") or tokens[k].type in (
                tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT)):
            break
        k -= 1
    target = tokens[k + 1:j]
    colons = [n for n, token in enumerate(target) if token.string == ":"]
    if colons:  # an annotated field or parameter
        target = target[:colons[0]]
    names = [token for token in target if token.type in (tokenize.NAME, tokenize.STRING)]
    return _name(names[-1]) if names else None


def duplicates(source: str, path: str, values=None, allowed=None) -> list[str]:
    """'path:line: literal is module.CONSTANT' for every table value the source writes again."""
    values = table_values() if values is None else values
    allowed = ALLOWED if allowed is None else allowed
    skip = (tokenize.COMMENT, tokenize.NL)
    tokens = [t for t in tokenize.generate_tokens(io.StringIO(source).readline)
              if t.type not in skip]
    found = []
    for i, token in enumerate(tokens):
        if token.type != tokenize.NUMBER:
            continue
        number = ast.literal_eval(token.string)
        if isinstance(number, complex) or abs(number) not in values or (
                (path, abs(number)) in allowed):
            continue
        value = abs(float(number))
        name = named(tokens, i)
        hits = [label for label, scalar in values[value]
                if not common(value) or (scalar and name in NAMES.get(label, ()))]
        if hits:
            found.append(f"{path}:{token.start[0]}: {token.string} is {' or '.join(hits)}")
    return found


def package_sources():
    return sorted(p for p in PACKAGE.rglob("*.py") if not p.is_relative_to(PAPERS))


def test_no_paper_value_is_written_outside_physics_papers():
    values = table_values()
    found = [line for path in package_sources()
             for line in duplicates(path.read_text(), path.relative_to(PACKAGE).as_posix(), values)]
    assert not found, "written again; read it from physics/papers/:\n" + "\n".join(found)


def test_every_allowed_equal_number_is_still_there():
    """An exception that no longer matches anything is dropped, not kept as a blind spot."""
    values = table_values()
    for (path, value), reason in ALLOWED.items():
        assert reason
        only = {value: values[value]}
        assert duplicates((PACKAGE / path).read_text(), path, only, allowed={}), (path, value)


def test_every_common_scalar_says_where_it_would_be_written():
    values = table_values()
    unnamed = sorted(label for value, labels in values.items() if common(value)
                     for label, scalar in labels if scalar and label not in NAMES)
    assert not unnamed, f"give these their names in NAMES: {unnamed}"
    assert set(NAMES) <= {label for labels in values.values() for label, _ in labels}


def test_the_package_docstring_names_every_paper_module():
    for info in pkgutil.iter_modules(papers.__path__):
        assert f"``{info.name}``" in papers.__doc__


# -- the scanner on planted duplicates: it must fail on them, or the check above proves nothing

PLANTED = '''"""A docstring quoting 2.2e-8 and 20 rollers."""
import math
ALPHA = 2.2e-8 * 1.0  # a comment quoting 0.195


class Guide:
    rollers_per_groove: int = 20
    angle: float = 45.0


def f(x, rollers_per_groove=20, index=20):
    g(rollers_per_groove=20, contact_angle=math.radians(45.0))
    row["rollers_per_groove"] = 20
    return {"rollers_per_groove": 20, "other": 20}, range(20), x ** 20, -0.195


def build(self):
    self.parameter("rollers_per_groove", 20, None, "rollers N")
    self.parameter("stop", 20, None, "not the roller count")
'''


def test_scanner_finds_every_planted_duplicate_and_nothing_else():
    found = duplicates(PLANTED, "planted.py")
    lines = sorted(int(f.split(":")[1]) for f in found)
    # line 3: distinctive anywhere (not in the docstring or the comment); 7: a field; 11: a
    # keyword default; 12: keyword arguments, the angle through radians(); 13: a subscript
    # target; 14: a dict key and a distinctive value behind a minus; 18: a parameter's value
    assert lines == [3, 7, 11, 12, 12, 13, 14, 14, 18]
    assert "planted.py:7: 20 is soleimanian2020.ROLLERS_PER_GROOVE" in found
    assert "planted.py:3: 2.2e-8 is soleimanian2020.PRESSURE_VISCOSITY" in found
    assert any(f.startswith("planted.py:12: 45.0 is wu2012.CONTACT_ANGLE_DEG") for f in found)


def test_scanner_honours_an_allowed_number_only_in_its_file():
    allowed = {("planted.py", 2.2e-8): "planted"}
    assert not any(":3:" in f for f in duplicates(PLANTED, "planted.py", allowed=allowed))
    assert any(":3:" in f for f in duplicates(PLANTED, "other.py", allowed=allowed))


@pytest.mark.parametrize("value, expected", [(20.0, True), (45.0, True), (0.25, True), (1.5, True),
                                             (8e-3, True), (4e-6, True), (0.047, False),
                                             (2e11, False), (9200.0, False), (0.534, False)])
def test_common_hand_values(value, expected):
    assert common(value) is expected
