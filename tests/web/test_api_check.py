"""POST /check: a stateless check through the sandbox, answered exactly as `grader check --jsonl`."""

import pytest

VARIABLES = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"},
             "theta": {"dimension": "angle", "domain": "real"}}
CONTRACT = {"verdict", "certainty", "reason", "parsed", "counterexample", "feedback", "ms"}


# The sphere on a hemisphere: the normal force is m g (3 cos θ - 2).
@pytest.mark.parametrize("answer, verdict", [
    ("mg(3cos θ - 2)", "equivalent"),
    ("3*m*g*cos(theta) - 2*m*g", "equivalent"),
    ("m*g*(2*cos(theta) - 3)", "not_equivalent"),
    ("m*g*(3*cos(theta) - 2", "invalid"),
])
def test_check_answers_one_jsonl_line(client, make_token, answer, verdict):
    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student, json={
        "reference": "m*g*(3*cos(theta) - 2)", "answer": answer, "variables": VARIABLES, "kind": "expression"})
    assert response.status_code == 200
    body = response.get_json()
    assert CONTRACT <= set(body) and body["verdict"] == verdict
    assert set(body["parsed"]) == {"text", "latex", "notes"}


def test_check_answers_exactly_what_grader_check_jsonl_prints(client, make_token):
    import json
    import subprocess
    import sys

    line = {"reference": "m*g", "answer": "g m", "variables": VARIABLES, "kind": "expression"}
    printed = subprocess.run([sys.executable, "-c", "from grader.cli import main; main()", "check", "--jsonl"],
                             input=json.dumps(line) + "\n", capture_output=True, text=True, timeout=120, check=True)
    from_cli = json.loads(printed.stdout.splitlines()[0])
    _, lms = make_token("lms")
    from_api = client.post("/api/v1/check", headers=lms, json=line).get_json()
    assert set(from_api) == set(from_cli)
    assert {k: v for k, v in from_api.items() if k != "ms"} == {k: v for k, v in from_cli.items() if k != "ms"}


@pytest.mark.parametrize("body, detail", [
    ({"answer": "m", "variables": {}}, "body.reference is required"),
    ({"reference": "m", "answer": "m", "variables": {}, "kind": "poem"}, "body.kind must be one of"),
    ({"reference": "m", "answer": ["m"], "variables": {}}, "body.answer must be of type string"),
])
def test_malformed_checks_are_422_problems(client, make_token, body, detail):
    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student, json=body)
    assert response.status_code == 422 and detail in response.get_json()["detail"]


DIMENSIONLESS = {"x": {"dimension": "dimensionless", "domain": "real"}}


# Inputs that once answered 500 or an internal error: each now gets its verdict. (A lone surrogate
# never reaches the checker here: the body validation refuses it with a 400.)
@pytest.mark.parametrize("reference, answer, verdict", [
    ("x", "x + 1", "not_equivalent"),      # a reference plus a constant
    ("x", "atan2(x)", "invalid"),          # a function with too few arguments
    ("atan2(x)", "x", "invalid"),          # ...in the reference
])
def test_inputs_that_used_to_break_the_checker_get_a_verdict(client, make_token, reference, answer, verdict):
    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student,
                           json={"reference": reference, "answer": answer, "variables": DIMENSIONLESS})
    assert response.status_code == 200
    body = response.get_json()
    assert body["verdict"] == verdict and "internal error" not in body["reason"]


def test_a_checker_whose_child_dies_on_start_up_is_a_503_not_a_500(app, client, make_token, monkeypatch):
    from pathlib import Path

    from grader.answers.sandbox import SandboxedChecker
    from grader.jobs.grading import CheckerPool

    monkeypatch.setenv("PYTHONPATH", str(Path(__file__).parents[1]))  # tests/sandbox_handlers.py
    app.extensions["lagrade.checkers"] = CheckerPool(
        1, lambda: SandboxedChecker(budget_s=1.0, handler="sandbox_handlers:no_such_handler"))
    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student,
                           json={"reference": "x", "answer": "x", "variables": DIMENSIONLESS})
    assert response.status_code == 503 and response.headers["Retry-After"] == "1"
    app.extensions["lagrade.checkers"].close()


