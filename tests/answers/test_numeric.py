"""Numeric answers (grader.answers.numeric): a number with its unit against the engine's value at the
student's numbers, with the scene's tolerance; routed through check(), like every other answer."""

import json
import math

import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from grader.answers.checker import check, check_request
from grader.answers.numeric import QuantityError, parse_quantity, within_tolerance
from grader.answers.reference import ReferenceAnswer
from grader.cli.check import check as check_cli

VARIABLES = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"}}
VALUES = {"m": 1.5, "g": 9.81}  # the weight m*g is 14.715 N
WEIGHT = dict(reference="m*g", variables=VARIABLES, kind="numeric", values=VALUES, unit="N")


# -- reading the student's number ---------------------------------------------------------------

@pytest.mark.parametrize("text, number", [
    ("14.7", 14.7), ("14.7 N", 14.7), ("14.7N", 14.7), ("  14.7   N ", 14.7),
    ("1.47e1 N", 14.7), ("1.47E+1 N", 14.7), ("147e-1 N", 14.7),
    ("1.47×10^1 N", 14.7), ("1.47 × 10^1 N", 14.7), ("1.47·10¹ N", 14.7), ("1.47*10**1 N", 14.7),
    ("1.47 x 10^1 N", 14.7), ("1.47×10^(1) N", 14.7), ("1.47×10⁻¹ N", 0.147),
    ("−14.7 N", -14.7), ("-14.7 N", -14.7), ("+14.7 N", 14.7), (".5 m", 0.5), ("5. m", 5.0), ("0 N", 0.0),
    # more ways to write a power of ten: another times sign, a power of ten alone
    ("1.47 ⋅ 10^1 N", 14.7), ("1.47∙10^1 N", 14.7), ("1.47X10^1 N", 14.7), ("10^3 N", 1000.0), ("10^-3 m", 1e-3),
    ("10**2 N", 100.0), ("10⁻³ m", 1e-3), ("-10^2 N", -100.0),
    # a name for the quantity, or "about", before the number; a full stop after the unit
    ("F = 14.7 N", 14.7), ("T=14.7N", 14.7), ("≈ 14.7 N", 14.7), ("~14.7 N", 14.7), ("F ≈ 14.7 N", 14.7),
    ("ω = 5 rad/s", 5.0), ("v(t) = 5 m/s", 5.0), ("14.7 N.", 14.7), ("14.7.", 14.7), ("5 1/s", 5.0),
])
def test_number_forms(text, number):
    assert parse_quantity(text).number == pytest.approx(number, rel=1e-15)


@pytest.mark.parametrize("text, message", [
    ("14,7 N", "decimal point, not a comma: 14.7, not 14,7"),
    ("1,000 N", "without commas: 1000 .or 1.000 if the comma is a decimal point"),
    ("14,715 N", "without commas: 14715 .or 14.715 if the comma is a decimal point"),
    ("1,000.5 N", "no thousands separators, such as 1000.5"), ("1.000,5 N", "no thousands separators"),
    ("1,000,000.0 N", "no thousands separators"),
    ("", "type a number"),
    ("N", "type a number first"),
    ("abc", "type a number first"),
    ("one newton", "type a number first"),
    ("1 000 N", "without spaces"),
    ("3/2 N", "not a calculation"),
    ("9.81*1.5 N", "not a calculation"),
    ("14.7 + 1 N", "not a calculation"),
    ("1e999 N", "too large"),
    ("inf", "type a number first"),
    ("nan N", "type a number first"),
    ("14.7 Nms", "could be N*ms or N*m*s"),
    ("1e-999 N", "too small"),
    ("π/6", "not in terms of π"), ("pi/6 rad", "not in terms of π"),
    ("1.5 kg × 9.81 m/s²", "not a calculation"), ("1.47 10^1 N", "without spaces"),
    ("14.7 N (upward)", "'upward' is not a unit"), ("14.7 n", "did you mean N?"),
    ("14.7 xyz", "unknown unit 'xyz'"),
    ("14.7 N^", "unit is not readable"),
    ("1" * 300, "at most 200 characters"),
    # a British raised decimal point, and characters that look like what they are not, named
    ("14·7 N", "'14·7' reads as the decimal 14.7 or as a product: type 14.7"),
    ("14.7 N\u200b", "ZERO WIDTH SPACE"), ("14.7 \u041d", "CYRILLIC CAPITAL LETTER EN"),
    ("14.7 \u039d", "GREEK CAPITAL LETTER NU"), ("\u201c14.7 N\u201d", "delete the quotation marks"),
    ("14.7 [N", "unit is not readable"),
])
def test_unreadable_numbers_are_refused_with_what_to_type(text, message):
    with pytest.raises(QuantityError, match=message.replace("*", r"\*").replace("+", r"\+")):
        parse_quantity(text)


@pytest.mark.parametrize("text, si, dimension", [
    ("1 km", 1000.0, "length"), ("1 cm", 0.01, "length"), ("1 mm", 1e-3, "length"), ("1 µm", 1e-6, "length"),
    ("1 g", 1e-3, "mass"), ("1 mg", 1e-6, "mass"), ("1 kg", 1.0, "mass"),
    ("1 min", 60.0, "time"), ("1 h", 3600.0, "time"), ("1 ms", 1e-3, "time"), ("1 µs", 1e-6, "time"),
    ("36 km/h", 10.0, "velocity"), ("1 m/s", 1.0, "velocity"), ("1 m s^-1", 1.0, "velocity"),
    ("1 kN", 1000.0, "force"), ("1 kg*m/s^2", 1.0, "force"), ("1 kg m/s²", 1.0, "force"), ("1 kg·m·s⁻²", 1.0, "force"),
    ("1 N*m", 1.0, "torque"), ("1 mJ", 1e-3, "energy"), ("1 kW", 1000.0, "power"), ("1 kPa", 1000.0, "kg/(m*s^2)"),
    ("1 MHz", 1e6, "frequency"), ("1 /s", 1.0, "frequency"), ("1 rad/s", 1.0, "angular_velocity"),
    ("1 [N]", 1.0, "force"), ("1 [kg m/s^2]", 1.0, "force"),  # a unit in brackets, as in a table's header
    ("1·10³ m", 1000.0, "length"),
    ("180 deg", math.pi, "angle"), ("180°", math.pi, "angle"), ("1 mrad", 1e-3, "angle"), ("2", 2.0, "dimensionless"),
    # units outside SI that textbooks still print, and the prefix deca
    ("1 rev", 2 * math.pi, "angle"), ("2 revolutions", 4 * math.pi, "angle"), ("60 arcmin", math.pi / 180, "angle"),
    ("3600 arcsec", math.pi / 180, "angle"), ("100 grad", math.pi / 2, "angle"), ("100 gon", math.pi / 2, "angle"),
    ("1 rev/min", math.pi / 30, "angular_velocity"), ("1 daN", 10.0, "force"), ("1 decanewton", 10.0, "force"),
    ("1e5 dyn", 1.0, "force"), ("1 dynes", 1e-5, "force"), ("1 kgf", 9.80665, "force"),
    ("1 lbf", 4.4482216152605, "force"),
])
def test_units_convert_to_si(text, si, dimension):
    from grader.expressions import parse_dimension

    quantity = parse_quantity(text)
    assert quantity.si == pytest.approx(si, rel=1e-12)
    assert quantity.dimension == parse_dimension(dimension)


