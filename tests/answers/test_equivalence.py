"""Expression equivalence: never fooled by cancellation, tiny terms or the domain."""

import pytest
import sympy

from grader.answers import equivalence
from grader.answers.equivalence import Options, compare_expressions, symbolic_zero
from grader.answers.sampling import Sampler, seed_for
from grader.expressions import parse_domain

m, g, l, R, m1, m2 = sympy.symbols("m g l R m1 m2", positive=True)
theta = sympy.Symbol("theta", real=True)
alpha = sympy.Symbol("alpha", nonnegative=True)
POS = parse_domain("positive")


def sampler(**domains):
    symbols = {s.name: s for s in (m, g, l, R, m1, m2, theta, alpha)}
    return Sampler({symbols[n]: parse_domain(d) for n, d in domains.items()}, seed_for(sorted(domains)))


ATWOOD = sampler(m1="positive", m2="positive", g="positive")
T = m1 * m2 * g / (m1 + m2)
a = m2 * g / (m1 + m2)


@pytest.mark.parametrize("answer", [
    m2 * (g - a),                       # cancels badly in float64 when m2 >> m1
    m2 * g - m2**2 * g / (m1 + m2),
    g / (1 / m1 + 1 / m2),
    m1 * g - m1**2 * g / (m1 + m2),
])
def test_half_atwood_tension_forms_are_equivalent(answer):
    c = compare_expressions(T, answer, ATWOOD, Options(symbolic=False))
    assert c.equivalent is True and c.certainty == "numeric" and c.evidence["digits"] >= 30


@pytest.mark.parametrize("answer", [
    T * (1 + sympy.Rational(1, 10**9)),   # off by a relative 1e-9
    T + m1 * g / 10**12,
    m1 * g * (1 - m1 / m2),               # a truncated series
])
def test_near_misses_are_proved_wrong_with_a_counterexample(answer):
    c = compare_expressions(T, answer, ATWOOD, Options(symbolic=False))
    assert c.equivalent is False and c.certainty == "proved"
    assert set(c.counterexample["values"]) >= {"m1", "m2", "g"}
    assert c.counterexample["answer"] != c.counterexample["reference"]


def test_small_angle_cancellation_is_decided_in_balls():
    # the sphere near its top: R(1 - cos theta) at theta ~ 1e-8, where float64 returns 0
    s = sampler(R="positive", theta=[1e-9, 1e-7])
    exact = R * (1 - sympy.cos(theta))
    assert compare_expressions(exact, 2 * R * sympy.sin(theta / 2) ** 2, s, Options(symbolic=False)).equivalent
    approx = compare_expressions(exact, R * theta**2 / 2, s, Options(symbolic=False))
    assert approx.equivalent is False and approx.certainty == "proved"


@pytest.mark.parametrize("domain, expected", [([-1.5, 1.5], True), ([-3.1416, 3.1416], False)])
def test_sqrt_one_minus_sin_squared_is_cos_only_where_cos_is_nonnegative(domain, expected):
    s = sampler(theta=domain)
    c = compare_expressions(sympy.cos(theta), sympy.sqrt(1 - sympy.sin(theta) ** 2), s)
    assert c.equivalent is expected


def test_positivity_makes_sqrt_of_a_square_the_variable():
    assert compare_expressions(m * g, sympy.sqrt(m**2) * g, sampler(m="positive", g="positive")).certainty == "proved"


def test_an_answer_undefined_where_the_reference_is_defined_is_wrong():
    c = compare_expressions(m * g, m * g * sympy.log(g - 100), sampler(m="positive", g="positive"))
    assert c.equivalent is False and c.counterexample["answer"] == "undefined"


def test_differing_constants_are_decided_exactly():
    c = compare_expressions(sympy.Rational(2, 3), sympy.Rational(6666666666666666666666666667, 10**28), ATWOOD)
    assert c.equivalent is False and c.certainty == "proved"


@pytest.mark.parametrize("diff, proved", [
    (m * g * (3 * sympy.cos(theta) - 2) - (3 * m * g * sympy.cos(theta) - 2 * m * g), True),
    (sympy.sin(theta) ** 2 + sympy.cos(theta) ** 2 - 1, False),  # true, but left to the numeric judge
    ((m + g) ** 40 - (g + m) ** 40, True),
])
def test_symbolic_step_is_cheap_and_only_claims_proofs(diff, proved):
    assert symbolic_zero(diff) is proved


_a, _b, _c, _d, _e = sympy.symbols("a b c d e", positive=True)
_NESTED = (_a + _b + _c) ** 5 + (_d + _e) ** 5


@pytest.mark.parametrize("diff", [
    # powers of sums of powers of sums, each under the size limits: 27,405 terms expanded (minutes)
    _NESTED ** 5 - _NESTED ** 4 * (_NESTED + (_a - _b) * (_a + _b) - _a ** 2 + _b ** 2),
    ((_a + _b + _c) ** 4 + (_d + _e) ** 4) ** 3 - 1,
    1 / ((_a + _b + _c + _d) ** 3 + _e) ** 3 - 1 / _e,  # in a denominator too
])
def test_the_symbolic_step_never_expands_what_multiplies_out_to_thousands_of_terms(diff, monkeypatch):
    monkeypatch.setattr(sympy, "expand", lambda *args, **kwargs: pytest.fail("expanded"))
    assert symbolic_zero(diff) is False  # left to the numeric judge, which proves it at its points


