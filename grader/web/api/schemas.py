"""JSON schemas of the API, used twice: published in the OpenAPI document and enforced on requests.

:func:`read_json` validates a request body against the small subset of JSON Schema used here
(object, required, properties, string/integer/object/array, maxLength, enum, additionalProperties),
so that what the document promises is what the server checks.
"""

from __future__ import annotations

from typing import Any

from flask import request

from grader.jobs.queue import MAX_ANSWER_CHARS
from grader.web.errors import ApiProblem

__all__ = ["CHECK_REQUEST", "CHECK_RESULT", "SUBMISSION_REQUEST", "read_json"]

_VARIABLE = {
    "type": "object",
    "properties": {"dimension": {"type": "string"}, "domain": {}},
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
        "reference": {"type": "string", "maxLength": 4000},
        "answer": {"type": "string", "maxLength": MAX_ANSWER_CHARS},
        "variables": {"type": "object", "additionalProperties": _VARIABLE},
        "kind": {"type": "string", "enum": ["expression", "equation"], "default": "expression"},
        "feedback": {"type": "array", "items": {"type": "object", "properties": {
            "expr": {"type": "string"}, "message": {"type": "string"}}}},
        "state": {"type": "array", "items": {"type": "string"},
                  "description": "Equations: the names that are state (coordinates, velocities)."},
        "budget_s": {"type": "number", "description": "Time budget; capped by the server's own."},
    },
}

CHECK_RESULT = {
    "type": "object",
    "description": "Exactly one line of `grader check --jsonl`.",
    "required": ["verdict", "certainty", "reason", "parsed", "counterexample", "feedback", "ms"],
    "properties": {
        "verdict": {"type": "string"},
        "certainty": {"type": "string", "nullable": True},
        "reason": {"type": "string", "nullable": True},
        "parsed": {**PARSED, "nullable": True},
        "counterexample": {"type": "object", "nullable": True},
        "feedback": {"nullable": True},
        "ms": {"type": "number"},
        "evidence": {"type": "object"},
        "budget_exceeded": {"type": "boolean"},
    },
}

SUBMISSION_REQUEST = {
    "type": "object",
    "required": ["answer", "text"],
    "additionalProperties": False,
    "properties": {
        "answer": {"type": "string", "maxLength": 64, "description": "The name of the problem's answer."},
        "text": {"type": "string", "maxLength": MAX_ANSWER_CHARS, "description": "The student's answer."},
        "user": {"type": "string", "maxLength": 200,
                 "description": "LMS tokens only: the external id of the student this is for."},
    },
}

_PY_TYPES = {"string": str, "object": dict, "array": list, "integer": int, "number": (int, float), "boolean": bool}


def read_json(schema: dict) -> dict[str, Any]:
    """The request's JSON body, checked against ``schema``; a 400/415/422 problem otherwise."""
    if not request.is_json:
        raise ApiProblem(415, "Send the body as JSON with 'Content-Type: application/json'.", kind="unsupported-media-type")
    body = request.get_json(silent=True)
    if body is None:
        raise ApiProblem(400, "The body is not valid JSON.", kind="invalid-json")
    errors = list(_errors(body, schema, "body"))
    if errors:
        raise ApiProblem(422, "; ".join(errors), kind="invalid-request", errors=errors)
    return body


def _errors(value: Any, schema: dict, where: str):
    expected = schema.get("type")
    if expected and (not isinstance(value, _PY_TYPES[expected]) or (expected != "boolean" and isinstance(value, bool))):
        yield f"{where} must be of type {expected}"
        return
    if "enum" in schema and value not in schema["enum"]:
        yield f"{where} must be one of {', '.join(map(str, schema['enum']))}"
    if "maxLength" in schema and len(value) > schema["maxLength"]:
        yield f"{where} is {len(value)} characters long; the limit is {schema['maxLength']}"
    if expected == "object":
        properties = schema.get("properties", {})
        for name in schema.get("required", []):
            if name not in value:
                yield f"{where}.{name} is required"
        extra = schema.get("additionalProperties", True)
        for name, item in value.items():
            if name in properties:
                yield from _errors(item, properties[name], f"{where}.{name}")
            elif extra is False:
                yield f"{where}.{name} is not a known field"
            elif isinstance(extra, dict):
                yield from _errors(item, extra, f"{where}.{name}")
    if expected == "array" and "items" in schema:
        for index, item in enumerate(value):
            yield from _errors(item, schema["items"], f"{where}[{index}]")
