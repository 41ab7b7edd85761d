"""JSON schemas of the API, used twice: published in the OpenAPI document and enforced on requests.

Every string and list in a request has a limit here (``maxLength``, ``maxItems``, ``maxProperties``,
``minimum``/``maximum``, ``pattern``); the route registry (:mod:`grader.web.api.spec`) validates
each JSON body against its schema with ``jsonschema`` before the view runs (:mod:`.bodies`), so
what the document says is what the server checks. Lengths of stored fields are read from the
database's columns (:mod:`grader.store.models`), so the two cannot drift apart.
"""

from __future__ import annotations

from typing import Any

from flask import g

from grader.answers.verdict import CERTAINTIES, VERDICTS
from grader.jobs.queue import MAX_ANSWER_CHARS
from grader.store.models import Submission, User
from grader.web.api.bodies import validated_body

__all__ = ["CHECK_REQUEST", "CHECK_RESULT", "SUBMISSION_REQUEST", "check_cost", "read_json"]

MAX_REFERENCE_CHARS = 4000
MAX_VARIABLES = 64
MAX_FEEDBACK = 16
MAX_MESSAGE_CHARS = 2000
NAME_PATTERN = "^[A-Za-z][A-Za-z0-9_]*$"

_VARIABLE = {
    "type": "object",
    "additionalProperties": False,
    "properties": {
        "dimension": {"type": "string", "maxLength": 100, "description": "e.g. 'mass', 'kg*m^2'"},
        "domain": {"oneOf": [
            {"type": "string", "maxLength": 32, "description": "'positive', 'nonnegative' or 'real'"},
            {"type": "array", "minItems": 2, "maxItems": 2, "description": "[lo, hi]",
             "items": {"oneOf": [{"type": "number"}, {"type": "string", "maxLength": 64}]}}]},
        "kind": {"type": "string", "enum": ["parameter", "coordinate", "velocity", "acceleration", "multiplier",
                                            "force", "time", "answer"]},
        "below": {"type": "string", "maxLength": 64, "pattern": NAME_PATTERN,
                  "description": "another variable of the same dimension this one stays below (d < R): answers "
                                 "are compared only where it does"},
    },
    "description": "A name the text may use: its dimension (e.g. 'mass') and domain ('positive', [lo, hi]).",
}

PARSED = {
    "type": "object",
    "properties": {"text": {"type": "string"}, "latex": {"type": "string"},
                   "notes": {"type": "array", "items": {"type": "string"}}},
}

CHECK_REQUEST = {
    "type": "object",
    "required": ["reference", "answer", "variables"],
    "additionalProperties": False,
    "properties": {
        "reference": {"type": "string", "maxLength": MAX_REFERENCE_CHARS},
        "answer": {"type": "string", "maxLength": MAX_ANSWER_CHARS},
        "variables": {"type": "object", "maxProperties": MAX_VARIABLES, "additionalProperties": _VARIABLE,
                      "description": "The names the texts may use (keys: letters, digits and _)."},
        "kind": {"type": "string", "enum": ["expression", "equation", "numeric"], "default": "expression",
                 "description": "'numeric': the answer is a number with a unit, checked against the reference "
                                "evaluated at 'values'."},
        "feedback": {"type": "array", "maxItems": MAX_FEEDBACK, "items": {
            "type": "object", "required": ["expr", "message"], "additionalProperties": False, "properties": {
                "expr": {"type": "string", "maxLength": MAX_REFERENCE_CHARS},
                "message": {"type": "string", "maxLength": MAX_MESSAGE_CHARS},
                "score": {"type": "number", "minimum": 0, "maximum": 1,
                          "description": "Partial credit for an answer that matches this entry."}}},
            "description": "Known wrong answers and what to tell a student who gives one. Each item costs "
                          "one more check against the rate limit."},
        "state": {"type": "array", "maxItems": MAX_VARIABLES, "items": {"type": "string", "maxLength": 64},
                  "description": "Equations: the names that are state (coordinates, velocities)."},
        "budget_s": {"type": "number", "minimum": 0.01, "maximum": 60,
                     "description": "Time budget in seconds; capped by the server's own."},
        "feedback_detail": {"type": "string", "enum": ["kind", "full"], "default": "kind",
                            "description": "'kind': slip messages name the slip but no value that would "
                                           "reveal the reference; 'full': they also state factors and differences."},
        # kind = "numeric" (grader.answers.numeric)
        "values": {"type": "object", "maxProperties": MAX_VARIABLES, "additionalProperties": {"type": "number"},
                   "description": "Numeric answers: the parameter values the reference is evaluated at (SI units)."},
        "unit": {"type": "string", "maxLength": 200, "description": "Numeric answers: the SI unit asked for, e.g. 'N'."},
        "dimension": {"type": "string", "maxLength": 200, "description": "Numeric answers: the answer's dimension."},
        "tolerance": {"type": "object", "additionalProperties": False, "properties": {
            "relative": {"type": "number", "minimum": 0}, "absolute": {"type": "number", "minimum": 0},
            "sig_figs": {"type": "integer", "minimum": 1, "maximum": 15}},
            "description": "Numeric answers: within relative or absolute (default 1 % relative); sig_figs: "
                           "rounded to that many significant figures."},
        "implicit": {"type": "object", "additionalProperties": False,
                     "required": ["condition", "unknown", "interval", "root"], "properties": {
                         "condition": {"type": "string", "maxLength": MAX_REFERENCE_CHARS},
                         "unknown": {"type": "string", "maxLength": 64},
                         "interval": {"type": "array", "minItems": 2, "maxItems": 2, "items": {"type": "number"}},
                         "root": {"type": "integer", "minimum": 0, "maximum": 1000}},
                     "description": "Numeric answers without a closed form: 'reference' is in 'unknown', taken at "
                                    "root number 'root' (from 0, counted upwards) of condition = 0 in 'interval', "
                                    "found numerically at 'values'."},
    },
}