@pytest.mark.parametrize("minus", ["\u2010", "\u2011", "\u2014"])  # hyphen, non-breaking hyphen, em dash
@pytest.mark.parametrize("form", ["{m}14.7 N", "{m}1.47e1 N", "-1.47e{m}2 kN", "{m}1.47×10^{m}2 kN"])
def test_every_dash_a_formula_reads_as_a_minus_is_one_in_a_number(minus, form):
    # a word processor's or PDF's dash for a typed minus, as the formula's tokens read it (OPERATOR_CHARS)
    assert parse_quantity(form.format(m=minus)).si == pytest.approx(-14.7, rel=1e-12)


@pytest.mark.parametrize("text", ["14.7 N;", "14.7 N ;", "14.7;", "1.47e1 kg*m/s^2;", "14.7 N.;"])
def test_a_closing_semicolon_is_ignored_as_in_a_formula(text):
    # MATLAB's and Maxima's statements end with ';': as m*g/3; and θ̈ = -g/l sin θ; are read
    assert parse_quantity(text).si == pytest.approx(14.7, rel=1e-12)


@pytest.mark.parametrize("text, figures", [
    ("14.7", 3), ("14.70", 4), ("0.0147", 3), ("1.47e1", 3), ("1500", 4), ("0.5", 1), ("0", 1), ("1.470×10^1", 4),
])
def test_significant_figures_are_counted_as_typed(text, figures):
    assert parse_quantity(text).sig_figs == figures


# -- tolerances ----------------------------------------------------------------------------------

@pytest.mark.parametrize("value, tolerance, ok", [
    (14.8, {"relative": 0.01}, True), (14.86, {"relative": 0.01}, True), (14.87, {"relative": 0.01}, False),
    (14.8, {}, True), (15.0, {}, False),  # no band given: 1 % relative
    (14.8, {"absolute": 0.1}, True), (14.9, {"absolute": 0.1}, False),
    (14.9, {"absolute": 0.1, "relative": 0.02}, True),  # either band is enough
    (14.7, {"sig_figs": 3}, True), (14.72, {"sig_figs": 3}, True), (14.66, {"sig_figs": 3}, True),
    (14.6, {"sig_figs": 3}, False), (14.8, {"sig_figs": 3}, False), (15.0, {"sig_figs": 2}, True),
    (14.7, {"sig_figs": 4}, False), (14.72, {"sig_figs": 4}, True),
    (14.7, {"sig_figs": 3, "relative": 1e-4}, False),  # both must hold when both are given
])
def test_tolerance(value, tolerance, ok):
    assert within_tolerance(value, 14.715, tolerance) is ok


def test_significant_figures_are_counted_in_the_students_unit():
    # 0.0147 kN is 14.7 N: three figures either way.
    assert within_tolerance(14.7, 14.715, {"sig_figs": 3}, size=1000.0)
    assert not within_tolerance(15.0, 14.715, {"sig_figs": 3}, size=1000.0)


# -- verdicts ------------------------------------------------------------------------------------

@pytest.mark.parametrize("answer", ["14.7 N", "14.715 N", "1.47e1 kg*m/s^2", "0.0147 kN", "1471.5 cN", "14.7 kg m/s²",
                                    "1.4715×10^1 N", "1.4715 daN", "1.4715e6 dyn", "1.5005 kgf", "3.308 lbf"])
def test_right_values_in_any_unit_of_a_force_are_equivalent(answer):
    verdict = check(answer=answer, **WEIGHT)
    assert (verdict.verdict, verdict.certainty) == ("equivalent", "numeric"), verdict.reason


@pytest.mark.parametrize("answer", [
    # as an equation editor or a LaTeX source writes a number and its unit
    r"14.715\,\mathrm{N}", r"14.715\ \mathrm{N}", r"14.715 \mathrm{N}", r"14.715\text{ N}", r"14.715~\text{N}",
    r"14.715\;N", r"14.715\quad N", r"1.4715\times10^{1}\,\mathrm{N}", r"1.4715 \cdot 10^{1} N", r"$14.715$ N",
    r"\SI{14.715}{N}", r"\qty{14.715}{N}", r"14.715\ \mathrm{kg\cdot m/s^{2}}",
    r"F_{N} = 14.715\ \mathrm{N}", r"\(14.715\,\mathrm{N}\)", r"14.715\,\mathrm{kg}\,\frac{m}{s^{2}}",
])
def test_a_number_and_unit_in_latex_read_as_typed_plainly(answer):
    verdict = check(answer=answer, **WEIGHT)
    assert (verdict.verdict, verdict.certainty) == ("equivalent", "numeric"), verdict.reason


@pytest.mark.parametrize("answer, message", [
    (r"1\,000\,\mathrm{N}", "without spaces inside it"),  # SI's thin space between thousands: said, not guessed
    (r"14.715\,\mathrm{furlong}", "the unit is not readable"),
])
def test_latex_that_reads_as_no_quantity_is_refused_with_what_to_type(answer, message):
    verdict = check(answer=answer, **WEIGHT)
    assert verdict.verdict == "invalid" and message in verdict.reason


@pytest.mark.parametrize("answer, code, message", [
    ("15.5 N", None, None),
    ("-14.7 N", "sign", "sign"),
    ("147 N", "power_of_ten", "power of ten"),
    ("1.47 N", "power_of_ten", "power of ten"),
    ("14.7 m", "dimension", "Your unit m is a length (m); the answer is a force (kg·m/s²)."),
    ("14.7 kg", "dimension", "is a mass"),
    ("14.7 J", "dimension", "an energy or torque"),
])
def test_wrong_values_and_wrong_units_are_not_equivalent(answer, code, message):
    verdict = check(answer=answer, **WEIGHT)
    assert verdict.verdict == "not_equivalent"
    codes = [f["code"] for f in verdict.feedback]
    assert codes == ([code] if code else [])
    if message:
        assert message in verdict.feedback[0]["message"]


def test_a_missing_unit_is_invalid_and_says_which_quantity_is_asked():
    verdict = check(answer="14.7", **WEIGHT)
    assert verdict.verdict == "invalid"
    assert verdict.reason == "give a unit: the answer is a force (kg·m/s²), for example in N"
    assert verdict.feedback[0]["code"] == "missing_unit"


