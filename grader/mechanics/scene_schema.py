"""The structure of a scene file as a JSON Schema (draft 2020-12), checked right after TOML parsing.

The schema says which keys exist at every level of a scene file, of what type and how long they may
be; ``additionalProperties: false`` everywhere, so a misspelt key (``in_term_of``, ``kinteic``) is an
error with a did-you-mean instead of a key silently ignored that changes the derived answer. What
the keys *mean* (names, dimensions, expressions) is still checked by the loader in
:mod:`grader.mechanics.scene`, with its own messages.

To add a key, add it to :data:`SCENE_SCHEMA` below (one dict literal) at the level where it belongs;
``/work/coord/scene-schema.md`` and ``docs/scene-format.md`` say more.

Examples
--------
>>> structure_problems({"id": "drop", "coordinates": {"z": {"dimension": "length"}},
...                     "energy": {"kinteic": "m/2*zdot^2"}})
[('energy', "unknown key 'kinteic'; did you mean 'kinetic'?")]
>>> structure_problems({"id": "drop", "coordinates": {}, "energy": {}, "answers": [{"name": "a", "expr": 1}]})
[('answers[0] (a).expr', 'must be a string')]
"""

from __future__ import annotations

import difflib
from functools import cache
from typing import Any, Iterable

from jsonschema import Draft202012Validator, ValidationError

__all__ = ["MAX_ITEMS", "SCENE_SCHEMA", "scene_validator", "structure_problems"]

MAX_ITEMS = 64  # entries of any table or list (parameters, constraints, answers...)
MAX_TITLE_CHARS = 200  # problem_versions.title is String(200)
MAX_NAME_CHARS = 64  # submissions.answer_name is String(64)
MAX_EXPRESSION_CHARS = 4000  # the longest reference POST /check accepts
MAX_TEXT_CHARS = 2000  # a prompt or a feedback message
MAX_STATEMENT_CHARS = 50_000


def _string(max_length: int, **more: Any) -> dict[str, Any]:
    return {"type": "string", "maxLength": max_length, **more}


_EXPRESSION = _string(MAX_EXPRESSION_CHARS, description="an expression in a string")
# Numbers are allowed where the loader reads `theta = 0` as the expression "0".
_NUMBER_OR_EXPRESSION = {"anyOf": [{"type": "number"}, _EXPRESSION],
                         "description": "a number or an expression in a string"}
_DIMENSION = _string(200, description='a dimension such as "length" or "kg*m^2"')
_DOMAIN = {"anyOf": [_string(200), {"type": "array", "prefixItems": [{"type": "number"}, {"type": "number"}],
                                    "minItems": 2, "maxItems": 2}],
           "description": 'a domain: "positive", "nonnegative", "real" or [lo, hi]'}
# A declared coordinate (of the scene or of a parametrization).
_COORDINATE = {"type": "object", "additionalProperties": False,
               "properties": {"dimension": _DIMENSION, "domain": _DOMAIN}}
_FEEDBACK = {"type": "object", "additionalProperties": False, "required": ["expr", "message"],
             "properties": {"expr": _EXPRESSION, "message": _string(MAX_TEXT_CHARS),
                            "score": {"type": "number"}}}  # partial credit, 0..1 (the loader checks the range)
# A parameter drawn per student (grader.answers.randomised): random = { min, max, step } or choices = [...]
_RANDOM = {"type": "object", "additionalProperties": False, "required": ["min", "max", "step"],
           "properties": {"min": {"type": "number"}, "max": {"type": "number"}, "step": {"type": "number"}}}
_CHOICES = {"type": "array", "minItems": 1, "maxItems": MAX_ITEMS, "items": {"type": "number"}}
# [[answers.tests]]: an example answer and the verdict it must get (grader.answers.question_tests)
_TEST = {"type": "object", "additionalProperties": False, "required": ["answer", "expect"],
         "properties": {"answer": _string(MAX_EXPRESSION_CHARS),
                        "expect": {"enum": ["equivalent", "not_equivalent", "invalid"]},
                        "score": {"type": "number"},
                        "values": {"type": "object", "maxProperties": MAX_ITEMS,
                                   "additionalProperties": {"type": "number"}}}}
_TOLERANCE = {"type": "object", "additionalProperties": False,
              "properties": {"relative": {"type": "number"}, "absolute": {"type": "number"},
                             "sig_figs": {"type": "integer"}}}


def _table(values: dict[str, Any]) -> dict[str, Any]:
    """A table of user-chosen names (parameters, coordinates, initial values) to ``values``."""
    return {"type": "object", "maxProperties": MAX_ITEMS, "additionalProperties": values,
            "propertyNames": {"maxLength": MAX_NAME_CHARS}}


