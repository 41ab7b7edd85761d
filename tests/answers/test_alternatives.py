"""Alternatives: an answer may accept several references, and the verdict says which one matched."""

import pytest

from grader.answers.checker import check, check_request
from grader.answers.reference import ReferenceAnswer

HOOP = {"g": {"dimension": "acceleration", "domain": "positive"},
        "a": {"dimension": "length", "domain": "positive"},
        "omega": {"dimension": "angular_velocity", "domain": [5, 10]}}
EQUILIBRIUM = "acos(g/(omega^2*a))"  # the bead's off-axis equilibrium; its mirror image is -theta*
MIRROR = "-acos(g/(omega^2*a))"


@pytest.mark.parametrize("answer, verdict, matched", [
    ("acos(g/(ω² a))", "equivalent", 0),
    ("-acos(g/(ω² a))", "equivalent", 1),          # the mirror equilibrium
    ("-arccos(g/(a omega^2))", "equivalent", 1),
    ("asin(g/(ω² a))", "not_equivalent", None),
])
def test_the_verdict_says_which_reference_matched(answer, verdict, matched):
    v = check(EQUILIBRIUM, answer, HOOP, alternatives=[MIRROR])
    assert v.verdict == verdict
    assert v.evidence.get("matched") == matched


def test_without_alternatives_the_mirror_is_wrong():
    assert check(EQUILIBRIUM, "-acos(g/(ω² a))", HOOP).verdict == "not_equivalent"


def test_alternatives_must_be_texts():
    assert check(EQUILIBRIUM, "x", HOOP, alternatives="-theta").verdict == "invalid"


PENDULUM = {"g": {"dimension": "acceleration", "domain": "positive"}, "l": {"dimension": "length", "domain": "positive"},
            "theta": {"dimension": "angle", "domain": "real", "kind": "coordinate"},
            "thetaddot": {"dimension": "angular_acceleration", "domain": "real", "kind": "acceleration"}}


@pytest.mark.parametrize("answer", ["thetaddot = -g/l*sin(theta)", "thetaddot = g/l*sin(theta)", "g/l*sin(theta) = 0"])
def test_a_bare_alternative_to_an_equation_is_a_request_error(answer):
    # "g/l*sin(theta)" beside "thetaddot = -g/l*sin(theta)" is the other sign's right-hand side, not
    # "g/l*sin(theta) = 0": whatever the answer, the request is refused, naming the alternative
    v = check("thetaddot = -g/l*sin(theta)", answer, PENDULUM, kind="equation", alternatives=["g/l*sin(theta)"])
    assert v.verdict == "invalid" and "accepted answer 2 ('g/l*sin(theta)') is not an equation" in v.reason


def test_a_residual_reference_may_have_residual_alternatives():
    v = check("thetaddot + g/l*sin(theta)", "thetaddot = g/l*sin(theta)", PENDULUM, kind="equation",
              alternatives=["thetaddot - g/l*sin(theta)"])
    assert v.verdict == "equivalent" and v.evidence["matched"] == 1


SCENE = '''
id = "hoop_equilibrium"
title = "Bead on a rotating hoop: where it rests"
statement = "A bead on a smooth hoop of radius $a$ spinning at $\\\\omega$ about its vertical diameter."

[parameters]
m = { dimension = "mass", domain = "positive", value = 0.1 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
a = { dimension = "length", domain = "positive", value = 0.5 }
omega = { dimension = "angular_velocity", domain = [5, 10], value = 7.0 }

[coordinates]
theta = { dimension = "angle", domain = [-3.1416, 3.1416] }
phi = { dimension = "angle" }

[energy]
kinetic = "m/2*(a^2*thetadot^2 + a^2*sin(theta)^2*phidot^2)"
potential = "-m*g*a*cos(theta)"

[[constraints]]
name = "drive"
f = "phi - omega*t"

[initial]
theta = 0.3
thetadot = 0

[[answers]]
name = "equilibrium"
prompt = "An angle where the bead can rest off the axis"
expr = "acos(g/(omega^2*a))"
alternatives = ["-acos(g/(omega^2*a))"]
'''