def test_a_pure_number_needs_no_unit_and_refuses_one():
    pure = dict(WEIGHT, reference="m*g/(m*g)", unit="")
    assert check(answer="1.0", **pure).verdict == "equivalent"
    assert check(answer="1.0 N", **pure).feedback[0]["message"] == (
        "Your unit N is a force (kg·m/s²); the answer is a pure number.")


def test_an_angle_in_degrees_converts():
    angle = dict(WEIGHT, reference="asin(m/(2*m))", unit="rad")
    assert check(answer="30°", **angle).verdict == "equivalent"
    assert check(answer="0.5236 rad", **angle).verdict == "equivalent"
    assert check(answer="30", **angle).verdict == "not_equivalent"  # 30 rad: no unit on a pure number is radians


def test_a_decimal_comma_is_invalid_with_the_corrected_number():
    verdict = check(answer="14,7 N", **WEIGHT)
    assert verdict.verdict == "invalid" and "14.7, not 14,7" in verdict.reason


def test_too_few_significant_figures_are_refused_when_the_scene_asks_for_them():
    verdict = check(answer="15 N", tolerance={"sig_figs": 3}, **WEIGHT)
    assert verdict.verdict == "not_equivalent" and verdict.feedback[0]["code"] == "sig_figs"
    assert check(answer="14.7 N", tolerance={"sig_figs": 3}, **WEIGHT).verdict == "equivalent"


def test_the_students_own_numbers_decide():
    # The same text is right for one student and wrong for another.
    assert check(answer="14.7 N", **WEIGHT).verdict == "equivalent"
    assert check(answer="14.7 N", **dict(WEIGHT, values={"m": 2.0, "g": 9.81})).verdict == "not_equivalent"


@pytest.mark.parametrize("answer", ["15.5 N", "-14.7 N", "147 N", "14.7 m", "14.7"])
def test_messages_never_state_the_expected_value(answer):
    text = json.dumps(check(answer=answer, **WEIGHT).to_json())
    assert "14.715" not in text and "14.72" not in text


def test_instructor_feedback_is_matched_numerically_at_the_students_numbers():
    feedback = [{"expr": "m*g/3", "message": "That is a third of the weight.", "score": 0.5}]
    verdict = check(answer="4.9 N", feedback=feedback, **WEIGHT)
    assert verdict.verdict == "not_equivalent" and verdict.score == 0.5
    assert verdict.feedback == [{"code": "instructor", "message": "That is a third of the weight.", "score": 0.5}]
    assert check(answer="5.5 N", feedback=feedback, **WEIGHT).score is None


@pytest.mark.parametrize("change, reason", [
    ({"values": {"m": 1.5}}, "no number for 'g'"),
    ({"unit": "m"}, "is not a force"),
    ({"unit": "furlong"}, "bad unit"),
    ({"tolerance": {"relative": -1}}, "tolerance.relative"),
    ({"tolerance": {"sig_figs": 0}}, "sig_figs"),
    ({"tolerance": {"ulps": 3}}, "tolerance"),
    ({"reference": "m*g*"}, "the reference does not parse"),
    ({"reference": "sqrt(-m)"}, "not a real number"),
])
def test_a_wrong_request_is_invalid_not_a_crash(change, reason):
    request = {**WEIGHT, "dimension": "force", **change}
    verdict = check(answer="14.7 N", **request)
    assert verdict.verdict == "invalid" and reason in verdict.reason


def test_check_request_and_grader_check_jsonl_handle_numeric_answers():
    line = {"answer": "14.7 N", **WEIGHT, "tolerance": {"relative": 0.01}, "dimension": "force"}
    assert check_request(line)["verdict"] == "equivalent"
    lines = [json.dumps(line), json.dumps({**line, "answer": "14.7 m"})]
    result = CliRunner().invoke(check_cli, ["--jsonl", "--no-sandbox"], input="\n".join(lines) + "\n")
    assert result.exit_code == 0, result.output
    assert [json.loads(r)["verdict"] for r in result.output.splitlines()] == ["equivalent", "not_equivalent"]


# -- the stored reference ------------------------------------------------------------------------

REFERENCE = {"name": "tension_value", "prompt": "T", "kind": "numeric", "reference": "g*m/3", "variables": VARIABLES,
             "dimension": "kg*m*s^-2", "latex": "", "unit": "N", "tolerance": {"relative": 0.01}, "weight": 2,
             "parameters": {"m": {"random": {"min": 0.1, "max": 0.5, "step": 0.05}}, "g": {"value": 9.81}}}


def test_a_numeric_request_carries_the_students_numbers_with_the_fixed_ones():
    request = ReferenceAnswer.from_json(REFERENCE).request("0.981 N", values={"m": 0.3})
    assert request["values"] == {"g": 9.81, "m": 0.3} and request["unit"] == "N"
    assert check_request(request)["verdict"] == "equivalent"


def test_without_a_draw_the_preview_numbers_are_used():
    from grader.answers.randomised import PREVIEW_SEED, draw_parameters

    request = ReferenceAnswer.from_json(REFERENCE).request("1 N")
    assert request["values"] == draw_parameters(REFERENCE["parameters"], PREVIEW_SEED)


def test_symbolic_answers_of_a_randomised_problem_stay_symbolic():
    symbolic = ReferenceAnswer.from_json({**REFERENCE, "kind": "expression"})
    request = symbolic.request("m g/3", values={"m": 0.3})
    assert "values" not in request and check_request(request)["verdict"] == "equivalent"


def test_the_reference_round_trips_with_its_new_keys():
    ref = ReferenceAnswer.from_json(REFERENCE)
    assert ReferenceAnswer.from_json(ref.to_json()) == ref and ref.weight == 2.0


@pytest.mark.parametrize("change, message", [
    ({"tolerance": {"relative": "1%"}}, "'tolerance'"),
    ({"weight": -1}, "'weight'"),
    ({"feedback": [{"expr": "m*g", "message": "w", "score": 2}]}, "score"),
    ({"tests": [{"answer": "1 N", "expect": "right"}]}, "'tests'"),
    ({"unit": 3}, "'unit'"),
])
def test_the_contract_refuses_bad_new_keys(change, message):
    from grader.answers.reference import ReferenceAnswerError

    with pytest.raises(ReferenceAnswerError, match=message):
        ReferenceAnswer.from_json({**REFERENCE, **change})


# -- hostile text --------------------------------------------------------------------------------

_PIECES = st.sampled_from(["1", "4.7", "e", "E", "-", "−", "+", ".", ",", " ", "×", "·", "x", "10", "^", "**", "(",
                           ")", "/", "*", "N", "kg", "m", "s", "²", "⁻", "µ", "°", "min", "Nm", "1e999", "\ud800"])