@pytest.mark.parametrize("answer, verdict", [("14.7 N", "equivalent"), ("0.0147 kN", "equivalent"),
                                             ("14.7 m", "not_equivalent"), ("14,7 N", "invalid")])
def test_numeric_answers_are_checked_at_the_given_values(client, make_token, answer, verdict):
    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student, json={
        "reference": "m*g", "answer": answer, "variables": VARIABLES, "kind": "numeric",
        "values": {"m": 1.5, "g": 9.81}, "unit": "N", "tolerance": {"relative": 0.01}})
    assert response.status_code == 200 and response.get_json()["verdict"] == verdict


@pytest.mark.parametrize("k, status, verdict", [(5.0, 200, "equivalent"), (9.0, 200, "not_equivalent")])
def test_a_numeric_answer_without_a_closed_form_is_checked_at_its_root(client, make_token, k, status, verdict):
    # the tilt of an upright pendulum on a torsion spring: g sin θ = k θ (root 2 in [0, π])
    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student, json={
        "reference": "theta", "answer": "1.873 rad", "kind": "numeric", "unit": "rad",
        "variables": {"g": {"dimension": "acceleration", "domain": "positive"},
                      "k": {"dimension": "1/s^2", "domain": "positive"},
                      "theta": {"dimension": "angle", "domain": [0, 3.1416]}},
        "values": {"g": 9.81, "k": k},
        "implicit": {"condition": "g*sin(theta) - k*theta", "unknown": "theta", "interval": [0, 3.1416], "root": 1}})
    assert response.status_code == status and response.get_json()["verdict"] == verdict


def test_a_malformed_implicit_root_is_refused_by_the_schema(client, make_token):
    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student, json={
        "reference": "theta", "answer": "1 rad", "kind": "numeric", "unit": "rad", "values": {},
        "variables": {"theta": {"dimension": "angle", "domain": [0, 3.1416]}},
        "implicit": {"condition": "sin(theta)", "unknown": "theta", "interval": [0], "root": 0}})
    assert response.status_code == 422 and "implicit" in response.get_data(as_text=True)


def test_partial_credit_of_a_matched_feedback_entry_is_in_the_verdict(client, make_token):
    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student, json={
        "reference": "m*g/3", "answer": "m g", "variables": VARIABLES,
        "feedback": [{"expr": "m*g", "message": "That is the weight.", "score": 0.25}]})
    body = response.get_json()
    assert response.status_code == 200 and body["verdict"] == "not_equivalent" and body["score"] == 0.25


def test_a_variable_below_another_is_part_of_the_check_contract(client, make_token):
    """'below' goes through the request schema to the checker: |R − a| is R − a where a < R."""
    _, student = make_token("student")
    variables = {"R": {"dimension": "length", "domain": "positive"},
                 "a": {"dimension": "length", "domain": "positive", "below": "R"},
                 "g": {"dimension": "acceleration", "domain": "positive"}}
    body = {"reference": "sqrt(g*(R - a))", "answer": "sqrt(g abs(R - a))", "variables": variables}
    response = client.post("/api/v1/check", headers=student, json=body)
    assert response.status_code == 200 and response.get_json()["verdict"] == "equivalent"
    variables["a"]["below"] = "R; drop table"
    assert client.post("/api/v1/check", headers=student, json=body).status_code == 422


@pytest.mark.parametrize("dimension", ["kg^(1/0)", "kg^(0/0)", "m^(-1/0)", "kg^(10^400)"])
def test_a_variable_dimension_with_an_impossible_exponent_is_refused_as_a_bad_dimension(client, make_token,
                                                                                        dimension):
    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student, json={
        "reference": "m", "answer": "m", "variables": {"m": {"dimension": dimension, "domain": "positive"}}})
    body = response.get_json()
    assert "internal error" not in str(body)
    assert "exponent" in str(body)