# Equal to T, but 10^100 times a ball-arithmetic zero: every point needs more precision than the
# first, so the judge reaches its deadline check (an easy answer would be decided before it).
HARD_T = T + 10**100 * T * (sympy.sin(m1) ** 2 + sympy.cos(m1) ** 2 - 1)


def test_budget_exhaustion_is_reported_not_guessed():
    c = compare_expressions(T, HARD_T, ATWOOD, Options(symbolic=False), deadline=0.0)
    assert c.equivalent is None and c.budget_exceeded and c.certainty == "none"
    # ...and with time, the same comparison is decided: it was the budget that stopped it.
    assert compare_expressions(T, HARD_T, ATWOOD, Options(symbolic=False)).equivalent is True


@pytest.mark.parametrize("method, tolerance", [("float64", 1e-3), ("mpmath", 1e-20)])
def test_fixed_precision_methods_exist_for_the_benchmark(method, tolerance):
    c = compare_expressions(T, g / (1 / m1 + 1 / m2), ATWOOD, Options(method=method, tolerance=tolerance, symbolic=False))
    assert c.equivalent is True and c.certainty == "numeric"


# -- powers and roots over the reals ------------------------------------------------------------
# Power laws that hold for complex numbers or positive bases (combining nested powers, moving an
# exponent inside a root, exp(log x) = x) must not make two texts equal where the declared domain
# allows a negative base: x is real here, y positive, n real, k in [0.5, 3].
POWER_VARIABLES = {"x": {"domain": "real"}, "y": {"domain": "positive"}, "n": {"domain": "real"},
                   "k": {"domain": [0.5, 3]}}


def _parsed_pair(reference, answer):
    from grader.expressions import Namespace, parse_expression

    ns = Namespace.from_spec(POWER_VARIABLES)
    r, a = parse_expression(reference, ns), parse_expression(answer, ns)
    s = Sampler({v.symbol: v.domain for v in ns.variables}, seed_for(reference, answer))
    return r, a, s


@pytest.mark.parametrize("reference, answer, expected", [
    ("x", "sqrt(x)^2", False),              # sympy makes it x; over the reals it needs x >= 0
    ("x", "x^(1/2) x^(1/2)", False),
    ("x", "(x^(1/3))^3", False),
    ("x", "exp(log(x))", False),
    ("x", "sin(asin(x))", False),           # only for |x| <= 1
    ("sqrt(x)^2", "x", False),              # the same, the other way round
    ("(x^3)^(1/3)", "x", False),            # the reference is undefined for x < 0, the answer is not
    ("(x^k)^(1/k)", "x", False),
    ("(x^2)^n", "x^(2n)", False),
    ("(x^2)^(1/2)", "x", False),
    ("sqrt(x^2 y)", "x sqrt(y)", False),
    ("log(x^2)", "2 log(x)", False),
    ("(x^2)^(3/2)", "x^3", False),
    ("(x^2)^(1/2)", "abs(x)", True),
    ("(x^2)^n", "abs(x)^(2n)", True),
    ("sqrt(x^2 y)", "abs(x) sqrt(y)", True),
    ("(y^n)^k", "y^(n k)", True),           # a positive base: every law holds
    ("y", "sqrt(y)^2", True),
    ("y", "exp(log(y))", True),
    ("log(x^2)", "2 log(abs(x))", True),
    ("(x^6)^(1/3)", "x^2", True),
])
def test_power_laws_hold_only_where_the_domain_allows(reference, answer, expected):
    r, a, s = _parsed_pair(reference, answer)
    c = compare_expressions(r.expr, a.expr, s, answer_conditions=a.conditions, reference_conditions=r.conditions)
    assert c.equivalent is expected
    if not expected:  # and it is shown at a point with a negative base, not guessed
        assert c.certainty == "proved" and c.counterexample["values"]["x"] < 0


# -- removable points ---------------------------------------------------------------------------
# Where only one side is undefined at an isolated point (a zero of a denominator that cancels) the
# two are the same function wherever both are defined: a sample or landmark point that lands there
# (x = 2 is twice half of the constant 4) is no counterexample. A region where only one side is
# undefined still is one (the power laws above).
@pytest.mark.parametrize("reference, answer, expected", [
    ("1", "abs(x^2 - 4)/(abs(x - 2) abs(x + 2))", True),   # landmark x = 2 was a counterexample
    ("abs(x^2 - 4)/(abs(x - 2) abs(x + 2))", "1", True),   # the reference undefined there
    ("x + 8", "(x^2 - 64)/(x - 8)", True),                 # a removable point at x = 8
    ("x - 8", "(x^2 - 64)/(x - 8)", False),                # a removable point, but wrong elsewhere
    ("1", "abs(x - 4)/(x - 4)", False),                    # -1 for x < 4: a region, not a point
    ("x", "sqrt(x - 4)^2 + 4", False),                     # undefined on x < 4: a region
])
def test_an_isolated_point_where_only_one_side_is_undefined_is_no_counterexample(reference, answer, expected):
    r, a, s = _parsed_pair(reference, answer)
    c = compare_expressions(r.expr, a.expr, s, answer_conditions=a.conditions, reference_conditions=r.conditions)
    assert c.equivalent is expected


