"""Dimensions: named and SI input, words for students, and the dimension of an expression."""

import time
from fractions import Fraction

import pytest
import sympy

from grader.expressions import Dimension, DimensionError, dimension_of, parse_dimension
from grader.expressions.dimensions import NAMED_DIMENSIONS, parse_unit

M, L, T = Dimension(1, 0, 0), Dimension(0, 1, 0), Dimension(0, 0, 1)


@pytest.mark.parametrize("name, si", [
    ("dimensionless", "1"), ("angle", "rad"), ("mass", "kg"), ("length", "m"), ("time", "s"),
    ("velocity", "m/s"), ("acceleration", "m/s^2"), ("force", "N"), ("energy", "J"),
    ("momentum", "kg*m/s"), ("angular_velocity", "rad/s"), ("angular_acceleration", "s^-2"),
    ("frequency", "Hz"), ("moment_of_inertia", "kg*m^2"), ("torque", "N*m"), ("power", "W"),
    ("area", "m^2"), ("volume", "m**3"), ("stiffness", "N/m"), ("density", "kg/m^3"),
    ("angular_momentum", "kg*m^2/s"),
])
def test_every_named_dimension_matches_its_si_units(name, si):
    assert parse_dimension(name) == parse_dimension(si)


def test_all_named_dimensions_are_tested():
    assert len(NAMED_DIMENSIONS) == 21


@pytest.mark.parametrize("text, expected", [
    ("kg*m^2", M * L ** 2),
    ("m/s^2", L / T ** 2),
    ("1/s", Dimension(0, 0, -1)),
    ("s^-1", Dimension(0, 0, -1)),
    ("(kg*m)/(s*s)", M * L / T ** 2),
    ("m^(1/2)", Dimension(0, Fraction(1, 2), 0)),
    ("J/(kg*m)", L / T ** 2),
    ("Angular Velocity", Dimension(0, 0, -1)),
])
def test_si_expressions(text, expected):
    assert parse_dimension(text) == expected


@pytest.mark.parametrize("text", ["furlong", "kg*", "m^x", "(m", ""])
def test_bad_dimension_text_is_refused(text):
    with pytest.raises(DimensionError):
        parse_dimension(text)


# Exponents that once escaped as a ZeroDivisionError (a checker's "internal error") or were
# refused as an "unbalanced parenthesis" they do not have: each is refused saying what is wrong.
@pytest.mark.parametrize("text, message", [
    ("kg^(1/0)", "divides by zero"),
    ("kg^(0/0)", "divides by zero"),
    ("m^(-1/0)", "divides by zero"),
    ("kg^1/0", "divides by zero"),
    ("m^(1e999)", "a unit exponent is a whole number or a fraction|unknown unit 'e'"),  # a unit reads letters
    ("kg^(10^400)", "a unit exponent is a whole number or a fraction"),
    ("kg^(1/1000)", "not plausible"),
])
@pytest.mark.parametrize("read", [parse_dimension, parse_unit], ids=["dimension", "unit"])
def test_an_exponent_that_is_no_plausible_number_is_refused_with_what_is_wrong(read, text, message):
    with pytest.raises(DimensionError, match=message):
        read(text)


@pytest.mark.parametrize("dim, words", [
    (M * L / T ** 2, "a force (kg·m/s²)"),
    (L, "a length (m)"),
    (Dimension(), "dimensionless"),
    (M * L ** 2 / T ** 2, "an energy or torque (kg·m²/s²)"),
    (Dimension(0, 0, -1), "an angular velocity or frequency (1/s)"),
    (M * L ** 3, "a quantity in kg·m³"),
])
def test_describe_in_words(dim, words):
    assert dim.describe() == words


m, g, l, x, theta = sympy.symbols("m g l x theta")
DIMS = {m: M, g: L / T ** 2, l: L, x: L, theta: Dimension()}


@pytest.mark.parametrize("expr, expected", [
    (m * g * l * sympy.cos(theta), M * L ** 2 / T ** 2),           # potential energy of a pendulum
    (sympy.sqrt(g / l), Dimension(0, 0, -1)),                      # small-oscillation frequency
    (2 * sympy.pi * sympy.sqrt(l / g), T),                         # period
    (l ** 2 - x ** 2, L ** 2),                                     # a constraint
    (sympy.atan2(x, l), Dimension()),
    (sympy.Abs(x), L),
    (sympy.sign(x) * m, M),
    (sympy.exp(-x / l) * m, M),
    (sympy.Eq(m * g, m * g * sympy.sin(theta)), M * L / T ** 2),
    (sympy.Integer(0), Dimension()),
])
def test_dimension_of_physical_expressions(expr, expected):
    assert dimension_of(expr, DIMS) == expected


