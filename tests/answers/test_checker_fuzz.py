"""The checker's public entry point on generated requests: always a documented verdict, as strict
JSON, in bounded time; never an exception.

``check_request`` is what ``grader check --jsonl``, ``POST /check`` and the grading worker all call
(in the sandbox child). Requests here are well-formed with hostile texts (token soups of the
grammar, unicode with lone surrogates, huge numbers, deep nesting), or malformed in their shape
(wrong types, unknown kinds, broken variables and feedback). A more specific fuzzer of the
evaluator's numerics lives with the evaluator's tests.
"""

import json
import re
import time

from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from grader.answers.checker import check_request
from grader.answers.verdict import CERTAINTIES, VERDICTS

VARIABLES = {
    "m": {"dimension": "mass", "domain": "positive"},
    "g": {"dimension": "acceleration", "domain": "positive"},
    "l": {"dimension": "length", "domain": "positive"},
    "x": {"dimension": "dimensionless", "domain": "real"},
    "theta": {"dimension": "angle", "domain": [-3.1416, 3.1416]},
    "thetadot": {"dimension": "angular_velocity", "domain": "real"},
}
REFERENCES = ["m*l*thetadot**2 + g*m*cos(theta)", "g*m/3", "x", "sqrt(g/l)", "thetadot**2 = g*cos(theta)/l"]
TOKENS = [
    "m", "g", "l", "x", "theta", "thetadot", "θ", "mg", "pi", "e", "0", "1", "2", "0.5", "1e999", "9" * 300,
    "+", "-", "*", "/", "^", "**", "(", ")", ",", "=", ";", "sin", "cos", "atan2", "atan2(x)", "sqrt", "log",
    "exp", "Abs", "|", "\\frac{", "\\sqrt{", "}", "__import__", " ", "\ud800", "\x00", "x^x^x^x", "10^10^10",
]
soup = st.lists(st.sampled_from(TOKENS), max_size=30).map("".join)
numbers = st.one_of(st.integers(-12, 12), st.sampled_from(["1/3", "0.3333", "1e-12", "10^300", "2^0.5", "pi"]),
                    st.integers(-10**40, 10**40))
NEAR_MISS_FORMS = ["{k}*({r})", "-({r})", "({r})/({k})", "({r})*(1 + {k}*1e-9)", "{s}", "({r}) + ({r})*{k}"]


def near_misses_of(reference: str):
    """Near misses of a reference: what drives the feedback (factor, sign, term, sin/cos, close)."""
    lhs, _, rhs = reference.rpartition("=")
    side = rhs.strip()
    return st.builds(lambda k, form: lhs + ("= " if lhs else "") + form.format(r=side, k=k,
                                                                               s=side.replace("cos", "sin")),
                     numbers, st.sampled_from(NEAR_MISS_FORMS))


near_misses = st.sampled_from(REFERENCES).flatmap(near_misses_of)
texts = st.one_of(
    near_misses,
    soup,
    st.text(st.characters(codec=None, categories=["L", "N", "P", "S", "Z", "C", "Cs"]), max_size=40),
    st.builds(lambda n: "(" * n + "x" + ")" * n, st.integers(0, 500)),
    st.builds(lambda a, c: f"{a} + {c}", st.sampled_from(REFERENCES), st.integers(-10**400, 10**400)),
)
json_values = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=10),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=5), inner, max_size=3),
    max_leaves=8,
)
well_formed = st.fixed_dictionaries(
    {"reference": st.sampled_from(REFERENCES) | texts, "answer": texts, "variables": st.just(VARIABLES)},
    optional={"kind": st.sampled_from(["expression", "equation"]),
              "feedback": st.lists(st.fixed_dictionaries({"expr": texts, "message": st.text(max_size=20)}), max_size=2),
              "feedback_detail": st.sampled_from(["kind", "full"]),
              "state": st.just(["theta", "thetadot"])},
)
malformed = st.fixed_dictionaries(
    {},
    optional={"reference": json_values | texts, "answer": json_values | texts, "variables": json_values,
              "kind": json_values, "feedback": json_values, "state": json_values, "budget_s": json_values,
              "feedback_detail": json_values},
)
REQUESTS = st.one_of(well_formed, malformed, json_values)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(request=REQUESTS)
def test_any_request_gets_a_documented_verdict_as_strict_json_in_bounded_time(request):
    if isinstance(request, dict) and "budget_s" not in request:
        request = dict(request, budget_s=0.5)
    started = time.monotonic()
    result = check_request(request)
    elapsed = time.monotonic() - started
    event(f"verdict: {result['verdict']}")  # --hypothesis-show-statistics: the mix of verdicts reached
    assert result["verdict"] in VERDICTS and result["certainty"] in CERTAINTIES
    assert isinstance(result["reason"], str) and result["reason"]
    assert "internal error" not in result["reason"]  # a checker bug, however handled, is a bug
    decoded = json.loads(json.dumps(result, allow_nan=False))  # strict JSON: no NaN or Infinity
    assert decoded["verdict"] == result["verdict"]
    assert all(isinstance(f.get("code"), str) and isinstance(f.get("message"), str) for f in result["feedback"])
    budget = request.get("budget_s") if isinstance(request, dict) else None
    bound = min(max(budget, 0.5), 60.0) if isinstance(budget, (int, float)) and budget == budget else 2.0
    assert elapsed < bound + 3.0


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_feedback_on_a_near_miss_never_states_a_value(data):
    # By default a slip is named, never measured: no factor, offset or difference a student could
    # use to compute the reference from their own answer (a digit in a message would be one).
    reference = data.draw(st.sampled_from(REFERENCES))
    answer = data.draw(near_misses_of(reference))
    kind = "equation" if "=" in reference else "expression"
    result = check_request({"reference": reference, "answer": answer, "variables": VARIABLES, "kind": kind,
                            "budget_s": 1.0, "state": ["theta", "thetadot"]})
    event(f"verdict: {result['verdict']}")
    event(f"feedback: {[f['code'] for f in result['feedback']]}")
    assert result["verdict"] in VERDICTS and "internal error" not in result["reason"]
    said = [f["message"] for f in result["feedback"] if f["code"] != "dimension"]
    if result["verdict"] == "not_equivalent" and not any(f["code"] == "dimension" for f in result["feedback"]):
        said.append(result["reason"])
    assert not [text for text in said if re.search("[0-9]", text)], said