@given(text=st.one_of(st.text(max_size=40), st.lists(_PIECES, max_size=12).map("".join)))
@settings(max_examples=300, deadline=None)
def test_any_text_is_a_quantity_or_a_quantity_error(text):
    try:
        quantity = parse_quantity(text)
    except QuantityError as error:
        assert str(error)  # a message to show
    else:
        assert math.isfinite(quantity.si) and quantity.sig_figs >= 1


@given(text=st.lists(_PIECES, max_size=12).map("".join))
@settings(max_examples=150, deadline=None)
def test_any_text_gets_a_verdict(text):
    assert check(answer=text, **WEIGHT).verdict in ("equivalent", "not_equivalent", "invalid")


def test_an_accepted_alternative_value_is_right_too():
    # The mirror equilibrium: +asin(1/2) or -asin(1/2), both accepted by the scene.
    angle = dict(WEIGHT, reference="asin(m/(2*m))", unit="rad", alternatives=["-asin(m/(2*m))"])
    verdict = check(answer="-30°", **angle)
    assert verdict.verdict == "equivalent" and verdict.evidence["matched"] == 1
    assert check(answer="45°", **angle).verdict == "not_equivalent"


# -- a reference without a closed form: its unknown at a root found at the student's numbers ----------
# The tilted equilibrium of an upright pendulum held by a torsion spring: m g l sin θ = k θ.
TORSION = {"reference": "theta", "kind": "numeric", "unit": "rad", "dimension": "dimensionless",
           "variables": {"m": {"dimension": "mass", "domain": "positive"},
                         "g": {"dimension": "acceleration", "domain": "positive"},
                         "l": {"dimension": "length", "domain": "positive"},
                         "k": {"dimension": "energy", "domain": "positive"},
                         "theta": {"dimension": "angle", "domain": [0, 3.1416]}},
           "implicit": {"condition": "g*l*m*sin(theta) - k*theta", "unknown": "theta",
                        "interval": [0, 3.1416], "root": 1}}


@pytest.mark.parametrize("k, answer, verdict", [
    (5.0, "1.873 rad", "equivalent"),        # brentq: 1.8730555
    (5.0, "107.32 deg", "equivalent"),
    (5.0, "1.5 rad", "not_equivalent"),
    (5.0, "0 rad", "not_equivalent"),        # the upright root is not the one asked
    (9.0, "0.7129 rad", "equivalent"),       # another student's numbers: another root
    (9.0, "1.873 rad", "not_equivalent"),
])
def test_a_reference_without_a_closed_form_is_its_root_at_the_students_numbers(k, answer, verdict):
    request = dict(TORSION, answer=answer, values={"m": 1.0, "g": 9.81, "l": 1.0, "k": k})
    assert check_request(request)["verdict"] == verdict


def test_numbers_at_which_the_root_does_not_exist_are_an_invalid_request_never_a_wrong_verdict():
    request = dict(TORSION, answer="1.0 rad", values={"m": 1.0, "g": 9.81, "l": 1.0, "k": 12.0})
    reply = check_request(request)
    assert reply["verdict"] == "invalid" and "fewer than 2 roots for theta" in reply["reason"]


@pytest.mark.parametrize("implicit, message", [
    ("theta", "'implicit' must be an object"),
    ({"condition": "g*sin(theta)", "unknown": "phi", "interval": [0, 1], "root": 0}, "not one of the variables"),
    ({"condition": "g*sin(theta", "unknown": "theta", "interval": [0, 1], "root": 0}, "does not parse"),
    ({"condition": "g*sin(theta)", "unknown": "theta", "interval": [1, 0], "root": 0}, "interval"),
])
def test_a_malformed_implicit_reference_is_an_invalid_request(implicit, message):
    request = dict(TORSION, answer="1 rad", implicit=implicit, values={"m": 1.0, "g": 9.81, "l": 1.0, "k": 5.0})
    reply = check_request(request)
    assert reply["verdict"] == "invalid" and message in reply["reason"]


def test_the_stored_reference_carries_its_root_to_the_checker_and_the_instructor():
    from grader.answers.numeric import reference_value

    data = dict(TORSION, name="tilt", prompt="tilt", latex="", parameters={
        "m": {"dimension": "kg", "value": 1.0}, "g": {"dimension": "m*s^-2", "value": 9.81},
        "l": {"dimension": "m", "value": 1.0}, "k": {"dimension": "kg*m^2*s^-2", "value": 5.0}})
    data.pop("unit")
    reference = ReferenceAnswer.from_json(dict(data, unit="rad"))
    assert ReferenceAnswer.from_json(reference.to_json()) == reference
    assert check_request(reference.request("1.873 rad"))["verdict"] == "equivalent"
    assert reference_value(reference.reference, reference.variables, reference.values(),
                           reference.implicit) == pytest.approx(1.8730555106317808)
    with pytest.raises(ValueError, match="'implicit' applies to numeric answers only"):
        ReferenceAnswer.from_json(dict(data, unit="rad", kind="expression"))


# -- units a dimension cannot tell apart, and readings we only guess -----------------------------

OMEGA = dict(reference="sqrt(k/m)", variables={"m": {"dimension": "mass", "domain": "positive"},
                                               "k": {"dimension": "stiffness", "domain": "positive"}},
             kind="numeric", values={"m": 4.0, "k": 100.0})  # 5 rad/s, f = 0.796 Hz


@pytest.mark.parametrize("unit, answer, verdict", [
    ("rad/s", "5 rad/s", "equivalent"), ("rad/s", "5 s^-1", "equivalent"), ("rad/s", "286.5 deg/s", "equivalent"),
    ("rad/s", "5 Hz", "invalid"), ("rad/s", "0.796 Hz", "invalid"), ("rad/s", "5 kHz", "invalid"),
    ("Hz", "0.796 Hz", "equivalent"), ("Hz", "0.796 s^-1", "equivalent"), ("Hz", "796 mHz", "equivalent"),
    ("Hz", "5 rad/s", "invalid"), ("Hz", "0.796 rad/s", "invalid"),
    # the scene did not say which (a unit of 1/s or none): s⁻¹ is taken, Hz and rad/s are refused, since
    # either may be 2π off (5 Hz for ω = 5 rad/s was accepted); a declared dimension or variable says
    ("s^-1", "5 s^-1", "equivalent"), ("s^-1", "5 1/s", "equivalent"), ("", "5 s^-1", "equivalent"),
    ("s^-1", "5 Hz", "invalid"), ("s^-1", "5 rad/s", "invalid"), ("", "5 Hz", "invalid"), ("", "5 rad/s", "invalid"),
])
def test_hertz_and_radians_per_second_are_not_mixed(unit, answer, verdict):
    # 1 Hz is one cycle per second, 2π rad/s: where the scene's unit says which is asked, the other is
    # refused (never judged: "5 Hz" for ω = 5 rad/s is wrong by 2π, "0.796 Hz" is f, not ω).
    reference = OMEGA["reference"] + ("/(2*pi)" if unit == "Hz" else "")
    reply = check(answer=answer, **dict(OMEGA, reference=reference, unit=unit))
    assert reply.verdict == verdict, reply.reason
    if verdict == "invalid":
        assert "2π" in reply.feedback[0]["message"] and "0.796" not in reply.feedback[0]["message"]


