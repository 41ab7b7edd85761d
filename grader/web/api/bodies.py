"""Request bodies of the API: strict JSON, checked against the schema the OpenAPI document publishes.

The route registry (:mod:`grader.web.api.spec`) calls :func:`validated_body` before a view runs, so
every JSON endpoint gets the same treatment and what the document says is what the server enforces:

- the body is at most :data:`MAX_BODY_BYTES`, UTF-8, one JSON value at most :data:`MAX_DEPTH` deep
  (deeper ones are refused before they can exhaust the parser's recursion), with finite numbers of
  reasonable length (no ``NaN``, ``Infinity``, ``1e999`` or a thousand digits), object keys of at
  most :data:`MAX_KEY_CHARS` characters and no lone surrogates (``"\\ud800"``) or NUL characters in
  any string: a 400;
- then the operation's JSON Schema (its ``maxLength``, ``maxItems``, ``maxProperties``,
  ``minimum``/``maximum``, ``pattern``, ``enum``, ``required``, ``additionalProperties``), checked
  by ``jsonschema``: a 422 listing each error with the JSON pointer of the field.

Problem documents carry ``errors: [{"pointer": "/variables/m/domain", "detail": "..."}]``.

Examples
--------
>>> parse_strict(b'{"budget_s": 2.5, "kind": "expression"}')
{'budget_s': 2.5, 'kind': 'expression'}
>>> parse_strict(b'{"budget_s": NaN}')
Traceback (most recent call last):
...
grader.web.errors.ApiProblem: The body is not valid JSON: NaN is not a JSON number.
>>> problems_of({"a": "x" * 5}, {"type": "object", "properties": {"a": {"type": "string", "maxLength": 3}}})
[{'pointer': '/a', 'detail': 'body.a is 5 characters long; the limit is 3'}]
"""

from __future__ import annotations

import json
import math
import re
from functools import lru_cache
from typing import Any

from jsonschema import Draft202012Validator, ValidationError

from grader.web.errors import ApiProblem

__all__ = ["MAX_BODY_BYTES", "MAX_DEPTH", "MAX_KEY_CHARS", "LIMITS_TEXT", "parse_strict", "problems_of",
           "validated_body", "validator_for"]

MAX_BODY_BYTES = 64 * 1024  # the largest valid body (a check with every list full) is well under this
MAX_DEPTH = 8  # {"variables": {"m": {"domain": [0, 1]}}} is 4 levels deep
MAX_KEY_CHARS = 64
_MAX_NUMBER_CHARS = 40  # a float64 needs at most 25 characters; `budget_s: 1000…0` gains nothing
_SURROGATE = re.compile("[\ud800-\udfff]")
_NUL = "\x00"  # PostgreSQL text cannot hold it; nothing a client sends needs it
_CONSTANTS = {"NaN", "Infinity", "-Infinity"}

# What every JSON body must be, said once (the OpenAPI document's description repeats it).
LIMITS_TEXT = (f"JSON request bodies are at most {MAX_BODY_BYTES // 1024} KiB of UTF-8, at most {MAX_DEPTH} levels "
               f"deep, with finite numbers of at most {_MAX_NUMBER_CHARS} characters, object keys of at most "
               f"{MAX_KEY_CHARS} characters and no lone surrogates or NUL characters in strings; each field has "
               "the limits of its schema.")


def _bad_json(reason: str, pointer: str | None = None) -> ApiProblem:
    extra = {"errors": [{"pointer": pointer, "detail": reason}]} if pointer is not None else {}
    return ApiProblem(400, f"The body is not valid JSON: {reason}.", kind="invalid-json", **extra)


def _constant(name: str) -> float:
    raise _bad_json(f"{name} is not a JSON number")


def _number(text: str, kind: type) -> int | float:
    if len(text) > _MAX_NUMBER_CHARS:
        raise _bad_json(f"a number of {len(text)} characters is too long (at most {_MAX_NUMBER_CHARS})")
    value = kind(text)
    if isinstance(value, float) and not math.isfinite(value):
        raise _bad_json(f"{text} is too large for a number")
    return value


def parse_strict(raw: bytes) -> Any:
    """Parse a request body as strict JSON, or raise a 400 :class:`ApiProblem` saying why."""
    if len(raw) > MAX_BODY_BYTES:
        raise ApiProblem(413, f"A JSON body may be at most {MAX_BODY_BYTES // 1024} KiB.", kind="too-large")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as error:
        raise _bad_json(f"it is not UTF-8 (byte {error.start})") from None
    try:
        value = json.loads(text, parse_constant=_constant, parse_int=lambda t: _number(t, int),
                           parse_float=lambda t: _number(t, float))
    except RecursionError:  # the C parser recurses per level; the limit is far above MAX_DEPTH
        raise _bad_json(f"it is nested more than {MAX_DEPTH} levels deep") from None
    except json.JSONDecodeError as error:
        raise _bad_json(f"{error.msg} at line {error.lineno} column {error.colno}") from None
    _check_values(value)
    return value