# -- the whole domain is sampled ----------------------------------------------------------------
X_REAL = {"x": {"domain": "real"}}


@pytest.mark.parametrize("reference, answer, expected", [
    ("acosh(x/5)", "log(x/5 + sqrt(x^2/25 - 1))", True),   # both defined only for x >= 5
    ("acosh(x/5)", "log(x/5 + sqrt(x^2/25 + 1))", False),  # asinh: defined where acosh is not
    ("sqrt(x - 5)", "sqrt(x - 6)", False),
    ("sqrt(x - 5)*sqrt(x + 5)", "sqrt(x^2 - 25)", False),  # the answer is defined for x <= -5 too
])
def test_an_expression_defined_only_far_from_zero_is_still_decided(reference, answer, expected):
    from grader.answers import check

    v = check(reference, answer, X_REAL)
    assert v.verdict == ("equivalent" if expected else "not_equivalent")


def test_undefined_at_every_point_is_a_last_resort_that_says_so():
    from grader.answers import check

    # defined nowhere on the real line (asin(x - 10), defined on [9, 11] only, is now compared there: see
    # test_a_reference_defined_only_past_the_sampled_magnitudes_is_compared_where_it_is_defined)
    v = check("log(-1 - x^2)", "log(-2 - x^2)", X_REAL)
    assert v.verdict == "invalid" and "undefined at all" in v.reason and "domains" in v.reason


def test_values_beyond_float_range_give_a_verdict_not_an_internal_error():
    from grader.answers import check

    v = check("cosh(sinh(e/1.5e-3))", "100/cosec(x)", X_REAL)
    assert "internal error" not in v.reason


# -- speed: the fast paths give the same verdicts as the older ones --------------------------------
@pytest.mark.parametrize("reference, answer", [
    ("M*g*m*cos(a)/(M + m*sin(a)^2)", "M m g cos(a)/(M + m - m cos(a)^2)"),
    ("M*g*m*cos(a)/(M + m*sin(a)^2)", "M m g cos(a)/(M + m sin(a))"),
    ("x", "sqrt(x)^2"),
    ("(x - 1)^2", "x^2 - 2x + 1"),
])
def test_the_fast_paths_give_the_verdicts_of_the_older_ones(reference, answer):
    from grader.answers import check

    variables = {"M": {"domain": "positive"}, "m": {"domain": "positive"}, "g": {"domain": "positive"},
                 "a": {"domain": [0.05, 1.5]}, "x": {"domain": "real"}}
    fast, slow = check(reference, answer, variables), check(reference, answer, variables, options=Options(fast=False))
    assert fast.verdict == slow.verdict and fast.verdict in ("equivalent", "not_equivalent")


@pytest.mark.parametrize("reference, answer, expected", [
    ("abs(x - 10)", "10 - x", "not_equivalent"),     # equal for every x <= 10, the ordinary samples' scale
    ("abs(x - 10)", "abs(10 - x)", "equivalent"),
    ("x/1000 + abs(x)", "0.001 x + sqrt(x^2)", "equivalent"),
])
def test_constants_beyond_the_sampling_scale_say_where_else_to_look(reference, answer, expected):
    from grader.answers import check

    assert check(reference, answer, X_REAL).verdict == expected


@pytest.mark.parametrize("reference, answer, domains", [
    (m * g * sympy.cos(theta), m * g * sympy.sin(theta), {"m": "positive", "g": "positive", "theta": "real"}),
    (T, m1 * g, {"m1": "positive", "m2": "positive", "g": "positive"}),
    (m * l * theta**2, m * l * theta**2 + m * g * l, {"m": "positive", "l": "positive", "g": "positive",
                                                        "theta": "real"}),
])
def test_a_counterexample_uses_round_values_a_student_can_check(reference, answer, domains):
    c = compare_expressions(reference, answer, sampler(**domains), Options(symbolic=False))
    assert c.equivalent is False and c.certainty == "proved"
    for value in c.counterexample["values"].values():
        assert value * 2 == round(value * 2) and value != 0, c.counterexample  # whole numbers or halves


def test_round_points_stay_inside_each_domain():
    from grader.answers.equivalence import round_values

    x = sympy.Symbol("x")
    narrow = parse_domain([0.1, 0.2])
    assert round_values({x: 0.1234}, {x: narrow}) == [{x: 0.1}]  # 0.5 is outside: only one figure fits