def test_alternatives_go_from_the_scene_file_through_the_reference_contract_to_the_checker():
    from types import SimpleNamespace

    from grader.mechanics.references import reference_answers
    from grader.mechanics.scene import parse_scene

    scene = parse_scene(SCENE, source="test")
    (spec,) = scene.answers
    # The answer is already in closed form in the parameters: its derived value is its expression
    # (a stand-in for derive(), whose time budget is not what this test is about).
    derivation = SimpleNamespace(scene=scene, answers={"equilibrium": spec.expr}, alternatives={}, implicit={})
    (data,) = reference_answers(derivation)
    reference = ReferenceAnswer.from_json(data)
    assert reference.alternatives == ("-acos(g/(a*omega**2))",)
    reply = check_request(reference.request("-acos(g/(omega^2 a))"))
    assert reply["verdict"] == "equivalent" and reply["evidence"]["matched"] == 1


def test_a_scene_alternative_of_the_wrong_dimension_is_refused():
    from grader.mechanics.scene import SceneError, parse_scene

    with pytest.raises(SceneError, match="alternatives"):
        parse_scene(SCENE.replace('alternatives = ["-acos(g/(omega^2*a))"]', 'alternatives = ["a"]'), source="test")


# A reaction force accepted in either sign convention: the slip is named against the accepted answer it is
# nearest to, never "check the sign" for a sign that is accepted (red team 19).
SWING = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"},
         "l": {"dimension": "length", "domain": "positive"},
         "theta": {"dimension": "angle", "domain": [-3.1416, 3.1416], "kind": "coordinate"},
         "thetadot": {"dimension": "angular_velocity", "domain": "real", "kind": "velocity"}}
TENSION = "m*(g*cos(theta) + l*thetadot^2)"


@pytest.mark.parametrize("answer, code, against", [
    ("-2 m (g cos(theta) + l thetadot^2)", "factor", 1),      # twice the accepted -T: a factor, not a sign
    ("-m g cos(theta)", "missing_term", 1),                    # -T less a term
    ("-m (g sin(theta) + l thetadot^2)", "sin_cos", 1),        # -T with sin for cos
    ("2 m (g cos(theta) + l thetadot^2)", "factor", None),     # nearest the main one: said against it
    ("m g cos(theta)", "missing_term", None),
])
def test_a_slip_is_named_against_the_nearest_accepted_answer(answer, code, against):
    v = check(TENSION, answer, SWING, alternatives=[f"-{TENSION}"])
    assert v.verdict == "not_equivalent"
    assert [f["code"] for f in v.feedback] == [code]
    assert not any("sign" in f["message"].lower() for f in v.feedback)
    assert v.evidence.get("feedback_from") == against


@pytest.mark.parametrize("answer, message", [
    ("-147 N", "Your value is off by a power of ten: check unit prefixes and conversions."),
    ("-1.47 N", "Your value is off by a power of ten: check unit prefixes and conversions."),
])
def test_a_numeric_slip_is_named_against_the_nearest_accepted_value(answer, message):
    v = check("m*g", answer, {k: SWING[k] for k in ("m", "g")}, kind="numeric", values={"m": 1.5, "g": 9.81},
              unit="N", alternatives=["-m*g"])
    assert v.verdict == "not_equivalent" and [f["message"] for f in v.feedback] == [message]


def test_a_sign_is_still_said_when_no_accepted_answer_has_that_sign():
    v = check(TENSION, "-m (g cos(theta) + l thetadot^2)", SWING, alternatives=["m*(g*cos(theta) + l*thetadot^2)*1"])
    assert v.verdict == "not_equivalent" and [f["code"] for f in v.feedback] == ["sign"]