def _check_values(value: Any) -> None:
    """Depth, key lengths and lone surrogates, by an explicit walk (no recursion on hostile input)."""
    stack = [(value, "", 1)]
    while stack:
        node, pointer, depth = stack.pop()
        if isinstance(node, str):
            if _SURROGATE.search(node):
                raise _bad_json("a string holds a lone surrogate (\\ud800-\\udfff), which is not text", pointer or "/")
            if _NUL in node:
                raise _bad_json("a string holds a NUL character (\\u0000), which is not text", pointer or "/")
        elif isinstance(node, (dict, list)):
            if depth > MAX_DEPTH:
                raise _bad_json(f"it is nested more than {MAX_DEPTH} levels deep", pointer)
            items = node.items() if isinstance(node, dict) else enumerate(node)
            for key, item in items:
                if isinstance(key, str):
                    if _SURROGATE.search(key) or _NUL in key:
                        raise _bad_json("a key holds a lone surrogate or a NUL character, which is not text",
                                        pointer or "/")
                    if len(key) > MAX_KEY_CHARS:
                        raise _bad_json(f"a key of {len(key)} characters is too long (at most {MAX_KEY_CHARS})",
                                        pointer or "/")
                stack.append((item, f"{pointer}/{_escape(key)}", depth + 1))


def _escape(key: str | int) -> str:
    """One JSON pointer segment (RFC 6901)."""
    return str(key).replace("~", "~0").replace("/", "~1")


def _json_schema(schema: Any) -> Any:
    """An OpenAPI 3.0 schema as JSON Schema 2020-12: ``nullable: true`` becomes a "null" type."""
    if isinstance(schema, list):
        return [_json_schema(s) for s in schema]
    if not isinstance(schema, dict):
        return schema
    out = {k: _json_schema(v) for k, v in schema.items() if k != "nullable"}
    if schema.get("nullable") and "type" in schema:
        out["type"] = [schema["type"], "null"]
    return out


@lru_cache(maxsize=64)
def _validator(schema_json: str) -> Draft202012Validator:
    return Draft202012Validator(json.loads(schema_json))


# (id(schema), id(components), len(components)) -> (schema, components, validator): schemas are module
# constants, so a request finds its validator without serializing them again (about 0.1 ms saved).
_BY_IDENTITY: dict[tuple[int, int, int], tuple[Any, Any, Draft202012Validator]] = {}


def validator_for(schema: dict, components: dict[str, dict] | None = None) -> Draft202012Validator:
    """A validator of ``schema`` (OpenAPI 3.0 flavour), resolving ``#/components/schemas/...``."""
    key = (id(schema), id(components), len(components or {}))
    found = _BY_IDENTITY.get(key)
    if found is not None and found[0] is schema and found[1] is components:
        return found[2]
    document = {**_json_schema(schema), "components": {"schemas": _json_schema(components or {})}}
    validator = _validator(json.dumps(document, sort_keys=True))
    if len(_BY_IDENTITY) < 256:
        _BY_IDENTITY[key] = (schema, components, validator)
    return validator


def problems_of(body: Any, schema: dict, components: dict[str, dict] | None = None) -> list[dict[str, str]]:
    """Every way ``body`` breaks ``schema``, as ``{"pointer", "detail"}``, in document order."""
    problems = []
    for error in validator_for(schema, components).iter_errors(body):
        problems.extend(_explain(error))
    return sorted(problems, key=lambda p: p["pointer"])


_TYPE_WORDS = {"string": "a string", "object": "an object", "array": "an array", "number": "a number",
               "integer": "an integer", "boolean": "true or false", "null": "null"}


def _explain(error: ValidationError) -> list[dict[str, str]]:
    path = list(error.absolute_path)
    value, rule = error.instance, error.validator_value

    def problem(where: list, detail: str) -> dict[str, str]:
        return {"pointer": "".join(f"/{_escape(p)}" for p in where),
                "detail": f"{'.'.join(['body'] + [str(p) for p in where])} {detail}"}

    if error.validator == "required":
        return [problem(path + [name], "is required") for name in rule if name not in value]
    if error.validator == "additionalProperties":
        known = set(error.schema.get("properties", {}))
        return [problem(path + [name], "is not a known field") for name in value if name not in known]
    if error.validator == "type":
        types = rule if isinstance(rule, list) else [rule]
        return [problem(path, "must be of type " + " or ".join(t for t in types))]
    words = {
        "enum": lambda: "must be one of " + ", ".join(map(str, rule)),
        "maxLength": lambda: f"is {len(value)} characters long; the limit is {rule}",
        "minLength": lambda: f"must have at least {rule} character{'s' if rule != 1 else ''}",
        "maxItems": lambda: f"has {len(value)} items; the limit is {rule}",
        "maxProperties": lambda: f"has {len(value)} members; the limit is {rule}",
        "minimum": lambda: f"must be at least {rule}",
        "maximum": lambda: f"must be at most {rule}",
        "pattern": lambda: f"must match the pattern {rule}",
    }
    detail = words[error.validator]() if error.validator in words else error.message
    return [problem(path, detail)]


def validated_body(schema: dict, components: dict[str, dict]) -> Any:
    """The request's JSON body, parsed strictly and valid against ``schema``; else a problem (400/413/415/422)."""
    from flask import request

    if request.mimetype != "application/json":
        raise ApiProblem(415, "Send the body as JSON with 'Content-Type: application/json'.",
                         kind="unsupported-media-type")
    if (request.content_length or 0) > MAX_BODY_BYTES:
        raise ApiProblem(413, f"A JSON body may be at most {MAX_BODY_BYTES // 1024} KiB.", kind="too-large")
    body = parse_strict(request.get_data(cache=True))
    problems = problems_of(body, schema, components)
    if problems:
        raise ApiProblem(422, "; ".join(p["detail"] for p in problems[:10]), kind="invalid-request", errors=problems)
    return body