@pytest.mark.parametrize("answer", [
    T * (1 + sympy.Rational(1, 10**40)),        # off by far less than the judge's 30 digits
    T + sympy.exp(-100),                        # a constant term of 1e-44
    T + m1 * g * sympy.exp(-120),
    sympy.exp(theta) + sympy.exp(-100) - sympy.exp(theta) + T,
])
def test_a_difference_below_the_judges_digits_is_still_found_when_sympy_isolates_it(answer):
    # The points agree to 40 digits; the difference that sympy's exact arithmetic leaves
    # (T/10^40, e^-100) evaluated by itself is a proof that the answers differ.
    s = sampler(m1="positive", m2="positive", g="positive", theta="real")
    c = compare_expressions(T, answer, s)
    assert c.equivalent is False and c.certainty == "proved"
    assert c.counterexample["relative_difference"] < 1e-30


@pytest.mark.parametrize("answer", [
    m1 * m2 * g * (sympy.sin(theta)**2 + sympy.cos(theta)**2) / (m1 + m2),  # equal, not cancelled by sympy
    m2 * (g - a),
    T + sympy.exp(theta) - sympy.exp(theta),
])
def test_an_equal_answer_whose_difference_sympy_does_not_cancel_stays_equivalent(answer):
    s = sampler(m1="positive", m2="positive", g="positive", theta="real")
    assert compare_expressions(T, answer, s).equivalent is True


XYZ_REAL = {n: {"dimension": "dimensionless", "domain": "real"} for n in ("x", "y", "z")}


@pytest.mark.parametrize("shift", range(1, 41))
@pytest.mark.parametrize("reference, answer, expected", [
    # Each pair agrees wherever the argument of abs/sign is positive and differs only in a smaller
    # region (y < -|x|: a quarter of the samples; x < -(|y| + |z|): fewer), which the handful of
    # random points (seeded by the reference, so shifted by a constant to draw other points) can
    # all miss: every sign pattern of the arguments that sampling meets must be compared.
    ("abs(x) + y", "abs(abs(x) + y)", "not_equivalent"),
    ("x + abs(y) + abs(z)", "abs(x + abs(y) + abs(z))", "not_equivalent"),
    ("0", "sign(x + abs(y)) - 1", "not_equivalent"),
    ("abs(abs(x) + y)", "||x|+y|", "equivalent"),
    ("x/abs(x) + abs(y - z)", "sign(x) + |z - y|", "equivalent"),
])
def test_every_sign_pattern_of_an_abs_argument_met_is_compared(reference, answer, expected, shift):
    from grader.answers import check

    assert check(f"{reference} + {shift}", f"{answer} + {shift}", XYZ_REAL).verdict == expected


# Wrong only on the part of an interval past a branch point near one end (red team, 2026-11-27 C): an
# inverse trigonometric function or a root of a square is the answer on one side of π/2 (or π) only.
_BRANCH_PAIRS = [("cos(x)", "sqrt(1 - sin(x)^2)"), ("asin(sin(x))", "x"), ("atan(tan(x))", "x"),
                 ("acos(cos(x))", "abs(x)")]
_BRANCH_ENDS = {"cos(x)": 1.5708, "asin(sin(x))": 1.5708, "atan(tan(x))": 1.5708, "acos(cos(x))": 3.1416}


def _check_on(reference, answer, lo, hi):
    from grader.answers.checker import check

    return check(reference, answer, {"x": {"dimension": "dimensionless", "domain": [lo, hi]}})


@pytest.mark.parametrize("reference, answer", _BRANCH_PAIRS)
@pytest.mark.parametrize("lo", [0.1, -0.5, 0.0])
def test_an_answer_wrong_only_past_a_branch_point_near_an_end_is_refused(reference, answer, lo):
    # The far end runs from just past the branch point (0.1% of the interval) to 0.7 past it.
    past = _BRANCH_ENDS[reference]
    for hi in [past + 0.004, past + 0.03, *(past + 0.0125 * k for k in range(1, 56))]:
        verdict = _check_on(reference, answer, lo, hi)
        assert verdict.verdict == "not_equivalent", (hi, verdict.reason)
        assert verdict.counterexample["values"]["x"] > past


@pytest.mark.parametrize("reference, answer", _BRANCH_PAIRS)
@pytest.mark.parametrize("short", [0.07, 0.0])
def test_the_same_answers_are_right_on_an_interval_up_to_the_branch_point(reference, answer, short):
    # short = 0: the end is the branch point written to four decimals (1.5708 for π/2, 3.1416 for π), a
    # few millionths past it, as instructors write an incline's or a swing's range
    lo = 0.1 if reference in ("cos(x)", "acos(cos(x))") else -1.5
    verdict = _check_on(reference, answer, lo, _BRANCH_ENDS[reference] - short)
    assert verdict.verdict == "equivalent", verdict.reason