@pytest.mark.parametrize("dimension, variables, answer, verdict", [
    ("angular_velocity", {}, "5 rad/s", "equivalent"), ("angular_velocity", {}, "5 Hz", "invalid"),
    ("frequency", {}, "5 Hz", "equivalent"), ("frequency", {}, "5 rad/s", "invalid"),
    # a reference that is a variable declared an angular velocity (or a frequency) says it too
    (None, {"w": {"dimension": "angular_velocity", "domain": "positive"}}, "5 rad/s", "equivalent"),
    (None, {"w": {"dimension": "angular_velocity", "domain": "positive"}}, "5 Hz", "invalid"),
    (None, {"w": {"dimension": "frequency", "domain": "positive"}}, "5 Hz", "equivalent"),
    (None, {"w": {"dimension": "frequency", "domain": "positive"}}, "5 rad/s", "invalid"),
])
def test_a_declared_dimension_or_variable_says_which_of_hertz_and_radians_per_second(dimension, variables, answer,
                                                                                      verdict):
    request = dict(OMEGA, reference="w", variables=variables, values={"w": 5.0}) if variables else OMEGA
    reply = check(answer=answer, **dict(request, dimension=dimension))
    assert reply.verdict == verdict, reply.reason


@pytest.mark.parametrize("reference, variables, values, answer, verdict", [
    # an angle (a variable declared so, an inverse trigonometric function): % is no unit of it
    ("theta", {"theta": {"dimension": "angle", "domain": "real"}}, {"theta": 0.5236}, "52.36 %", "invalid"),
    ("theta", {"theta": {"dimension": "angle", "domain": "real"}}, {"theta": 0.5236}, "30°", "equivalent"),
    ("acos(g/(w^2*R))", {"g": {"dimension": "acceleration", "domain": "positive"},
                         "R": {"dimension": "length", "domain": "positive"},
                         "w": {"dimension": "angular_velocity", "domain": "positive"}},
     {"g": 9.81, "R": 1.0, "w": 4.0}, "52.15 %", "invalid"),
    # a ratio in % stays a ratio
    ("m/(m + M)", {"m": {"dimension": "mass", "domain": "positive"}, "M": {"dimension": "mass", "domain": "positive"}},
     {"m": 1.0, "M": 3.0}, "25 %", "equivalent"),
])
def test_an_angle_is_not_given_in_percent(reference, variables, values, answer, verdict):
    reply = check(reference, answer, variables, kind="numeric", values=values)
    assert reply.verdict == verdict, reply.reason


TORQUE = dict(reference="F*r", variables={"F": {"dimension": "force", "domain": "positive"},
                                          "r": {"dimension": "length", "domain": "positive"}},
              kind="numeric", values={"F": 10.0, "r": 0.5})  # 5 N m


@pytest.mark.parametrize("unit, answer, verdict", [
    ("N*m", "5 N m", "equivalent"), ("N*m", "5 Nm", "equivalent"), ("N*m", "5 N-m", "equivalent"),
    ("N*m", "0.005 kNm", "equivalent"), ("N*m", "5 J/rad", "equivalent"), ("N*m", "5 kg m^2/s^2", "equivalent"),
    ("N*m", "5 J", "invalid"), ("N*m", "5000 mJ", "invalid"),
    ("J", "5 J", "equivalent"), ("J", "5 N m", "equivalent"), ("J", "5 Nm", "equivalent"),  # 1 J is 1 N m of work
])
def test_a_torque_asked_in_newton_metres_is_not_given_in_joules(unit, answer, verdict):
    reply = check(answer=answer, **dict(TORQUE, unit=unit))
    assert reply.verdict == verdict, reply.reason


ANGLE = dict(WEIGHT, reference="asin(m/(2*m))")  # 30°


@pytest.mark.parametrize("unit, answer, verdict, code", [
    ("deg", "30", "equivalent", None), ("deg", "30.0", "equivalent", None), ("deg", "0.5236 rad", "equivalent", None),
    ("deg", "0.5236", "not_equivalent", "angle_unit"),  # read in degrees, as asked
    ("rad", "0.5236", "equivalent", None), ("rad", "30", "not_equivalent", "angle_unit"),
    ("rad", "30 degrees", "equivalent", None), ("rad", "30º", "equivalent", None), ("rad", "0.52 radians", "equivalent", None),
    ("rad", "52.36 %", "invalid", "unit"), ("deg", "52.36%", "invalid", "unit"),
    ("%", "50", "equivalent", None), ("%", "50 %", "equivalent", None),  # a ratio asked in %: 50 is 50 %
])
def test_a_bare_number_for_an_angle_is_in_the_unit_asked(unit, answer, verdict, code):
    reference = ANGLE["reference"] if unit != "%" else "m/(2*m)"
    reply = check(answer=answer, **dict(ANGLE, reference=reference, unit=unit))
    assert reply.verdict == verdict, reply.reason
    assert [f["code"] for f in reply.feedback][:1] == ([code] if code else [])


@pytest.mark.parametrize("unit, answer", [
    ("m/s^2", "9.8 ms^-2"), ("m/s^2", "9.8 ms⁻²"), ("m/s", "5 ms^-1"), ("m/s", "5 ms-1"), ("N*m", "5 mN"),
])
def test_a_milli_prefix_that_may_be_metres_times_a_unit_is_refused_with_the_spacing_to_type(unit, answer):
    # ms is the millisecond: "9.8 ms^-2" is strictly 9.8e6 s^-2, but what the student meant is m s^-2.
    speed = dict(WEIGHT, reference="sqrt(g*l)", variables={**VARIABLES, "l": {"dimension": "length",
                                                                               "domain": "positive"}},
                 values={**VALUES, "l": 1.0})  # a velocity, as the unit m/s asks
    request = {"m/s^2": dict(WEIGHT, reference="g"), "m/s": speed, "N*m": dict(TORQUE)}[unit]
    reply = check(answer=answer, **dict(request, unit=unit))
    assert reply.verdict == "invalid" and "put a space between them: m " in reply.feedback[0]["message"]


@pytest.mark.parametrize("answer", ["14.7 Nm", "14.7 kgm", "14.7 Nms/s"])
def test_units_written_together_are_a_guess_refused_rather_than_judged_when_their_dimension_is_wrong(answer):
    reply = check(answer=answer, **WEIGHT)
    assert reply.verdict == "invalid", reply.reason


