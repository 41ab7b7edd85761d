"""check(): the verdict contract, dimensions in words, and no input that crashes it."""

import pytest

from grader.answers import Verdict, check
from grader.answers.checker import _prepare
from grader.answers.feedback import _reference_candidates

YOYO = {"m": {"dimension": "mass", "domain": "positive"},
        "g": {"dimension": "acceleration", "domain": "positive"},
        "R": {"dimension": "length", "domain": "positive"}}
SPHERE = {"m": {"dimension": "mass", "domain": "positive"},
          "g": {"dimension": "acceleration", "domain": "positive"},
          "theta": {"dimension": "angle", "domain": [-3.1416, 3.1416]}}
KEYS = {"verdict", "certainty", "reason", "parsed", "counterexample", "feedback", "ms"}


def test_verdict_json_has_the_contract_keys():
    v = check("m*g/3", "mg/3", YOYO)
    data = v.to_json()
    assert KEYS <= set(data) and set(data["parsed"]) == {"text", "latex", "notes"}
    assert data["verdict"] == "equivalent" and data["parsed"]["text"] == "g*m/3"
    assert Verdict.from_json(data).verdict == "equivalent"


@pytest.mark.parametrize("answer", ["mg(3cos θ - 2)", "3 m g cos(theta) - 2 m g", "m*g*(1 - 6*sin(theta/2)^2)"])
def test_sphere_normal_force_forms_are_accepted(answer):
    assert check("m*g*(3*cos(theta) - 2)", answer, SPHERE).verdict == "equivalent"


def test_a_wrong_sphere_answer_has_a_counterexample_with_both_values():
    v = check("m*g*(3*cos(theta) - 2)", "m*g*(3*cos(theta) - 1)", SPHERE)
    assert v.verdict == "not_equivalent" and v.certainty == "proved"
    example = v.counterexample
    assert set(example["values"]) == {"m", "g", "theta"}
    assert example["answer"] - example["reference"] == pytest.approx(example["values"]["m"] * example["values"]["g"])


@pytest.mark.parametrize("answer, words", [
    ("m*g/3 + R", "adds a length"),
    ("g/3", "should be a force"),
    ("m*g*R/3", "should be a force"),
    ("m*g*cos(R)", "dimensionless argument"),
])
def test_dimension_errors_are_wrong_and_said_in_words(answer, words):
    v = check("m*g/3", answer, YOYO)
    assert v.verdict == "not_equivalent" and v.certainty == "proved"
    assert words in v.reason and v.feedback[0]["code"] == "dimension"


@pytest.mark.parametrize("answer", ["m*g/", "M*g/3", "x", "", "m*g/3 = 0", "1/0", "factorial(3)"])
def test_unreadable_answers_are_invalid_with_a_reason(answer):
    v = check("m*g/3", answer, YOYO)
    assert v.verdict == "invalid" and v.certainty == "none" and v.reason


@pytest.mark.parametrize("answer", ["m*g*sqrt(-1)", "sqrt(-m)*sqrt(m)*g/3", "m*g*log(-1)"])
def test_non_real_answers_are_refused_as_not_real(answer):
    # The parser refuses a root or logarithm of a negative quantity, with the reason in words.
    v = check("m*g/3", answer, YOYO)
    assert v.verdict == "invalid" and "not a real number" in v.reason


@pytest.mark.parametrize("reference, variables, kind", [
    (None, YOYO, "expression"),
    ("m*g/3", "not a dict", "expression"),
    ("m*g/3", {"m": {"dimension": "wibble"}}, "expression"),
    ("m*g/(", YOYO, "expression"),
    ("m*g/3", YOYO, "poem"),
])
def test_bad_requests_give_invalid_verdicts_not_exceptions(reference, variables, kind):
    v = check(reference, "m*g/3", variables, kind=kind)
    assert v.verdict == "invalid"


def test_an_inconsistent_reference_does_not_blame_the_student():
    # m*g + m adds a force to a mass; the student's m*(g + 1) is the same expression, so it is
    # judged equal (not refused for the reference's dimensions), with a note saying why.
    v = check("m*g + m", "m*(g + 1)", YOYO)
    assert v.verdict == "equivalent"
    assert any("dimensions not checked" in n for n in v.parsed["notes"])


def test_typical_check_takes_milliseconds():
    check("m*g/3", "mg/3", YOYO)
    v = check("m*g*(3*cos(theta) - 2)", "m*g*(1 - 6*sin(theta/2)^2)", SPHERE)
    assert v.ms < 100