@pytest.mark.parametrize("points", [1, 8, 16, 24])
@pytest.mark.parametrize("reference, answer, hi", [("acos(cos(x))", "abs(x)", 3.15), ("atan(tan(x))", "x", 1.6)])
def test_the_ends_of_an_interval_are_compared_however_many_points_are_asked(points, reference, answer, hi):
    # wrong only within 0.3% of the interval's end: no number of ordinary points is sure to land there
    from grader.answers.checker import check

    variables = {"x": {"dimension": "dimensionless", "domain": [-1.5 if hi < 2 else -3.14, hi]}}
    verdict = check(reference, answer, variables, options=Options(points=points, symbolic=False))
    assert verdict.verdict == "not_equivalent", verdict.reason


# Red team, 2026-11-27 (s11): a kink or branch whose other regions lie beyond the sampled scale (|v| in 0.5 .. 3)
# or between two close roots. Each answer is right on the regions the samples meet and wrong on another one,
# which the points between the boundaries of its kink or branch arguments (along each variable) must meet,
# however the reference is scaled (a scale is another seed, so other sample points).
THETA_REAL = {"theta": {"dimension": "angle", "domain": "real"}}
X_POSITIVE = {"x": {"dimension": "dimensionless", "domain": "positive"}}
XD_LENGTHS = {"x": {"dimension": "length", "domain": "positive"}, "d": {"dimension": "length", "domain": "positive"}}
_PAST_THE_KINKS = [
    ("cos(theta/2)", "sqrt((1+cos(theta))/2)", THETA_REAL),        # differ for theta in (pi, 3 pi)
    ("theta", "atan2(sin(theta), cos(theta))", THETA_REAL),         # past pi
    ("sin(theta)*cos(theta)", "sign(theta)*sqrt(1-cos(theta)^2)*cos(theta)", THETA_REAL),
    ("(x-3)*(x-4)", "abs((x-3)*(x-4))", X_POSITIVE),                 # between the close roots 3 and 4
    ("(x-50)*(x-60)", "abs((x-50)*(x-60))", X_POSITIVE),
    ("x^2+1", "(x^2+1)*sign((x-4)*(x-6))", X_POSITIVE),
    ("(x-5*d)*(x-6*d)", "abs((x-5*d)*(x-6*d))", XD_LENGTHS),
    ("x", "10*acos(cos(x/10))", X_POSITIVE),                         # past 10 pi
    ("cos(x/3)", "sqrt(1-sin(x/3)^2)", X_POSITIVE),                  # past 3 pi/2
    ("x", "x*sign((x-40)*(x-41))", {"x": {"dimension": "dimensionless", "domain": [0, 100]}}),
]
_RIGHT_ACROSS_THE_KINKS = [
    ("abs(cos(theta/2))", "sqrt((1+cos(theta))/2)", THETA_REAL),
    ("abs(sin(theta))", "sqrt(1-cos(theta)^2)", THETA_REAL),
    ("atan2(sin(theta), cos(theta))", "atan2(2*sin(theta), 2*cos(theta))", THETA_REAL),
    ("cos(theta/2)", "sqrt((1+cos(theta))/2)", {"theta": {"dimension": "angle", "domain": [-3.1416, 3.1416]}}),
    ("abs((x-3)*(x-4))", "abs(x-3)*abs(x-4)", X_POSITIVE),
    ("(x^2+1)*sign((x-4)*(x-6))", "(x^2+1)*sign(x-4)*sign(x-6)", X_POSITIVE),
    ("abs((x-5*d)*(x-6*d))", "abs(x-5*d)*abs(6*d-x)", XD_LENGTHS),
    ("x", "10*acos(cos(x/10))", {"x": {"dimension": "dimensionless", "domain": [0, 30]}}),
    ("abs(cos(x/3))", "sqrt(1-sin(x/3)^2)", X_POSITIVE),
    ("x*sign((x-40)*(x-41))", "x*sign(x-40)*sign(x-41)", {"x": {"dimension": "dimensionless", "domain": [0, 100]}}),
]
_SCALES = ["1", "3", "7/2", "10", "1/9"]


def _scaled(scale: str, text: str) -> str:
    return text if scale == "1" else f"{scale}*({text})"


@pytest.mark.parametrize("scale", _SCALES)
@pytest.mark.parametrize("reference, answer, variables", _PAST_THE_KINKS)
def test_an_answer_wrong_only_in_a_region_of_its_kink_beyond_the_samples_is_refused(reference, answer, variables,
                                                                                  scale):
    from grader.answers.checker import check

    verdict = check(_scaled(scale, reference), _scaled(scale, answer), variables)
    assert verdict.verdict == "not_equivalent" and verdict.certainty == "proved", verdict.reason


@pytest.mark.parametrize("scale", _SCALES)
@pytest.mark.parametrize("reference, answer, variables", _RIGHT_ACROSS_THE_KINKS)
def test_the_same_kinks_written_otherwise_stay_equivalent(reference, answer, variables, scale):
    from grader.answers.checker import check

    verdict = check(_scaled(scale, reference), _scaled(scale, answer), variables)
    assert verdict.verdict == "equivalent", verdict.reason