@pytest.mark.parametrize("answer", ["14.7 newtons", "14.7 kgm/s^2", "14.7 kg m/s2", "14.7 kg m s-2", "14.7 N.",
                                    "F = 14.7 N", "≈ 14.7 N", "14.7 Kg m/s^2", "1.47⋅10^1 N", "14.7 kg⋅m/s²"])
def test_a_force_as_students_type_it(answer):
    assert check(answer=answer, **WEIGHT).verdict == "equivalent"


# -- zero under significant figures --------------------------------------------------------------
# Zero has no significant figures: "0.00 N" has as many as "0 N" (none that count). A zero answer is
# never told to give more figures; nor is any answer to a zero reference, which has no figures to
# match: there the rule of within_tolerance decides (below 10^-n in the student's unit).
SLOPE = dict(reference="m*g*sin(theta)", kind="numeric", unit="N",
             variables={**VARIABLES, "theta": {"dimension": "angle", "domain": "real"}})
FLAT = {"m": 2, "g": 9.81, "theta": 0}              # the force along a flat floor: exactly 0 N
TILTED = {"m": 2, "g": 9.81, "theta": math.pi / 6}  # 9.81 N


@pytest.mark.parametrize("values, answer, tolerance, verdict, codes", [
    # a zero answer to a zero reference: right whatever sig_figs asks
    (FLAT, "0 N", {"sig_figs": 2}, "equivalent", []),
    (FLAT, "0.0 N", {"sig_figs": 2}, "equivalent", []),
    (FLAT, "0.00 N", {"sig_figs": 2}, "equivalent", []),
    (FLAT, "0e0 N", {"sig_figs": 2}, "equivalent", []),
    (FLAT, "-0 N", {"sig_figs": 2}, "equivalent", []),
    (FLAT, "0.00 kN", {"sig_figs": 2}, "equivalent", []),
    (FLAT, "0 N", {"sig_figs": 15}, "equivalent", []),
    (FLAT, "0 N", {"sig_figs": 3, "relative": 0.01}, "equivalent", []),
    # a nonzero answer to a zero reference: zero to n decimal places, or wrong by its value
    (FLAT, "0.001 N", {"sig_figs": 2}, "equivalent", []),
    (FLAT, "0.0010 N", {"sig_figs": 2}, "equivalent", []),
    (FLAT, "0.01 N", {"sig_figs": 2}, "not_equivalent", []),
    (FLAT, "1 N", {"sig_figs": 2}, "not_equivalent", []),
    (FLAT, "0.5 N", {"sig_figs": 3}, "not_equivalent", []),
    # a zero answer to a nonzero reference: wrong by its value, not for its figures
    (TILTED, "0 N", {"sig_figs": 2}, "not_equivalent", []),
    (TILTED, "0.00 N", {"sig_figs": 2}, "not_equivalent", []),
    # nonzero answers to a nonzero reference: the figures still count
    (TILTED, "9.8 N", {"sig_figs": 2}, "equivalent", []),
    (TILTED, "1e1 N", {"sig_figs": 2}, "not_equivalent", ["sig_figs"]),
])
def test_a_zero_is_judged_by_its_value_never_by_its_significant_figures(values, answer, tolerance, verdict, codes):
    reply = check(answer=answer, values=values, tolerance=tolerance, **SLOPE)
    assert (reply.verdict, [f["code"] for f in reply.feedback]) == (verdict, codes), reply.reason
    if codes != ["sig_figs"]:
        assert "significant figures" not in reply.reason


# -- the unit asked, and a request without one ---------------------------------------------------
# unit = "" asks for the reference's dimension in any unit of it, with the rules of a unit that is
# given (a force needs a unit); a pure number only where the reference is dimensionless.
NO_UNIT = {k: v for k, v in WEIGHT.items() if k != "unit"}


@pytest.mark.parametrize("answer, verdict, codes", [
    ("14.7 N", "equivalent", []), ("0.0147 kN", "equivalent", []), ("1.47e1 kg*m/s^2", "equivalent", []),
    ("1471.5 cN", "equivalent", []),
    ("15.5 N", "not_equivalent", []), ("147 N", "not_equivalent", ["power_of_ten"]),
    ("14.7 m", "not_equivalent", ["dimension"]),
    ("14.7", "invalid", ["missing_unit"]),  # as when "N" is asked: a force is given with its unit
])
@pytest.mark.parametrize("request_unit", [None, ""])
def test_without_a_unit_the_answer_is_of_the_references_dimension(answer, verdict, codes, request_unit):
    request = dict(NO_UNIT, answer=answer, **({} if request_unit is None else {"unit": request_unit}))
    reply = check_request(request)
    assert (reply["verdict"], [f["code"] for f in reply["feedback"]]) == (verdict, codes), reply["reason"]


def test_a_missing_unit_without_a_unit_asked_names_the_dimension_only():
    reply = check(answer="14.7", **NO_UNIT)
    assert reply.reason == "give a unit: the answer is a force (kg·m/s²)"


def test_a_dimensionless_reference_without_a_unit_is_still_a_pure_number():
    pure = dict(NO_UNIT, reference="m*g/(m*g)")
    assert check(answer="1.0", **pure).verdict == "equivalent"
    assert check(answer="1.0 N", **pure).feedback[0]["code"] == "dimension"


@pytest.mark.parametrize("change, words", [
    ({"unit": "m"}, ("the unit 'm' is a length (m)", "the reference is a force (kg·m/s²)")),
    ({"unit": "deg"}, ("the unit 'deg' is dimensionless", "the reference is a force")),
    ({"unit": "kJ"}, ("an energy or torque", "the reference is a force")),
    ({"unit": "N", "reference": "m*g/(m*g)"}, ("the unit 'N' is a force", "the reference is dimensionless")),
    ({"unit": "", "dimension": "length"}, ("the dimension 'length' is a length (m)", "the reference is a force")),
])
@pytest.mark.parametrize("answer", ["14.7 N", "14.7 m", "14.7"])
def test_a_unit_that_contradicts_the_references_dimension_is_a_bad_request(change, words, answer):
    reply = check(answer=answer, **dict(WEIGHT, **change))
    assert reply.verdict == "invalid" and all(w in reply.reason for w in words), reply.reason
    assert reply.feedback == []  # nothing for the student: the request is at fault


def test_a_stored_reference_without_a_unit_asks_for_its_dimension():
    reference = ReferenceAnswer.from_json({**REFERENCE, "unit": ""})
    assert check_request(reference.request("0.981 N", values={"m": 0.3}))["verdict"] == "equivalent"
    assert check_request(reference.request("0.981", values={"m": 0.3}))["verdict"] == "invalid"
    wrong = ReferenceAnswer.from_json({**REFERENCE, "unit": "m", "dimension": "m"})
    reply = check_request(wrong.request("0.981 m", values={"m": 0.3}))
    assert reply["verdict"] == "invalid" and "the reference is a force" in reply["reason"]