def test_a_verdict_does_not_depend_on_the_answers_checked_before():
    # Per-reference work (parsed reference, sample points, feedback candidates and their values)
    # is cached; an answer checked after others must get exactly the verdict it gets first.
    answers = ["m*g*(3*sin(theta) - 2)", "2*m*g*(3*cos(theta) - 2)", "m*g*(3*cos(theta) - 2) + m*g",
               "mg(3cos θ - 2)", "m*g*(2 - 3*cos(theta))", "3*m*g*cos(theta)"]
    reference = "m*g*(3*cos(theta) - 2)"

    def verdict(answer):
        data = check(reference, answer, SPHERE).to_json()
        data.pop("ms")
        return data

    _prepare.cache_clear()  # so that "first" is checked against a cold reference, as in a fresh process
    _reference_candidates.cache_clear()
    first = {a: verdict(a) for a in answers}
    assert {a: verdict(a) for a in reversed(answers)} == first


CART = {"M": {"dimension": "kg", "domain": "positive"}, "m": {"dimension": "kg", "domain": "positive"},
        "g": {"dimension": "m*s^-2", "domain": "positive"}, "R": {"dimension": "m", "domain": "positive"},
        "a": {"dimension": "m", "domain": "positive"}, "theta0": {"dimension": "dimensionless", "domain": [0.01, 1.5]}}
CART_SPEED = "2*m*sqrt(g*(1 - cos(theta0))*(R - a))/sqrt((M + m)*(3*M + m))"


@pytest.mark.parametrize("answer, below, expected", [
    # a cylinder of radius a rolling in a hollow of radius R > a: |R − a| is R − a where the scene lives
    ("2 m sqrt(g (1 - cos(theta0)) abs(R - a))/sqrt((M + m)(3M + m))", "R", "equivalent"),
    ("4 m sin(theta0/2) sqrt(g (R - a)/2)/sqrt((M + m)(3M + m))", "R", "equivalent"),
    ("2 m sqrt(g (1 - cos(theta0)) (R + a))/sqrt((M + m)(3M + m))", "R", "not_equivalent"),
    # without the relation a > R is in the domain, where only |R − a| is defined
    ("2 m sqrt(g (1 - cos(theta0)) abs(R - a))/sqrt((M + m)(3M + m))", None, "not_equivalent"),
])
def test_answers_are_compared_only_where_a_variable_declared_below_another_is(answer, below, expected):
    variables = {**CART, "a": {**CART["a"], "below": below}} if below else CART
    assert check(CART_SPEED, answer, variables).verdict == expected


@pytest.mark.parametrize("below, message", [
    ("L", "must name another variable"), ("a", "must name another variable"), ("g", "another dimension"),
    (3, "must name another variable"),
])
def test_a_below_relation_must_name_another_variable_of_the_same_dimension(below, message):
    verdict = check(CART_SPEED, "0", {**CART, "a": {**CART["a"], "below": below}})
    assert verdict.verdict == "invalid" and message in verdict.reason


@pytest.mark.parametrize("a_domain, r_domain, message", [
    # no value of a below any of R: refused before any point is drawn
    ([5, 6], [1, 2], "no values of its domain are below"),
    ([2, 3], [1, 2], "no values of its domain are below"),
    # an order that few points keep, none of 17 draws nor their swaps: said, never compared outside it
    ([5, 100], [1, 5.01], "keeps a < R"),
])
def test_an_order_the_domains_cannot_keep_is_refused_never_compared_outside(a_domain, r_domain, message):
    variables = {**CART, "a": {"dimension": "m", "domain": a_domain, "below": "R"},
                 "R": {"dimension": "m", "domain": r_domain}}
    verdict = check(CART_SPEED, CART_SPEED, variables)
    assert verdict.verdict == "invalid" and message in verdict.reason


DRAG = {"c": {"dimension": "mass/length", "domain": "positive"}, "v": {"dimension": "velocity", "domain": [-1, 10]}}
PENDULUM = {"g": {"dimension": "acceleration", "domain": "positive"}, "l": {"dimension": "length", "domain": "positive"},
            "theta": {"dimension": "angle", "domain": [-3.1416, 3.1416], "kind": "coordinate"},
            "thetadot": {"dimension": "angular_velocity", "domain": "real", "kind": "velocity"},
            "thetaddot": {"dimension": "angular_acceleration", "domain": "real", "kind": "acceleration"}}