_PENDULUM = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"},
             "l": {"dimension": "length", "domain": "positive"},
             "theta": {"dimension": "angle", "domain": "real", "kind": "coordinate"},
             "thetadot": {"dimension": "angular_velocity", "domain": "real", "kind": "velocity"},
             "thetaddot": {"dimension": "angular_acceleration", "domain": "real", "kind": "acceleration"}}
_SPRINGS = {"m": {"dimension": "mass", "domain": "positive"}, "k": {"dimension": "stiffness", "domain": "positive"},
            **{q: {"dimension": "length", "domain": "real", "kind": "coordinate"} for q in ("x", "y")},
            **{f"{q}dot": {"dimension": "velocity", "domain": "real", "kind": "velocity"} for q in ("x", "y")},
            **{f"{q}ddot": {"dimension": "acceleration", "domain": "real", "kind": "acceleration"} for q in ("x", "y")}}


@pytest.mark.parametrize("reference, answer, variables, expected", [
    ("thetaddot = -g/l*sin(theta)", "thetaddot = -g/l*sqrt(1-cos(theta)^2)*sign(theta)", _PENDULUM, "not_equivalent"),
    ("thetaddot = -g/l*sin(theta)", "thetaddot = -g/l*sin(acos(cos(theta)))*sign(theta)", _PENDULUM,
     "not_equivalent"),
    ("thetaddot + g/l*sin(theta) = 0", "thetaddot + g/l*sin(theta)*sign(cos(theta) + 0.999) = 0", _PENDULUM,
     "not_equivalent"),                                          # wrong only within 0.045 of theta = pi
    ("m*xddot = -k*x; m*yddot = -k*y", "m*xddot = -k*x*sign((x-5*y)*(x-6*y)); m*yddot = -k*y", _SPRINGS,
     "not_equivalent"),                                          # wrong only between x = 5y and x = 6y
    ("thetaddot = -g/l*sin(theta)", "thetaddot = -g/l*sqrt(1-cos(theta)^2)*sign(sin(theta))", _PENDULUM,
     "equivalent"),
    ("thetaddot + g/l*sin(theta) = 0", "thetaddot + g/l*sin(theta)*sign(cos(theta) + 1.001) = 0", _PENDULUM,
     "equivalent"),
    ("m*xddot = -k*x*sign((x-5*y)*(x-6*y)); m*yddot = -k*y",
     "m*xddot = -k*x*sign(x-5*y)*sign(x-6*y); m*yddot = -k*y", _SPRINGS, "equivalent"),
])
def test_equations_are_compared_in_the_regions_of_their_kinks_too(reference, answer, variables, expected):
    from grader.answers.checker import check

    assert check(reference, answer, variables, kind="equation").verdict == expected


def test_the_regions_of_a_kink_are_located_between_close_and_narrow_boundaries():
    from grader.answers.equivalence import kink_region_points

    x = sympy.Symbol("x", positive=True)
    points = kink_region_points([sympy.sign((x - 40) * (x - 41))], {x: POS}, {x: 1.0})
    assert any(40 < p[x] < 41 for p in points) and any(p[x] > 41 for p in points)
    # cos θ + 0.999 < 0 only within 0.045 of odd multiples of π, between two points of any grid
    near_pi = kink_region_points([sympy.sign(sympy.cos(theta) + sympy.Float("0.999"))], {theta: parse_domain("real")},
                                 {theta: 1.0})
    assert any(abs(p[theta] - sympy.pi.evalf()) < 0.045 for p in near_pi)
    assert kink_region_points([m * g * sympy.sqrt(2 * l / g)], {m: POS, g: POS, l: POS}, {m: 1.0, g: 1.0, l: 1.0}) == []


# -- red team 15 (2026-11-28): a difference below the 1024-bit confirmation -------------------------------------

_x, _y = sympy.symbols("x y", positive=True)
_TINY = sympy.Rational(1, 10**200)
_HUGE = sympy.Integer(10)**400


def _wide_sampler(y_domain="positive"):
    return Sampler({_x: POS, _y: parse_domain(y_domain)}, seed_for(["x", "y", y_domain]))


@pytest.mark.parametrize("reference, answer, y_domain, why", [
    (_x, _x * (1 + sympy.exp(-1000)), "positive", "relative 5e-435"),
    (_x, _x * sympy.tanh(2000), "positive", "tanh(2000) = 1 - 2e-1737"),
    (_x, _x * sympy.tanh(2000 * _y), "positive", "1 - tanh(2000 y) is below 2^-1024 wherever y > 0.18"),
    (_x, _x * (1 + sympy.exp(-_y)), [1000, 2000], "the domain's own scale puts e^-y below 1e-434"),
    (_x, _x * (1 + sympy.exp(-800 * _y)), [1, 2], "e^-800y < 1e-347"),
    (sympy.Integer(1), sympy.tanh(1000 * _x)**2, "positive", "1 - tanh²(1000 x) is 4 e^-2000x"),
    (sympy.Integer(1), sympy.cos(_TINY), "positive", "1 - cos(1e-200) = 5e-401"),
    (sympy.pi / 2, sympy.atan(_HUGE), "positive", "atan(1e400) = pi/2 - 1e-400"),
    (_x, _x * sympy.cos(sympy.exp(-300)), "positive", "1 - cos(e^-300) = 1.9e-261 (within 1024 bits already)"),
])
def test_a_difference_below_the_confirming_precision_is_found_at_the_expressions_range(reference, answer,
                                                                                        y_domain, why):
    result = compare_expressions(reference, answer, _wide_sampler(y_domain))
    assert result.equivalent is False and result.certainty == "proved", why