u, m0, m1, r, R, n = sympy.symbols("u m0 m1 r R n", positive=True)
SCALED = {u: L / T, m0: M, m1: M, r: L, R: L, n: Dimension(), g: L / T ** 2, l: L, m: M}


@pytest.mark.parametrize("expr, expected", [
    # A rocket's speed, u ln(m₀/m₁), as students write it: each log has a mass in it, not the sum.
    (u * (sympy.log(m0) - sympy.log(m1)), L / T),
    (u * sympy.log(m0) - u * sympy.log(m1), L / T),
    (sympy.Eq(u, u * sympy.log(m0) - u * sympy.log(m1)), L / T),
    (sympy.exp(sympy.log(m0) - sympy.log(m1)) * u, L / T),
    # A power-law potential's (r/R)ⁿ written over two powers, and through logarithms.
    (m * g * l * r ** n / R ** n, M * L ** 2 / T ** 2),
    (m * g * l * sympy.exp(n * (sympy.log(r) - sympy.log(R))), M * L ** 2 / T ** 2),
    (r ** (2 * n + 1) / R ** (2 * n), L),
    (r ** n / R ** (n + 1), L ** -1),
])
def test_a_whole_that_is_homogeneous_has_its_dimension_though_its_parts_have_none(expr, expected):
    assert dimension_of(expr, SCALED) == expected


@pytest.mark.parametrize("expr, words", [
    (u * sympy.log(m0), "log needs a dimensionless argument, got a mass (kg)"),    # ln m₀ alone
    (u * sympy.log(m0) - sympy.log(m1), "log needs a dimensionless argument"),     # not the same multiple
    (u * (sympy.log(m0) - sympy.log(r)), "log needs a dimensionless argument"),     # a mass over a length
    (r ** n, "raises a length (m) to the non-numeric power n"),
    (sympy.sin(r) - sympy.sin(R), "sin needs a dimensionless argument"),           # not homogeneous
])
def test_a_whole_that_changes_with_the_units_keeps_the_walkers_error(expr, words):
    with pytest.raises(DimensionError) as err:
        dimension_of(expr, SCALED)
    assert words in str(err.value)


@pytest.mark.parametrize("expr, words", [
    (m * g + l, ["adds", "a force (kg·m/s²)", "a length (m)"]),      # sympy orders the terms
    (l + 1, ["adds", "a length (m)", "a dimensionless number"]),
    (sympy.sin(l), "sin needs a dimensionless argument, got a length (m)"),
    (sympy.log(m), "log needs a dimensionless argument, got a mass (kg)"),
    (sympy.atan2(x, m), "atan2 needs two arguments of one dimension"),
    (l ** x, "raises to a power that is a length (m)"),
    (l ** theta, "raises a length (m) to the non-numeric power theta"),
    (sympy.Eq(m, l), "equates a mass (kg) to a length (m)"),
    (sympy.Symbol("k"), "'k' has no known dimension"),
])
def test_dimension_mismatches_are_explained_in_words(expr, words):
    with pytest.raises(DimensionError) as err:
        dimension_of(expr, DIMS)
    for fragment in [words] if isinstance(words, str) else words:
        assert fragment in str(err.value)


def test_symbols_match_by_name_whatever_their_assumptions():
    positive_m = sympy.Symbol("m", positive=True)
    assert dimension_of(positive_m * g, {"m": "mass", g: "acceleration"}) == M * L / T ** 2


def test_dynamicsymbols_and_time_derivatives():
    t = sympy.Symbol("t")
    q = sympy.Function("q")(t)
    assert dimension_of(q.diff(t, 2), {"q": "length"}) == L / T ** 2


def test_fractional_exponents_add_up_to_whole_ones():
    # sqrt(l)^3 * sqrt(l) is l^2: halves along the way, a plain area at the end.
    assert dimension_of(sympy.sqrt(l) ** 3 * sympy.sqrt(l), DIMS) == L ** 2
    assert dimension_of(sympy.sqrt(m * l) * sympy.sqrt(l / m), DIMS) == L