def _list(item: dict[str, Any]) -> dict[str, Any]:
    """A TOML array of tables (``[[constraints]]``, ``[[answers]]``)."""
    return {"type": "array", "maxItems": MAX_ITEMS, "items": item}


# The scene file, level by level. Add a key where it belongs; keep `additionalProperties: False`.
SCENE_SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": "lagrade scene file (docs/scene-format.md)",
    "type": "object",
    "additionalProperties": False,
    "required": ["id", "coordinates", "energy"],
    "properties": {
        "id": _string(64, pattern="^[a-z0-9][a-z0-9_-]{0,63}$",
                      description="1-64 lowercase letters, digits, '-' or '_'"),
        "title": _string(MAX_TITLE_CHARS),
        "statement": _string(MAX_STATEMENT_CHARS),
        # name = { dimension, domain, value | random | choices }
        "parameters": _table({"type": "object", "additionalProperties": False,
                              "properties": {"dimension": _DIMENSION, "domain": _DOMAIN, "value": {"type": "number"},
                                             "random": _RANDOM, "choices": _CHOICES,
                                             "below": {"type": "string", "maxLength": 64}}}),
        "coordinates": _table(_COORDINATE),
        "energy": {"type": "object", "additionalProperties": False,
                   "properties": {"kinetic": _NUMBER_OR_EXPRESSION, "potential": _NUMBER_OR_EXPRESSION}},
        "constraints": _list({
            "type": "object", "additionalProperties": False, "required": ["f"],
            "properties": {
                "name": _string(MAX_NAME_CHARS),
                "f": _EXPRESSION,
                # "rolling" and the contact keys below are read by grader/simulate (effects).
                "kind": {"enum": ["bilateral", "unilateral", "rolling"]},
                "restitution": _NUMBER_OR_EXPRESSION,  # unilateral: bounce (0 sticks, 1 elastic)
                "mu_s": _NUMBER_OR_EXPRESSION,  # rolling: static friction coefficient
                "mu_k": _NUMBER_OR_EXPRESSION,  # rolling: kinetic friction coefficient
                "normal": _string(MAX_NAME_CHARS),  # rolling: the constraint giving the normal force
            },
        }),
        # coordinate or velocity name = number or expression in parameters
        "initial": _table(_NUMBER_OR_EXPRESSION),
        # the motion shown on the problem page (grader/simulate/motion.py)
        "simulation": {"type": "object", "additionalProperties": False, "properties": {
            "t_end": {"type": "number", "exclusiveMinimum": 0, "maximum": 600},
            "show_students": {"type": "boolean"},
        }},
        # where to draw bodies (pictures only, grader/mechanics/geometry.py): x right, y up
        "geometry": {"type": "object", "additionalProperties": False, "properties": {
            "points": _table({"type": "array", "minItems": 2, "maxItems": 2, "items": _NUMBER_OR_EXPRESSION}),
            "bars": {"type": "array", "maxItems": MAX_ITEMS,
                     "items": {"type": "array", "minItems": 2, "maxItems": 2, "items": _string(MAX_NAME_CHARS)}},
            "circles": {"type": "array", "maxItems": MAX_ITEMS, "items": {
                "type": "object", "additionalProperties": False, "required": ["radius"],
                "properties": {"centre": {"type": "array", "minItems": 2, "maxItems": 2,
                                          "items": _NUMBER_OR_EXPRESSION},
                               "radius": _NUMBER_OR_EXPRESSION}}},
        }},
        "parametrization": {"type": "object", "additionalProperties": False,
                            "properties": {"variables": _table(_COORDINATE), "map": _table(_NUMBER_OR_EXPRESSION)}},
        # How much automatic feedback on wrong answers may say (grader.answers.feedback).
        "feedback": {"type": "object", "additionalProperties": False,
                     "properties": {"detail": {"enum": ["kind", "full"]}}},
        "answers": _list({
            "type": "object", "additionalProperties": False, "required": ["name", "expr"],
            "properties": {
                "name": _string(MAX_NAME_CHARS),
                "prompt": _string(MAX_TEXT_CHARS),
                "expr": _EXPRESSION,
                "kind": {"enum": ["expression", "equation", "small_oscillation", "maximum", "minimum", "numeric"]},
                "in_terms_of": {"type": "array", "maxItems": MAX_ITEMS, "items": _string(MAX_NAME_CHARS)},
                "dimension": _DIMENSION,
                "where": _string(MAX_EXPRESSION_CHARS, description='a condition such as "normal_force = 0"; '
                                 'an equilibrium at rest as "thetaddot = 0, thetadot = 0"'),
                "feedback": {"type": "array", "maxItems": MAX_ITEMS, "items": _FEEDBACK},
                # other values that are also right (the mirror equilibrium, the other sign convention)
                "alternatives": {"type": "array", "maxItems": MAX_ITEMS, "items": _EXPRESSION},
                # kind = "numeric": the SI unit asked for and the tolerance (grader.answers.numeric)
                "unit": _string(200),
                "tolerance": _TOLERANCE,
                "weight": {"type": "number"},  # the answer's share of the problem's score
                "tests": {"type": "array", "maxItems": MAX_ITEMS, "items": _TEST},
            },
        }),
    },
}