# -- reasons keep a unit symbol as typed -----------------------------------------------------------

@pytest.mark.parametrize("question, answer, reason", [
    (dict(OMEGA, unit="rad/s"), "5 Hz", "Hz counts cycles per second (f = ω/2π); give this angular frequency in "
                                        "rad/s (or s⁻¹)"),
    (dict(OMEGA, reference="sqrt(k/m)/(2*pi)", unit="Hz"), "5 rad/s", "give this frequency in Hz"),
    (dict(TORQUE, unit="N*m"), "5 J", "a torque is given in N·m"),
    (WEIGHT, "14.7 Nm", "Nm was read as N m"),
    (dict(WEIGHT, reference="g", unit="m/s^2"), "9.8 ms^-2", "ms is the millisecond"),
])
def test_a_reason_starts_lower_case_unless_it_starts_with_a_unit_symbol(question, answer, reason):
    reply = check(answer=answer, **question)
    assert reply.verdict == "invalid" and reply.reason.startswith(reason), reply.reason
    assert reply.feedback[0]["message"].rstrip(".").lower() == reply.reason.lower()


# -- the student's numbers lie in their variables' domains -----------------------------------------
HOOP = dict(reference="m*g*d/R", kind="numeric", unit="N",
            variables={**VARIABLES, "R": {"dimension": "length", "domain": "positive"},
                       "d": {"dimension": "length", "domain": "nonnegative", "below": "R"},
                       "theta": {"dimension": "angle", "domain": [0, 1.5708]}})
INSIDE = {"m": 1.5, "g": 9.81, "R": 1.0, "d": 0.5, "theta": 1.0}  # m g d/R = 7.3575 N


@pytest.mark.parametrize("change, words", [
    ({"m": -1.5}, "the value -1.5 of 'm' is outside its domain (positive)"),
    ({"m": 0}, "of 'm' is outside its domain (positive)"),
    ({"g": math.inf}, "of 'g' is outside its domain (positive)"),
    ({"g": math.nan}, "of 'g' is outside its domain (positive)"),
    ({"d": -0.1}, "of 'd' is outside its domain (nonnegative)"),
    ({"theta": 2.0}, "of 'theta' is outside its domain ([0, 1.5708])"),  # named though the reference has no theta
    ({"d": 1.0}, "the value 1 of 'd' is not below that of 'R' (1)"),
])
@pytest.mark.parametrize("answer", ["7.36 N", "-7.36 N", "7.36 m"])
def test_numbers_outside_their_domains_are_a_bad_request_never_graded(change, words, answer):
    reply = check(answer=answer, values={**INSIDE, **change}, **HOOP)
    assert reply.verdict == "invalid" and words in reply.reason, reply.reason


@pytest.mark.parametrize("change", [{}, {"d": 0.0}, {"theta": 0.0}, {"theta": 1.5708}, {"other": -1.0}])
def test_numbers_in_their_domains_are_graded_ends_included(change):
    values = {**INSIDE, **change}
    answer = f"{1.5 * 9.81 * values['d']:.4g} N"
    assert check(answer=answer, values=values, **HOOP).verdict == "equivalent"


LENGTH = {"x": {"dimension": "length", "domain": "real"}}


@pytest.mark.parametrize("answer, verdict", [
    # a zero is matched to n decimal places in the unit asked (m), not in the student's: 0.0009 Mm is 900 m
    ("0.0009 Mm", "not_equivalent"), ("9e-4 km", "not_equivalent"), ("0.0009 m", "equivalent"),
    ("0.9 mm", "equivalent"), ("0 m", "equivalent"), ("0.002 m", "not_equivalent"),
])
def test_a_zero_reference_is_matched_in_the_unit_asked(answer, verdict):
    reply = check("x", answer, LENGTH, kind="numeric", values={"x": 0.0}, unit="m", tolerance={"sig_figs": 3})
    assert reply.verdict == verdict, reply.reason


@pytest.mark.parametrize("answer, code", [
    # too few figures is the slip only where the figures given are right; otherwise the value is wrong
    ("2.5 m", "sig_figs"), ("2 m", "sig_figs"), ("7 m", None), ("-2.5 m", "sign"), ("25 m", "power_of_ten"),
    ("-25 m", "power_of_ten"),
])
def test_too_few_figures_is_said_only_of_a_value_right_to_its_figures(answer, code):
    reply = check("x", answer, LENGTH, kind="numeric", values={"x": 2.5}, tolerance={"sig_figs": 3})
    assert reply.verdict == "not_equivalent"
    assert [f["code"] for f in reply.feedback] == ([code] if code else [])
    if answer == "-25 m":  # a prefix fixed, the sign would still be wrong
        assert "sign" in reply.feedback[0]["message"]


SPUN_HOOP = dict(variables={"g": {"dimension": "acceleration", "domain": "positive"},
                       "R": {"dimension": "length", "domain": "positive"},
                       "omega": {"dimension": "angular_velocity", "domain": "positive"}},
            kind="numeric", values={"g": 9.81, "R": 1.0, "omega": 2.0}, unit="rad")  # ω²R < g: no acos(g/ω²R)


@pytest.mark.parametrize("alternatives, answer, verdict", [
    (["acos(g/(omega^2*R))", "0"], "0 rad", "equivalent"), (["0", "acos(g/(omega^2*R))"], "0 rad", "equivalent"),
    (["acos(g/(omega^2*R))"], "1.0 rad", "not_equivalent"), (["acos(g/(omega^2*R))"], "3.1416 rad", "equivalent"),
])
def test_an_accepted_value_that_does_not_exist_at_the_numbers_is_skipped(alternatives, answer, verdict):
    # the hoop's ±acos(g/ω²R) exists only where ω²R > g; the other accepted values still count
    reply = check("pi", answer, alternatives=alternatives, **SPUN_HOOP)
    assert reply.verdict == verdict, reply.reason


@pytest.mark.parametrize("answer, direction", [("2.5 cycles", False), ("1.5 micron", False), ("2.5 m down", True),
                                                ("2.5 m downwards", True)])
def test_the_sign_is_offered_for_a_direction_only_after_a_direction_word(answer, direction):
    reply = check("x", answer, LENGTH, kind="numeric", values={"x": 2.5})
    assert reply.verdict == "invalid"
    assert ("a direction is the sign" in reply.reason) is direction


# -- numbers written in other ways than one decimal: refused, never judged, with what to type -------
TURNED = dict(reference="a", variables={"a": {"dimension": "angle", "domain": "positive"}}, kind="numeric",
             values={"a": 1.0587}, unit="rad")  # 60.66°, 0.337π rad