def test_the_mismatch_reported_is_the_first_in_printed_order():
    with pytest.raises(DimensionError) as err:
        dimension_of(l + m * g + x * g / g, DIMS)
    assert str(err.value).startswith("adds a force (kg·m/s²) to a length (m): g*m + l")


def test_a_mismatch_deep_in_nested_sums_is_found_quickly():
    # Each level is a sum holding a product holding the next sum; the mismatch is at the bottom.
    # A term whose dimension fails is walked once, not again at every level above it.
    expr = l + g
    for _ in range(13):  # walking it again at each level would take 2**13 walks: seconds, not ms
        expr = l + x * expr / l
    start = time.perf_counter()
    with pytest.raises(DimensionError, match="adds an acceleration"):
        dimension_of(expr, DIMS)
    assert time.perf_counter() - start < 0.5


# -- a quantity's unit as students type it (parse_unit / read_unit) ------------------------------

from grader.expressions.dimensions import parse_unit, read_unit  # noqa: E402


@pytest.mark.parametrize("typed, canonical", [
    # symbols written together, where only one reading exists
    ("Nm", "N*m"), ("kNm", "kN*m"), ("kgm/s^2", "kg*m/s^2"), ("kgm^2/s^2", "kg*m^2/s^2"), ("N/kgm^2", "N/(kg*m^2)"),
    ("Ns", "N*s"), ("rads^-1", "rad/s"), ("degs^-1", "deg/s"),
    # an exponent right after its unit, a hyphen between units
    ("m/s2", "m/s^2"), ("m s-2", "m/s^2"), ("kg m2 s-2", "J"), ("N m-1", "N/m"), ("N-m", "N*m"),
    # units in words, any case, plural, with prefixes in words
    ("newtons", "N"), ("Newton", "N"), ("newton-metres", "N*m"), ("metres", "m"), ("meters", "m"), ("Metre", "m"),
    ("secs", "s"), ("sec", "s"), ("seconds", "s"), ("msec", "ms"), ("millisecond", "ms"), ("microseconds", "µs"),
    ("kilometres", "km"), ("centimeters", "cm"), ("kilograms", "kg"), ("grams", "g"), ("joules", "J"),
    ("radians", "rad"), ("rads", "rad"), ("degrees", "deg"), ("degs", "deg"), ("hertz", "Hz"), ("hrs", "h"),
    ("hours", "h"), ("minutes", "min"), ("mins", "min"), ("km/hr", "km/h"), ("percent", "%"),
    ("metres per second squared", "m/s^2"), ("N per m", "N/m"), ("per second", "1/s"), ("(dimensionless)", "1"),
    ("unitless", "1"), ("kgs", "kg"), ("kilos", "kg"), ("KG", "kg"), ("kgs^-1", "kg/s"), ("kgm2s-3", "W"),
    # a capital first letter where that is no other unit
    ("Kg", "kg"), ("Km/h", "km/h"), ("Rad", "rad"), ("Deg", "deg"),
    # look-alikes of the degree sign and the dot
    ("º", "°"), ("˚", "°"), ("N⋅m", "N*m"), ("N∙m", "N*m"), ("kg×m/s²", "kg*m/s^2"),
])
def test_units_as_students_type_them(typed, canonical):
    assert parse_unit(typed) == pytest.approx(parse_unit(canonical))


@pytest.mark.parametrize("typed, size, dimension", [
    ("ms", 1e-3, T), ("mN", 1e-3, M * L / T ** 2), ("Ms", 1e6, T), ("nm", 1e-9, L), ("mm", 1e-3, L),
    ("MN", 1e6, M * L / T ** 2), ("min", 60.0, T), ("%", 0.01, Dimension()), ("kWh", 3.6e6, M * L ** 2 / T ** 2),
])
def test_a_unit_symbol_is_that_unit_before_any_other_reading(typed, size, dimension):
    assert parse_unit(typed) == (pytest.approx(size), dimension)