_TYPE_WORDS = {"string": "a string", "object": "a table", "array": "a list", "number": "a number",
               "integer": "an integer", "boolean": "true or false"}


@cache
def scene_validator() -> Draft202012Validator:
    """The compiled validator of :data:`SCENE_SCHEMA` (made once)."""
    return Draft202012Validator(SCENE_SCHEMA)


def structure_problems(data: dict[str, Any]) -> list[tuple[str, str]]:
    """Every way ``data`` (a parsed scene file) breaks the schema, as (key, problem), in file order.

    Keys are written as the loader writes them: ``answers[2] (normal_force).in_terms_of``.
    """
    problems: list[tuple[tuple[int, ...], str, str]] = []
    for error in scene_validator().iter_errors(data):
        for path, where, problem in _explain(error):
            problems.append((_file_order(data, where), _key(data, path), problem))
    problems.sort(key=lambda p: p[0])
    return [(key, problem) for _, key, problem in problems]


def _explain(error: ValidationError) -> Iterable[tuple[list[Any], list[Any], str]]:
    """(path named in the message, path of the offending place in the file, problem) for one error."""
    path, schema, value = list(error.absolute_path), error.schema, error.instance
    if error.validator == "additionalProperties":
        known = sorted(schema.get("properties", {}))
        for name in value:
            if name not in known:
                yield path, path + [name], _unknown_key(name, known)
        return
    if error.validator == "required":
        for name in error.validator_value:
            if name not in value:
                yield path + [name], path + [name], "missing (required)"
        return
    yield path, path, _problem(error)


def _problem(error: ValidationError) -> str:
    schema, value = error.schema, error.instance
    if error.validator == "type":
        return f"must be {_TYPE_WORDS.get(error.validator_value, error.validator_value)}"
    if error.validator == "enum":
        return "must be one of " + ", ".join(f'"{v}"' for v in error.validator_value)
    if error.validator == "maxLength":
        return f"is {len(value)} characters long; the limit is {error.validator_value}"
    if error.validator in ("maxItems", "maxProperties"):
        return f"has {len(value)} entries; the limit is {error.validator_value}"
    if error.validator == "propertyNames":
        return f"a name is longer than {MAX_NAME_CHARS} characters"
    if error.validator == "anyOf":
        # A value of an allowed type that breaks that branch's limits (a 5000-character
        # expression) is told about the limit, not that it has the wrong type.
        near = [e for e in error.context if e.validator in ("maxLength", "maxItems")]
        if near:
            return _problem(near[0])
    if error.validator in ("pattern", "anyOf") and "description" in schema:
        return f"must be {schema['description']}"
    return error.message  # not reached by SCENE_SCHEMA today; the library's own words are clear


def _unknown_key(name: str, known: list[str]) -> str:
    close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
    if close:
        return f"unknown key '{name}'; did you mean '{close[0]}'?"
    return f"unknown key '{name}' (known keys: {', '.join(known)})"


def _key(data: Any, path: list[Any]) -> str:
    """``answers[2] (normal_force).feedback[0]``: list items of a name carry it, as the loader writes."""
    key, node = "", data
    for part in path:
        if isinstance(part, int):
            key += f"[{part}]"
            node = node[part] if isinstance(node, list) and part < len(node) else None
            if isinstance(node, dict) and isinstance(node.get("name"), str) and path[-1] != "name":
                key += f" ({node['name']})"
        else:
            key += f".{part}" if key else str(part)
            node = node.get(part) if isinstance(node, dict) else None
    return key


def _file_order(data: Any, path: list[Any]) -> tuple[int, ...]:
    """Where ``path`` is in the file, as positions of each key in its table (TOML keeps file order)."""
    order, node = [], data
    for part in path:
        if isinstance(node, dict):
            order.append(list(node).index(part) if part in node else len(node))
            node = node.get(part)
        elif isinstance(node, list) and isinstance(part, int):
            order.append(part)
            node = node[part] if part < len(node) else None
        else:
            order.append(0)
    return tuple(order)