@pytest.mark.parametrize("question, answer, said, instead", [
    # a multiple of π, however it is typed: its value in decimals, the unit kept
    (TURNED, "0.337π rad", "not in terms of π: 1.059 rad", "1.059 rad"),
    (TURNED, "0.337*pi rad", "not in terms of π: 1.059 rad", "1.059 rad"),
    (TURNED, "0.337 pi rad", "not in terms of π: 1.059 rad", "1.059 rad"),
    (TURNED, r"0.337\pi\,\mathrm{rad}", "not in terms of π: 1.059 rad", "1.059 rad"),
    (TURNED, "θ = 0.337·π rad", "not in terms of π: 1.059 rad", "1.059 rad"),
    (WEIGHT, "4.684π N", "not in terms of π: 14.72 N", "14.72 N"),
    (TURNED, "π/3 rad", "not in terms of π", None),
    # degrees, minutes and seconds: the decimal degrees
    (dict(TURNED, unit="deg"), "60°39′36″", "decimal degrees: 60.66°", "60.66°"),
    (dict(TURNED, unit="deg"), "60° 39' 36\"", "decimal degrees: 60.66°", "60.66°"),
    (dict(TURNED, unit="deg"), "60°39.6'", "decimal degrees: 60.66°", "60.66°"),
    (dict(TURNED, unit="deg"), "60 deg 39.6 min", "decimal degrees: 60.66°", "60.66°"),
    # a vulgar fraction: the decimal
    (WEIGHT, "14¾ N", "as a decimal: 14.75", "14.75 N"),
    # a power of ten that is not whole; an uncertainty; a note of the figures
    (WEIGHT, "1e1.168 N", "a power of ten is a whole number", None),
    (WEIGHT, "10^1.168 N", "a power of ten is a whole number", None),
    (WEIGHT, "14.7 ± 0.1 N", "without its uncertainty (±)", "14.7 N"),
    (WEIGHT, "14.7±0.1 N", "without its uncertainty (±)", "14.7 N"),
    (WEIGHT, "14.7 +/- 0.1 N", "without its uncertainty (±)", "14.7 N"),
    (WEIGHT, "(14.7 ± 0.1) N", "without its uncertainty (±)", "14.7 N"),
    (WEIGHT, "14.7 N (3 s.f.)", "without a note of its figures", "14.7 N"),
    (WEIGHT, "14.7 N to 3 sf", "without a note of its figures", "14.7 N"),
    # a formula, or a second '=', around the value: one name before '=' is read (F = 14.7 N), no more
    (WEIGHT, "W = mg = 14.7 N", "a formula or a second '=' is not read", "W = 14.7 N"),
    (WEIGHT, "m*g = 14.7 N", "a formula or a second '=' is not read", "14.7 N"),
    (WEIGHT, "|F| = 14.7 N", "a formula or a second '=' is not read", "F = 14.7 N"),
    (WEIGHT, "14.7 N = F", "a formula or a second '=' is not read", "14.7 N"),
])
def test_a_number_written_otherwise_is_refused_with_what_to_type(question, answer, said, instead):
    reply = check(answer=answer, **question)
    assert reply.verdict == "invalid"
    if said is not None:
        assert said in reply.reason, reply.reason
    if instead is not None:  # what the message says to type is read, and is the student's own value
        assert check(answer=instead, **question).verdict == "equivalent"


@pytest.mark.parametrize("text", ["14.7 N", "1.47e1 N", "1.47×10^1 N", "F = 14.7 N", "60.66°", "14.7 N.", "25 %"])
def test_the_written_forms_refused_are_never_looked_for_in_a_number_read(text, monkeypatch):
    import grader.answers.numeric as numeric

    def looked_for(text):
        raise AssertionError(f"{text!r} was read, yet its refusal was explained")

    monkeypatch.setattr(numeric, "_written_form", looked_for)
    assert numeric.parse_quantity(text).number > 0  # read without reaching the explanations of refusals


# Radians for cycles in a number (red team 19): f typed where ω is asked, or the other way round, had no
# feedback; it is named when the value is 2π or 1/2π times the right one within the tolerance.
@pytest.mark.parametrize("reference, answer, unit, code", [
    ("sqrt(k/m)", "3.18 1/s", "1/s", "two_pi"),       # f = 20/2π for ω = 20 s⁻¹
    ("sqrt(k/m)", "125.7 1/s", "1/s", "two_pi"),
    ("sqrt(k/m)/(2*pi)", "20 Hz", "Hz", "two_pi"),    # ω for f
    ("2*pi*sqrt(m/k)", "0.05 s", "s", "two_pi"),      # 1/ω for the period
    ("sqrt(k/m)", "6.37 1/s", "1/s", None),           # 20/π: no slip we can name
])
def test_a_value_off_by_two_pi_is_named_radians_for_cycles(reference, answer, unit, code):
    spring = {"k": {"dimension": "kg/s^2", "domain": "positive"}, "m": {"dimension": "mass", "domain": "positive"}}
    v = check(reference, answer, spring, kind="numeric", values={"k": 200.0, "m": 0.5}, unit=unit)
    assert v.verdict == "not_equivalent" and [f["code"] for f in v.feedback] == ([code] if code else [])


def test_two_pi_in_a_force_value_is_not_called_radians_for_cycles():
    mg = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"}}
    v = check("m*g", "2.34 N", mg, kind="numeric", values={"m": 1.5, "g": 9.81}, unit="N")  # 14.7/2π
    assert v.verdict == "not_equivalent" and v.feedback == []


# A ± before the value (red team 19): ±1.034 rad for a hoop's two equilibria ±acos(g/ω²a) is two answers, not a
# value with its uncertainty; it was refused "without its uncertainty (±)", which misreads the student.
@pytest.mark.parametrize("answer, says", [
    ("±1.034 rad", "one sign"),
    ("θ = ±59.2°", "one sign"),
    ("θ* = ±1.034", "one sign"),
    ("+/- 1.034 rad", "one sign"),
    ("1.034 ± 0.01 rad", "without its uncertainty (±)"),   # after the value: an uncertainty, as before
    ("(1.034 +/- 0.01) rad", "without its uncertainty (±)"),
])
def test_a_plus_minus_before_the_value_is_two_answers_not_an_uncertainty(answer, says):
    hoop = {"g": {"dimension": "acceleration", "domain": "positive"}, "a": {"dimension": "length", "domain": "positive"},
            "omega": {"dimension": "angular_velocity", "domain": [5, 10]}}
    v = check("acos(g/(omega^2*a))", answer, hoop, kind="numeric", values={"g": 9.81, "a": 0.3, "omega": 8.0},
              unit="rad", alternatives=["-acos(g/(omega^2*a))"])
    assert v.verdict == "invalid" and says in v.reason