@pytest.mark.parametrize("typed, message", [
    ("Nms", "'Nms' could be N*ms or N*m*s: write the units apart"),
    ("kn", "case-sensitive: did you mean kN?"), ("M/S", "did you mean m?"), ("CM", "did you mean cm?"),
    ("hz", "did you mean Hz?"), ("S", "did you mean s?"), ("j", "did you mean J?"),
    ("N upward", "'upward' is not a unit: type only the number and its unit"),
    ("furlong", "'furlong' is not a unit"), ("xyz", "unknown unit 'xyz'"), ("m s- 2", "cannot read unit"),
])
def test_ambiguous_and_wrong_case_units_are_refused_with_what_to_type(typed, message):
    with pytest.raises(DimensionError, match=message.replace("*", r"\*").replace("?", r"\?")):
        parse_unit(typed)


@pytest.mark.parametrize("typed, symbols", [
    ("kN*m", ("N", "m")), ("Nm", ("N", "m")), ("mJ", ("J",)), ("rad/s", ("rad", "s")), ("kHz", ("Hz",)),
    ("newton metres", ("N", "m")), ("°/s", ("°", "s")), ("J/rad", ("J", "rad")),
])
def test_read_unit_names_the_units_it_is_made_of(typed, symbols):
    assert read_unit(typed).symbols == symbols


@pytest.mark.parametrize("typed, dimension", [("ms^-2", L / T ** 2), ("ms-1", L / T), ("mN", M * L ** 2 / T ** 2)])
def test_milli_as_metre_is_the_other_reading_of_a_milli_prefixed_unit(typed, dimension):
    reading = read_unit(typed, milli_as_metre=True)
    assert reading.dimension == dimension and reading.split
    assert read_unit(typed).dimension != dimension


def test_scene_dimensions_keep_the_strict_grammar():
    # parse_dimension (scene files) reads SI units only: no words, no percent, no juxtaposed exponents.
    for text in ("newtons", "%", "m/s2", "Nm"):
        with pytest.raises(DimensionError):
            parse_dimension(text)


@pytest.mark.parametrize("typed, size, dimension", [
    # every SI prefix, yocto to yotta: a nucleus is some fm across, a laser pulse some fs or as long
    ("fm", 1e-15, L), ("am", 1e-18, L), ("zm", 1e-21, L), ("ym", 1e-24, L), ("fs", 1e-15, T), ("as", 1e-18, T),
    ("Pm", 1e15, L), ("Em", 1e18, L), ("Zg", 1e18, M), ("Yg", 1e21, M), ("PJ", 1e15, M * L ** 2 / T ** 2),
    ("fN", 1e-15, M * L / T ** 2), ("femtometres", 1e-15, L), ("attoseconds", 1e-18, T), ("petajoules", 1e15, M * L ** 2 / T ** 2),
    ("exametre", 1e18, L), ("yoctograms", 1e-27, M),
    # the tonne, accepted for use with SI
    ("t", 1e3, M), ("tonnes", 1e3, M), ("t/h", 1e3 / 3600, M / T),
])
def test_every_si_prefix_and_the_tonne_are_read(typed, size, dimension):
    assert parse_unit(typed) == (pytest.approx(size, rel=1e-12), dimension)


@pytest.mark.parametrize("typed", ["m s\u20102", "m·s^\u20112", "kg m s\u20142", "m s^(\u20122)"])
def test_a_units_exponent_takes_every_dash_read_as_a_minus(typed):
    assert parse_unit(typed)[1] in (L / T ** 2, M * L / T ** 2)


@pytest.mark.parametrize("typed", ["m/s·s", "m/s s", "m/s.s", "m/s*s", "kg/m s", "N/m·s", "J/kg·m", "m/s s^-1", "m/s²kg"])
def test_a_product_after_a_solidus_is_refused_naming_both_readings(typed):
    # m/s·s is (m/s)·s = m by precedence and m/(s·s) as many write it; the grader itself printed kg/m·s for kg/(m·s)
    with pytest.raises(DimensionError, match="every unit after the '/' below it, or only the first"):
        parse_unit(typed)


@pytest.mark.parametrize("typed, printed", [
    ("kg/(m s)", "kg/(m·s)"), ("kg/m/s", "kg/(m·s)"), ("m^3/(kg*s^2)", "m³/(kg·s²)"),
])
def test_a_denominator_of_several_units_is_printed_in_brackets(typed, printed):
    assert parse_unit(typed)[1].unit() == printed and parse_unit(printed) == parse_unit(typed)