def check_cost(body: dict[str, Any]) -> float:
    """Rate-limit tokens a ``POST /check`` costs: one, plus one per feedback item (each is a check
    of its own), plus a little for many variables or long texts.

    Examples
    --------
    >>> check_cost({"reference": "m*g", "answer": "m g", "variables": {"m": {}, "g": {}}})
    1.0
    >>> check_cost({"reference": "m*g", "answer": "m g", "variables": {}, "feedback": [{}] * 4})
    5.0
    """
    chars = len(body.get("reference", "")) + len(body.get("answer", ""))
    return (1.0 + len(body.get("feedback") or ()) + len(body.get("variables") or {}) // 16
            + len(body.get("state") or ()) // 16 + chars // 2000)


CHECK_RESULT = {
    "type": "object",
    "description": "Exactly one line of `grader check --jsonl`.",
    "required": ["verdict", "certainty", "reason", "parsed", "counterexample", "feedback", "ms"],
    "properties": {
        "verdict": {"type": "string", "enum": list(VERDICTS)},
        "certainty": {"type": "string", "nullable": True, "enum": [*CERTAINTIES, None]},
        "reason": {"type": "string", "nullable": True},
        "parsed": {**PARSED, "nullable": True},
        "counterexample": {"type": "object", "nullable": True},
        "feedback": {"nullable": True},
        "ms": {"type": "number"},
        "evidence": {"type": "object"},
        "budget_exceeded": {"type": "boolean"},
        "score": {"type": "number", "description": "Partial credit given by the instructor's feedback entry a "
                                                   "wrong answer matched (absent otherwise)."},
    },
}

SUBMISSION_REQUEST = {
    "type": "object",
    "required": ["answer", "text"],
    "additionalProperties": False,
    "properties": {
        "answer": {"type": "string", "maxLength": Submission.__table__.c.answer_name.type.length, "pattern": NAME_PATTERN,
                   "description": "The name of the problem's answer."},
        "text": {"type": "string", "maxLength": MAX_ANSWER_CHARS, "description": "The student's answer."},
        "user": {"type": "string", "minLength": 1, "maxLength": User.__table__.c.external_id.type.length,
                 "description": "LMS tokens only: the external id of the student this is for."},
    },
}


def read_json(schema: dict) -> dict[str, Any]:
    """The request's JSON body, valid against ``schema`` (a 400/413/415/422 problem otherwise).

    The route registry has already validated it for operations that declare a JSON body; views
    call this to get it.
    """
    body = getattr(g, "api_body", None)
    return body if body is not None else validated_body(schema, {})