@pytest.mark.parametrize("reference, answer, y_domain", [
    (_x * sympy.tanh(2000), _x * (1 - sympy.exp(-4000)) / (1 + sympy.exp(-4000)), "positive"),
    (_x * sympy.tanh(2000 * _y), _x * (sympy.exp(4000 * _y) - 1) / (sympy.exp(4000 * _y) + 1), "positive"),
    (sympy.sinh(800 * _y), (sympy.exp(800 * _y) - sympy.exp(-800 * _y)) / 2, [1, 2]),
    (sympy.tanh(1000 * _x)**2, 1 - 1 / sympy.cosh(1000 * _x)**2, "positive"),
    (sympy.atan(_HUGE), sympy.pi / 2 - sympy.atan(1 / _HUGE), "positive"),
    (sympy.cos(_TINY), 1 - 2 * sympy.sin(_TINY / 2)**2, "positive"),
])
def test_the_same_values_written_otherwise_stay_equivalent_at_that_range(reference, answer, y_domain):
    result = compare_expressions(reference, answer, _wide_sampler(y_domain), Options(symbolic=False))
    assert result.equivalent is True


# -- red team 15: a kink region that only two variables off the ordinary scale reach together --------------------

_XY = {"x": {"dimension": "dimensionless", "domain": "real"}, "y": {"dimension": "dimensionless", "domain": "real"}}


@pytest.mark.parametrize("reference, answer, expected", [
    # -1 only within 1 of (1e4, 1e4): no single variable moved from an ordinary point gets there
    ("1", "sign((x - 1e4)^2 + (y - 1e4)^2 - 1)", "not_equivalent"),
    ("1", "sign((x - 1e4)^2 + (y + 3e3)^2 - 1)", "not_equivalent"),
    # a coupled valley: one variable at a time closes half the distance a round
    ("1", "sign((x - 1e4)^2 + (y - 1e4)^2 + (x - y)^2 - 1)", "not_equivalent"),
    ("(x - 1e4)^2 + (y - 1e4)^2 - 1", "abs((x - 1e4)^2 + (y - 1e4)^2 - 1)", "not_equivalent"),
    ("abs((x - 1e4)^2 + (y - 1e4)^2 - 1)",
     "((x - 1e4)^2 + (y - 1e4)^2 - 1)*sign((x - 1e4)^2 + (y - 1e4)^2 - 1)", "equivalent"),
    ("1", "sign((x - 1e4)^2 + (y - 1e4)^2 + 1)", "equivalent"),
])
def test_a_kink_region_reached_only_by_two_variables_off_scale_is_compared(reference, answer, expected):
    from grader.answers.checker import check

    verdict = check(reference, answer, _XY)
    assert verdict.verdict == expected, verdict.reason
    if expected == "not_equivalent":
        values = verdict.counterexample["values"]
        assert abs(values["x"]) > 100 and abs(values["y"]) > 100


# -- red team 15: a period that every sample point fits ---------------------------------------------------------

@pytest.mark.parametrize("reference, answer, expected", [
    # sin(2^60 π x) = 0 and cos(2^60 π x) = 1 at every float x above 2^-7: the floats' grid fits the period
    ("x", "x + sin(2^60*pi*x)", "not_equivalent"),
    ("x", "x*cos(2^60*pi*x)", "not_equivalent"),
    ("x", "x + sin(9007199254740992*pi*x)", "not_equivalent"),   # 2^53
    ("x", "x + tan(2^60*pi*x)", "not_equivalent"),
    ("x", "x + sin(2^53*pi*x)^2", "not_equivalent"),
    # right forms: one exact zero on the grid (no precision resolves it) is decided off it
    ("sin(2^60*pi*x)", "2*sin(2^59*pi*x)*cos(2^59*pi*x)", "equivalent"),
    ("1", "cos(2^60*pi*x)^2 + sin(2^60*pi*x)^2", "equivalent"),
])
def test_a_period_that_fits_every_float_is_compared_off_the_floats_grid(reference, answer, expected):
    from grader.answers.checker import check

    verdict = check(reference, answer, {"x": {"dimension": "dimensionless", "domain": "real"}})
    assert verdict.verdict == expected, verdict.reason
    if verdict.counterexample:
        assert all(isinstance(v, float) for v in verdict.counterexample["values"].values())  # JSON numbers


# -- red team 15: a reference defined only past the sampled magnitudes -------------------------------------------