PENDULUM_ONE_SIDE = {**PENDULUM, "theta": {**PENDULUM["theta"], "domain": [-0.2, 3.1416]}}
SMALL = {"R": {"dimension": "length", "domain": "positive"}, "theta": {"dimension": "angle", "domain": [1e-11, 1e-10]}}
TINY_X = {"x": {"dimension": "dimensionless", "domain": [1e-13, 1e-12]}}
WEIGHT = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"}}
PENDULUM_EOM = "thetaddot = -(g/l)*sin(theta)"


@pytest.mark.parametrize("reference, answer, variables, kind", [
    # wrong only where ordinary points of an interval seldom go: near zero, on its short side, at its ends
    ("-c*v*abs(v)", "-c*v^2", DRAG, "expression"),
    ("-c*v", "-c*abs(v)", DRAG, "expression"),
    ("theta", "acos(cos(theta))", {"theta": {"dimension": "angle", "domain": [0, 3.3]}}, "expression"),
    (PENDULUM_EOM, "thetaddot = -(g/l)*sin(theta)*sign(abs(theta) - 0.25)", PENDULUM, "equation"),
    (PENDULUM_EOM, "(sign(abs(theta) - 0.1) + 1) thetaddot = -(g/l) sin(theta) (sign(abs(theta) - 0.1) + 1)",
     PENDULUM, "equation"),
    (PENDULUM_EOM, "thetaddot = -(g/l)*sqrt(1 - cos(theta)^2)", PENDULUM_ONE_SIDE, "equation"),
    # a value that cancels far below its terms is compared to its own digits, not to its terms'
    ("R*(1 - cos(theta))", "R*theta^2/2", SMALL, "expression"),
    ("cos(x) - 1 + x^2/2", "0", TINY_X, "expression"),
    ("cos(x) - 1 + x^2/2", "-x^4/24", TINY_X, "expression"),
    ("exp(x) - 1", "x + x^2/2", {"x": {"dimension": "dimensionless", "domain": [1e-14, 1e-13]}}, "expression"),
    # differences below the judge's 30 digits that no symbolic step isolates
    ("m*g", "m g sqrt(1 + 10^-40)", WEIGHT, "expression"),
    ("m*g", "m g cos(10^-20)", WEIGHT, "expression"),
    ("m*g", "m g (1 - exp(-100))", WEIGHT, "expression"),
    ("m*g", "m g tanh(100)", WEIGHT, "expression"),
    ("m*g", "m g exp(10^-40)", WEIGHT, "expression"),
    (PENDULUM_EOM, "thetaddot = -(g/l)*sin(theta*(1 + 10^-40))", PENDULUM, "equation"),
])
def test_answers_wrong_only_where_few_points_look_are_proved_wrong(reference, answer, variables, kind):
    verdict = check(reference, answer, variables, kind=kind)
    assert verdict.verdict == "not_equivalent", verdict.reason


@pytest.mark.parametrize("reference, answer, variables", [
    ("R*(1 - cos(theta))", "2*R*sin(theta/2)^2", SMALL),
    ("cos(x) - 1 + x^2/2", "2*sin(x/2)^4 - 2*sin(x/2)^2 + x^2/2 - 2*sin(x/2)^4 + 0", TINY_X),
    ("-c*v*abs(v)", "-c*v*sqrt(v^2)", DRAG),
    ("x", "sin(x)^2 + cos(x)^2 - 1 + x", {"x": {"dimension": "dimensionless", "domain": "real"}}),
])
def test_equal_answers_with_heavy_cancellation_stay_equivalent(reference, answer, variables):
    verdict = check(reference, answer, variables)
    assert verdict.verdict == "equivalent", verdict.reason


@pytest.mark.parametrize("reference, answer", [
    # constants whose typed form has a real domain to check (asin's argument in [-1, 1]): decided by
    # the points, never "differs by a constant" with a zero difference
    ("2*asin(1)", "2*asin(1)"), ("pi", "2*asin(1)"), ("pi/3", "2*asin(1/2)"), ("2*pi/3", "2*acos(1/2)"),
    ("pi", "asin(1) + asin(1)"), ("2", "2*sin(asin(1))"), ("2", "2*acosh(cosh(1))"), ("pi + 1", "2*asin(1) + 1"),
])
def test_a_constant_with_a_domain_to_check_is_equal_to_its_value(reference, answer):
    assert check(reference, answer, {}).verdict == "equivalent"