@pytest.mark.parametrize("reference, answer, domain, expected", [
    # defined only for x >= 1e7, x >= 1e12, x <= 1e-9 or |x| >= 1e8: the boundary of its own argument says where
    ("sqrt(x - 1e7)", "sqrt(x/1e7 - 1)*sqrt(1e7)", "positive", "equivalent"),
    ("sqrt(x - 1e7)", "sqrt(x/1e7 - 1)*sqrt(1e7)*1.0001", "positive", "not_equivalent"),
    ("log(x - 1e12)", "log(x/1e12 - 1) + log(1e12)", "real", "equivalent"),
    ("log(x - 1e12)", "log(x/1e12 - 1) + log(1e12) + 1e-3", "real", "not_equivalent"),
    ("sqrt(1e-9 - x)", "sqrt(1 - x*1e9)*sqrt(1e-9)", "positive", "equivalent"),
    ("sqrt(1e-9 - x)", "sqrt(1 - x*1e9)*sqrt(1e-9)*1.0001", "positive", "not_equivalent"),
    ("acosh(x/1e8)", "log(x/1e8 + sqrt(x^2/1e16 - 1))", "positive", "equivalent"),
    ("acosh(x/1e8)", "log(x/1e8 + sqrt(x^2/1e16 - 1))*1.001", "positive", "not_equivalent"),
    ("asin(x - 10)", "acos(x - 10)", "real", "not_equivalent"),   # defined on [9, 11] only; equal at one point
    ("asin(x - 10)", "pi/2 - acos(x - 10)", "real", "equivalent"),
])
def test_a_reference_defined_only_past_the_sampled_magnitudes_is_compared_where_it_is_defined(reference, answer,
                                                                                            domain, expected):
    from grader.answers.checker import check

    verdict = check(reference, answer, {"x": {"dimension": "dimensionless", "domain": domain}})
    assert verdict.verdict == expected, verdict.reason
# Node types an answer can hold (elementary functions, E**x, which isinstance takes for an exp, an undefined
# function), against each class set the walks after agreement test with a memo per type.
@pytest.mark.parametrize("classes", [
    equivalence._BRANCHES, (sympy.log,), (sympy.acosh,), (sympy.asin, sympy.acos, sympy.atanh),
])
def test_the_remembered_instance_tests_agree_with_isinstance(classes):
    x = sympy.Symbol("x", real=True)
    nodes = [f(x) for f in (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc, sympy.asin, sympy.acos,
                            sympy.atan, sympy.acot, sympy.asec, sympy.acsc, sympy.sinh, sympy.cosh, sympy.tanh,
                            sympy.coth, sympy.asinh, sympy.acosh, sympy.atanh, sympy.exp, sympy.log, sympy.Abs,
                            sympy.sign, sympy.floor, sympy.ceiling, sympy.sqrt, sympy.Function("f"))]
    nodes += [sympy.atan2(x, m), sympy.E ** x, x, x ** 2, x + m, 2 * x, sympy.pi, sympy.Integer(3)]
    test = equivalence.instance_test(classes)
    for node in nodes + nodes:  # the second time from the memo
        assert test(node) == isinstance(node, classes), node


def test_no_instance_test_is_remembered_for_classes_whose_isinstance_looks_further():
    # E**x is a Pow, and an exp to isinstance: the answer cannot come from its type
    with pytest.raises(TypeError):
        equivalence.instance_test((sympy.exp,))


# Red team 17: a kink within 0.1% of a whole end of an interval. A region that narrow beside an end written with
# decimals (1.5708 for π/2) is left out, as the end's round value is meant; beside a whole end (0, 1) it is a
# region of the domain: |x - 0.001| is not x - 0.001 on [0, 1], which it was taken for.
UNIT = {"x": {"dimension": "dimensionless", "domain": [0, 1]}}
_NEAR_A_WHOLE_END = [
    ("abs(x - 1/1000)", "x - 1/1000", UNIT, "expression"),
    ("sqrt((x - 1/10^6)^2)", "x - 1/10^6", UNIT, "expression"),
    ("abs(x^2 - 1/10^8)", "x^2 - 1/10^8", UNIT, "expression"),
    ("abs(x - 0.9999)", "0.9999 - x", UNIT, "expression"),
    ("sign(x - 1/10^4)", "1", UNIT, "expression"),
    ("abs(x - 1/1000)", "x - 1/1000", {"x": {"dimension": "dimensionless", "domain": [0, 2]}}, "expression"),
    ("y = abs(x - 1/2000)", "y = x - 1/2000", {**UNIT, "y": {"dimension": "dimensionless", "domain": "real"}},
     "equation"),
]


@pytest.mark.parametrize("reference, answer, variables, kind", _NEAR_A_WHOLE_END)
def test_a_kink_within_a_thousandth_of_a_whole_end_is_compared_beside_it(reference, answer, variables, kind):
    from grader.answers.checker import check

    verdict = check(reference, answer, variables, kind=kind)
    assert verdict.verdict == "not_equivalent", verdict.reason