@pytest.mark.parametrize("reference, answer", [("pi", "2*asin(1) + 10^-50"), ("2", "2*acosh(cosh(1)) + 1")])
def test_a_constant_with_a_domain_that_differs_is_still_proved_wrong(reference, answer):
    assert check(reference, answer, {}).verdict == "not_equivalent"


_ROD = {"r0": {"dimension": "length", "domain": "positive", "below": "L"}, "L": {"dimension": "length", "domain": "positive"},
        "omega": {"dimension": "angular_velocity", "domain": "positive"}, "v0": {"dimension": "velocity", "domain": "real"},
        "t": {"dimension": "time", "domain": "nonnegative", "kind": "time"}}
_ROD_MOTION = "r0*cosh(omega*t) + v0/omega*sinh(omega*t)"


@pytest.mark.parametrize("answer, close", [
    # a sinh/cosh swap or a wrong start agrees with a growing solution where ωt is large, and is far off
    # at t = 0: never "close" (it was, from the counterexample at ωt = 6 alone)
    ("r0*cosh(omega*t) + v0/omega*cosh(omega*t)", False),
    ("r0*sinh(omega*t) + v0/omega*cosh(omega*t)", False),
    ("(r0 + v0/omega)/2*exp(omega*t) + (r0 + v0/omega)/2*exp(-omega*t)", False),
    # a rounded coefficient is close everywhere
    ("r0*cosh(omega*t) + 1.00001*v0/omega*sinh(omega*t)", True),
    ("1.0001*r0*cosh(omega*t) + v0/omega*sinh(omega*t)", True),
])
def test_an_answer_is_called_close_only_where_it_is_close_at_every_ordinary_point(answer, close):
    verdict = check(_ROD_MOTION, answer, _ROD)
    assert verdict.verdict == "not_equivalent"
    assert ("close" in [f["code"] for f in verdict.feedback]) is close


# -- red team 2026-11-10b: an answer undefined on a part of the domain set by two variables --------

_TWO = {"x": {"dimension": "dimensionless", "domain": [-2, 3]}, "a": {"dimension": "dimensionless", "domain": "positive"}}


@pytest.mark.parametrize("reference", ["(a + x)^2", "(a+x)^2", "(x + a)^2", "(x+a)^2", "a^2 + 2*a*x + x^2", "(a+x)*(a+x)"])
@pytest.mark.parametrize("answer", ["exp(2*log(a+x))", "sqrt(a+x)^4", "(sqrt(a+x))^2*(a+x)", "exp(log(a+x))^2",
                                    "(a+x)^(3/2)*sqrt(a+x)", r"e^{2 \log{\left(a + x \right)}}"])
def test_an_answer_undefined_where_x_is_below_minus_a_is_refused_whatever_the_seed(reference, answer):
    # a + x < 0 for x in [-2, -a): a good part of the plane, which eight points can all miss
    verdict = check(reference, answer, _TWO)
    assert verdict.verdict == "not_equivalent" and "undefined" in verdict.reason
    assert verdict.counterexample["values"]["a"] + verdict.counterexample["values"]["x"] <= 0


@pytest.mark.parametrize("reference, answer", [
    ("exp(2*log(a+x))", "(a+x)^2"), ("exp(2*log(x+a))", "x^2 + 2*a*x + a^2"),
])
def test_an_answer_defined_where_the_reference_is_not_is_refused_whatever_the_seed(reference, answer):
    verdict = check(reference, answer, _TWO)
    assert verdict.verdict == "not_equivalent" and "defined at a point" in verdict.reason


@pytest.mark.parametrize("reference, answer", [
    ("(a + x + 2)^2", "exp(2*log(a+x+2))"), ("sqrt(a*(x+2))", "sqrt(a)*sqrt(x+2)"),
    ("sqrt(1 - x^2/9)", "sqrt(1 - x/3)*sqrt(1 + x/3)"), ("asin(x/3)", "atan(x/sqrt(9 - x^2))"),
])
def test_an_answer_restricted_only_outside_the_domain_is_still_right(reference, answer):
    assert check(reference, answer, _TWO).verdict == "equivalent"


@pytest.mark.parametrize("answer", ["m*g*sqrt(cos(atan(1e-200)))/3", "m*g*(cos(atan(1e-200)))^(1/2)/3",
                                    "m*g*cos(atan(1e-200))^(1/3)/3"])
def test_an_exact_number_sympy_cannot_test_for_a_perfect_power_is_refused_not_an_internal_error(answer):
    # cos(atan(1e-200)) is (1 + 10^-400)^(-1/2); a root of it sends sympy's perfect-power test into float overflow
    v = check("m*g/3", answer, YOYO)
    assert v.verdict == "invalid" and "internal error" not in v.reason and "too large" in v.reason


# g's value typed for g (red team 19): m·9.81 for m g was told only "Your answer is a mass (kg), but the answer
# should be a force", true, and no help to a student who wrote g's value; now the slip is named too.
GRAVITY = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"},
           "h": {"dimension": "length", "domain": "positive"}, "t": {"dimension": "time", "domain": "positive"},
           "l": {"dimension": "length", "domain": "positive"},
           "theta": {"dimension": "angle", "domain": "real", "kind": "coordinate"},
           "thetaddot": {"dimension": "angular_acceleration", "domain": "real", "kind": "acceleration"}}


@pytest.mark.parametrize("reference, answer, kind, named", [
    ("m*g", "m*9.81", "expression", True),
    ("m*g", "9.8 m", "expression", True),
    ("m*g*h", "9.81 m h", "expression", True),
    ("sqrt(2*g*h)", "sqrt(19.62 h)", "expression", True),     # 2g, read under the root as 4.43·√h
    ("g*t^2/2", "4.9 t^2", "expression", True),               # g/2
    ("thetaddot = -g/l*sin(theta)", "thetaddot = -9.81/l*sin(theta)", "equation", True),
    ("m*g", "10 m", "expression", False),                     # 10 is any number: the dimension alone is said
    ("m*g", "m*9.81 + m", "expression", False),               # g for 9.81 does not mend it
    ("thetaddot = -g/l*sin(theta)", "thetaddot = -9.81*sin(theta)", "equation", False),
])
def test_a_number_for_g_is_named_beside_the_wrong_dimension(reference, answer, kind, named):
    v = check(reference, answer, GRAVITY, kind=kind)
    codes = [f["code"] for f in v.feedback]
    assert v.verdict == "not_equivalent" and codes[0] == "dimension"
    assert ("g_value" in codes) == named


# An equation of motion with no acceleration in it (red team 19): d/dt(m r² φ̇) = m r² φ̈ is 2 m r ṙ φ̇ = 0, which
# relates the state only; "not combinations of the reference equations with coefficients free of the state"
# was all a student heard, as if another factor might have made it right.
POLAR = {"m": {"dimension": "mass", "domain": "positive"}, "k": {"dimension": "kg/s^2", "domain": "positive"},
         "r": {"dimension": "length", "domain": "positive", "kind": "coordinate"},
         "rdot": {"dimension": "velocity", "domain": "real", "kind": "velocity"},
         "rddot": {"dimension": "acceleration", "domain": "real", "kind": "acceleration"},
         "phi": {"dimension": "angle", "domain": "real", "kind": "coordinate"},
         "phidot": {"dimension": "angular_velocity", "domain": "real", "kind": "velocity"},
         "phiddot": {"dimension": "angular_acceleration", "domain": "real", "kind": "acceleration"}}
POLAR_EOM = "rddot = r*phidot^2 - k/m*r; phiddot = -2*rdot*phidot/r"


@pytest.mark.parametrize("reference, answer, says", [
    (POLAR_EOM, "m (r̈ - r φ̇²) = -k r; d/dt(m r² φ̇) = m r² φ̈", "Your equation 2 has no acceleration"),
    (POLAR_EOM, "2 m r ṙ φ̇ = 0; m (r̈ - r φ̇²) = -k r", "Your equation 1 has no acceleration"),
    ("phiddot = -2*rdot*phidot/r", "2 m r ṙ φ̇ = 0", "Your equation has no acceleration"),
    (POLAR_EOM, "m r̈ = m r φ̇² + k r; d/dt(m r² φ̇) = 0", None),   # a wrong sign, accelerations in both
    ("phiddot = -2*rdot*phidot/r", "r φ̈ = 2 ṙ φ̇", None),
])
def test_an_equation_of_motion_without_an_acceleration_is_said_to_be_one(reference, answer, says):
    v = check(reference, answer, POLAR, kind="equation")
    assert v.verdict == "not_equivalent"
    notes = [f["message"] for f in v.feedback if f["code"] == "no_acceleration"]
    assert (notes[0].startswith(says) if says else notes == [])
