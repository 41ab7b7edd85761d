"""Request bodies: every JSON endpoint of the OpenAPI document refuses hostile JSON with a clear 4xx
(never a 500), enforces every limit its published schema states, and charges expensive checks more."""

from __future__ import annotations

import json
import re

import pytest

from grader.web.api import spec
from grader.web.api.bodies import MAX_BODY_BYTES, MAX_DEPTH
from tests.web.conftest_pages import accounts, as_student, csrf, problems  # noqa: F401  (fixtures)

# Every operation of the document that takes a JSON body, by operationId.
JSON_OPERATIONS = [op for op in spec.operations if op.request and "application/json" in op.request]
OPERATION_IDS = [op.view.__name__ for op in JSON_OPERATIONS]


def resolve(schema: dict) -> dict:
    if "$ref" in schema:
        return spec.schemas[schema["$ref"].rsplit("/", 1)[1]]
    return schema


# Strings that satisfy the patterns request schemas use (names, codes, e-mail addresses, times).
_SAMPLE_STRINGS = ["a", "a@b.org", "2026-12-01T17:00:00Z"]


def minimal(schema: dict):
    """The smallest value valid against ``schema`` (its required members only)."""
    schema = resolve(schema)
    if "oneOf" in schema:
        return minimal(schema["oneOf"][0])
    kind = schema.get("type")
    if "enum" in schema:
        return schema["enum"][0]
    if kind == "object":
        required = schema.get("required", []) + [n for b in schema.get("anyOf", [])[:1] for n in b.get("required", [])]
        return {name: minimal(schema["properties"][name]) for name in required}
    if kind == "string":
        return next(s for s in _SAMPLE_STRINGS if re.search(schema.get("pattern", ""), s))
    if kind == "array":
        return [minimal(schema["items"]) for _ in range(schema.get("minItems", 0))]
    return {"number": schema.get("minimum", 1), "integer": schema.get("minimum", 1), "boolean": True}[kind]


def url_of(op) -> str:
    path = re.sub(r"<int:\w+>", "1", op.rule)
    return "/api/v1" + re.sub(r"<\w+>", "yoyo", path)


def string_fields(schema: dict, pointer: str = ""):
    """(pointer, schema) of every string member of ``schema``'s properties, at any depth."""
    schema = resolve(schema)
    for name, member in schema.get("properties", {}).items():
        member = resolve(member)
        if member.get("type") == "string":
            yield f"{pointer}/{name}", member
        elif member.get("type") == "object":
            yield from string_fields(member, f"{pointer}/{name}")


def with_value(body: dict, pointer: str, value) -> dict:
    body = json.loads(json.dumps(body))
    *parents, last = pointer.strip("/").split("/")
    node = body
    for part in parents:
        node = node.setdefault(part, {})
    node[last] = value
    return body


@pytest.fixture
def headers_for(make_token):
    """Headers with a token of a role the operation admits."""
    def make(op):
        return make_token(sorted(op.roles)[0])[1] if op.roles else {}
    return make


def test_there_are_json_operations_to_test():
    assert {"check_answer", "create_submission"} <= set(OPERATION_IDS)


@pytest.mark.parametrize("op", JSON_OPERATIONS, ids=OPERATION_IDS)
def test_the_minimal_valid_body_passes_validation(client, headers_for, yoyo_version, op):
    response = client.open(url_of(op), method=op.method, json=minimal(op.request["application/json"]),
                           headers=headers_for(op))
    # The view may still refuse it (no answer 'a'), but not the schema: no field is named as wrong.
    assert response.status_code not in (400, 413, 415), response.get_json()
    assert "errors" not in (response.get_json() or {}), response.get_json()
    assert response.status_code < 500


HOSTILE = {
    # name: (raw body, status, words in the detail)
    "nan": (b'{"x": NaN}', 400, "NaN is not a JSON number"),
    "infinity": (b'{"x": Infinity}', 400, "Infinity is not a JSON number"),
    "minus-infinity": (b'{"x": -Infinity}', 400, "Infinity is not a JSON number"),
    "overflowing-float": (b'{"x": 1e999}', 400, "too large"),
    "hundreds-of-digits": (b'{"x": 1' + b"0" * 400 + b"}", 400, "too long"),
    "deep-arrays": (b"[" * 20_000 + b"]" * 20_000, 400, "nested more than"),
    "deep-objects": (b'{"a":' * 5_000 + b"1" + b"}" * 5_000, 400, "nested more than"),
    "just-too-deep": (b'{"x":' + b"[" * MAX_DEPTH + b"]" * MAX_DEPTH + b"}", 400, "nested more than"),
    "lone-surrogate": (b'{"x": "\\ud800"}', 400, "lone surrogate"),
    "lone-low-surrogate-key": (b'{"\\udc00": 1}', 400, "lone surrogate"),
    "nul-character": (b'{"x": "a\\u0000b"}', 400, "NUL character"),  # PostgreSQL text cannot hold it
    "not-utf8": (b'{"x": "\xff\xfe"}', 400, "not UTF-8"),
    "truncated": (b'{"x": ', 400, "not valid JSON"),
    "empty": (b"", 400, "not valid JSON"),
    "long-key": (b'{"' + b"k" * 65 + b'": 1}', 400, "key of 65 characters"),
    "array-body": (b"[1, 2]", 422, "body must be of type object"),
    "string-body": (b'"text"', 422, "body must be of type object"),
    "null-body": (b"null", 422, "body must be of type object"),
    "number-body": (b"3", 422, "body must be of type object"),
    "too-large": (b'{"x": "' + b"a" * MAX_BODY_BYTES + b'"}', 413, "at most"),
}


# One app per operation, every case against it (an app per case would take a minute).
@pytest.mark.parametrize("op", JSON_OPERATIONS, ids=OPERATION_IDS)
def test_hostile_json_is_a_clear_4xx_problem(client, headers_for, yoyo_version, op):
    headers = {**headers_for(op), "Content-Type": "application/json"}
    for case, (raw, status, words) in HOSTILE.items():
        response = client.open(url_of(op), method=op.method, data=raw, headers=headers)
        assert response.status_code == status, case
        assert response.mimetype == "application/problem+json", case
        assert words in response.get_json()["detail"], case


@pytest.mark.parametrize("op", JSON_OPERATIONS, ids=OPERATION_IDS)
def test_a_body_that_is_not_declared_json_is_415(client, headers_for, yoyo_version, op):
    body = json.dumps(minimal(op.request["application/json"]))
    for content_type in ["text/plain", "application/x-www-form-urlencoded", None, "application/json-patch+json"]:
        headers = {**headers_for(op), **({"Content-Type": content_type} if content_type else {})}
        response = client.open(url_of(op), method=op.method, data=body, headers=headers)
        assert response.status_code == 415, content_type
        assert response.get_json()["type"].endswith("unsupported-media-type"), content_type


@pytest.mark.parametrize("op", JSON_OPERATIONS, ids=OPERATION_IDS)
def test_a_lone_surrogate_in_any_text_field_is_refused_with_its_pointer(client, headers_for, yoyo_version, op):
    schema = op.request["application/json"]
    for pointer, _ in string_fields(schema):
        body = json.dumps(with_value(minimal(schema), pointer, "m\ud800"))
        response = client.open(url_of(op), method=op.method, data=body,
                               headers={**headers_for(op), "Content-Type": "application/json"})
        assert response.status_code == 400, pointer
        assert response.get_json()["errors"][0]["pointer"] == pointer


def capped_fields(schema: dict, pointer: str = ""):
    """(pointer, kind of limit, the limit) of every limited member of a request schema."""
    schema = resolve(schema)
    for name, member in schema.get("properties", {}).items():
        member, here = resolve(member), f"{pointer}/{name}"
        for limit in ("maxLength", "maxItems", "maxProperties", "minimum", "maximum"):
            if limit in member:
                yield here, limit, member[limit]
        if member.get("type") == "object" and "properties" in member:
            yield from capped_fields(member, here)


def over(limit: str, value):
    return {"maxLength": lambda n: "a" * (n + 1), "maxItems": lambda n: ["a"] * (n + 1),
            "maxProperties": lambda n: {f"v{i}": {} for i in range(n + 1)},
            "minimum": lambda n: n - 1, "maximum": lambda n: n + 1}[limit](value)


@pytest.mark.parametrize("op", JSON_OPERATIONS, ids=OPERATION_IDS)
def test_every_published_limit_is_enforced_with_the_fields_pointer(client, headers_for, yoyo_version, op):
    schema = op.request["application/json"]
    fields = list(capped_fields(schema))
    assert fields, "a JSON body without a single limit"
    for pointer, limit, value in fields:
        response = client.open(url_of(op), method=op.method, json=with_value(minimal(schema), pointer, over(limit, value)),
                               headers=headers_for(op))
        assert response.status_code == 422, (pointer, limit)
        assert pointer in [e["pointer"] for e in response.get_json()["errors"]], (pointer, limit)


def request_schemas():
    for op in JSON_OPERATIONS:
        yield from _members(resolve(op.request["application/json"]), op.view.__name__)


def _members(schema: dict, where: str):
    schema = resolve(schema)
    yield where, schema
    for name, member in schema.get("properties", {}).items():
        yield from _members(member, f"{where}.{name}")
    for key in ("items", "additionalProperties"):
        if isinstance(schema.get(key), dict):
            yield from _members(schema[key], f"{where}.{key}")
    for branch in schema.get("oneOf", []):
        yield from _members(branch, f"{where}.oneOf")


def test_every_string_list_and_map_of_every_request_body_has_a_published_cap():
    # (Numbers need no cap of their own: every number is finite and at most 40 characters.)
    uncapped = []
    for where, schema in request_schemas():
        kind = schema.get("type")
        if kind == "string" and "maxLength" not in schema and "enum" not in schema:
            uncapped.append(where)
        if kind == "array" and "maxItems" not in schema:
            uncapped.append(where)
        if kind == "object" and schema.get("additionalProperties") not in (False, None) \
                and "maxProperties" not in schema:
            uncapped.append(where)
        if kind == "object" and "additionalProperties" not in schema:
            uncapped.append(f"{where} (open to any member)")
    assert uncapped == []


@pytest.mark.parametrize("key, status", [("k" * 200, 202), ("k" * 201, 422), ("", 422), ("a\x00b", 422)])
def test_the_idempotency_key_has_the_length_its_column_has(client, make_token, yoyo_version, key, status):
    _, student = make_token("student")
    response = client.post("/api/v1/problems/yoyo/submissions", json={"answer": "tension", "text": "m*g/3"},
                           headers={**student, "Idempotency-Key": key})
    assert response.status_code == status
    if status == 422:
        assert "Idempotency-Key" in response.get_json()["detail"]


@pytest.mark.parametrize("body, pointer", [
    ({"answer": "no such answer!", "text": "x"}, "/answer"),  # answer names are names
    ({"answer": "tension", "text": "x", "user": "u" * 201}, "/user"),  # users.external_id is String(200)
    ({"answer": "t" * 65, "text": "x"}, "/answer"),  # submissions.answer_name is String(64)
])
def test_submission_fields_have_the_database_lengths(client, make_token, yoyo_version, body, pointer):
    _, lms = make_token("lms")
    response = client.post("/api/v1/problems/yoyo/submissions", json=body, headers=lms)
    assert response.status_code == 422
    assert [e["pointer"] for e in response.get_json()["errors"]] == [pointer]


class _InstantChecker:
    def run(self, request, budget_s=None):
        return {"verdict": "equivalent", "certainty": "proved", "reason": None, "parsed": None,
                "counterexample": None, "feedback": None, "ms": 0.1}

    def close(self):
        pass


@pytest.fixture
def limited(app):
    """The app with rate limits on (check: 60 a minute, bursts of 20) and an instant checker."""
    from grader.jobs.grading import CheckerPool

    app.config.update(RATE_LIMITS_ENABLED=True, RATE_LIMITS={**app.config["RATE_LIMITS"], "check": (60, 20)})
    app.extensions["lagrade.checkers"].close()
    app.extensions["lagrade.checkers"] = CheckerPool(1, _InstantChecker)
    return app


CHEAP = {"reference": "m*g", "answer": "g*m", "variables": {"m": {"dimension": "mass"}, "g": {}}}
EXPENSIVE = {**CHEAP, "feedback": [{"expr": f"{i}*m*g", "message": "no"} for i in range(2, 12)]}  # 1 + 10 tokens


def _statuses(client, headers, body, n):
    return [client.post("/api/v1/check", json=body, headers=headers).status_code for _ in range(n)]


def test_a_check_with_many_feedback_items_costs_more_of_the_rate_limit(limited, make_token):
    client = limited.test_client()
    _, cheap = make_token("student")
    _, costly = make_token("student")
    assert _statuses(client, cheap, CHEAP, 20) == [200] * 20  # a burst of 20 plain checks
    assert _statuses(client, costly, EXPENSIVE, 2)[-1] == 429  # 11 + 11 tokens exceed the burst
    refused = client.post("/api/v1/check", json=EXPENSIVE, headers=costly)
    assert refused.status_code == 429 and int(refused.headers["Retry-After"]) >= 1


def test_invalid_checks_are_charged_too(limited, make_token):
    client = limited.test_client()
    _, student = make_token("student")
    statuses = _statuses(client, student, {"reference": "m"}, 21)
    assert statuses[:20] == [422] * 20 and statuses[20] == 429


def _int_routes(app):
    for rule in app.url_map.iter_rules():
        if "<int:" in rule.rule and "GET" in rule.methods:
            yield rule.rule


@pytest.mark.parametrize("value", ["2147483648", "9" * 30])
def test_an_id_beyond_the_databases_integers_is_404_in_every_route(app, client, make_token, value):
    # Ids are 32-bit INTEGER columns on PostgreSQL; a larger one used to reach the database (a 500).
    _, admin = make_token("admin")
    routes = list(_int_routes(app))
    assert any(r.startswith("/api/") for r in routes) and any(not r.startswith("/api/") for r in routes)
    for rule in routes:
        url = re.sub(r"<int:\w+>", value, re.sub(r"<\w+>", "yoyo", rule))
        assert client.get(url, headers=admin).status_code == 404, url


def test_a_slug_longer_than_any_stored_one_is_404(client, make_token):
    _, student = make_token("student")
    response = client.get("/api/v1/problems/" + "p" * 101, headers=student)
    assert response.status_code == 404 and response.mimetype == "application/problem+json"


# The pages' one JSON endpoint (the live preview) parses its body by the same strict rules.
@pytest.mark.parametrize("raw", [HOSTILE[case][0] for case in ("deep-arrays", "lone-surrogate", "nan", "not-utf8")]
                         + [b'{"problem": "\\ud800", "answer": "tension", "text": "m"}'],
                         ids=["deep", "lone-surrogate", "nan", "not-utf8", "surrogate-in-problem"])
def test_the_live_preview_refuses_hostile_json_with_a_400(as_student, problems, raw):
    response = as_student.post("/preview", data=raw, headers={"Content-Type": "application/json",
                                                              "X-CSRF-Token": csrf(as_student)})
    assert response.status_code == 400 and "Send JSON" in response.get_json()["error"]


@pytest.fixture
def unstorable_app(app):
    from grader.store.lengths import StoredValueError

    @app.get("/api/v1/unstorable")
    def unstorable():
        raise StoredValueError("users.name", "201 characters; the limit is 200")

    app.config["PROPAGATE_EXCEPTIONS"] = False
    return app


def test_a_value_its_column_cannot_hold_is_a_422_naming_the_column(unstorable_app):
    response = unstorable_app.test_client().get("/api/v1/unstorable")
    assert response.status_code == 422 and response.mimetype == "application/problem+json"
    assert "users.name: 201 characters; the limit is 200" in response.get_json()["detail"]


def test_the_costliest_valid_check_still_passes_once_the_bucket_is_full(limited, make_token):
    # 1 + 16 feedback items + 64 variables / 16 = 21 tokens, more than the burst of 20: charged the burst.
    client = limited.test_client()
    _, student = make_token("student")
    body = {**CHEAP, "variables": {f"v{i}": {} for i in range(64)},
            "feedback": [{"expr": f"{i}*m*g", "message": "no"} for i in range(2, 18)]}
    assert _statuses(client, student, body, 2) == [200, 429]


@pytest.mark.parametrize("query, status", [("format=csv", 200), ("format=json", 200), ("format=xml", 422)])
def test_a_documented_query_parameter_is_enforced(client, make_token, yoyo_version, query, status):
    _, admin = make_token("admin")
    response = client.get(f"/api/v1/problems/yoyo/grades?{query}", headers=admin)
    assert response.status_code == status
    if status == 422:
        assert "The format query parameter must be one of json, csv" in response.get_json()["detail"]


# Inputs that are valid JSON of the right shape but hostile to the checker: a verdict, never a 500.
@pytest.mark.parametrize("reference, answer", [
    ("x", "x + 1"),  # a reference plus a constant, x dimensionless
    ("atan2(x, 1)", "atan2(x)"),  # a function with one argument too few
    ("x", "9^9^9^9^9"),
    ("x", "(" * 300 + "x" + ")" * 300),
    ("x", "sin(" * 120 + "x" + ")" * 120),
    ("x", "x" * 4000),
])
def test_hostile_but_well_formed_checks_get_a_documented_verdict(client, make_token, reference, answer):
    from grader.answers.verdict import VERDICTS

    _, student = make_token("student")
    response = client.post("/api/v1/check", headers=student,
                           json={"reference": reference, "answer": answer, "variables": {"x": {}}})
    assert response.status_code == 200
    assert response.get_json()["verdict"] in VERDICTS


@pytest.mark.parametrize("source", [b'id = "x"\na = ' + b"[" * 5000 + b"]" * 5000,
                                    b'id = "x"\na = ' + b"{b=" * 2000 + b"1" + b"}" * 2000],
                         ids=["arrays", "inline-tables"])
def test_a_deeply_nested_scene_upload_is_a_422(client, make_token, source):
    _, instructor = make_token("instructor")
    response = client.post("/api/v1/problems", data=source,
                           headers={**instructor, "Content-Type": "application/toml"})
    assert response.status_code == 422 and "nested too deeply" in response.get_json()["detail"]


@pytest.mark.parametrize("method, url, data", [
    ("POST", "/login", {"username": "a\x00b@example.org", "password": "x"}),  # was a 500 on PostgreSQL
    ("GET", "/login?next=/problems%00", None),
    ("GET", "/api/v1/health?x=%00", None),
], ids=["form-field", "query", "api-query"])
def test_a_nul_character_in_a_form_or_query_is_a_400(app, method, url, data):
    client = app.test_client()
    client.get("/login")
    if data is not None:
        data = {**data, "csrf_token": csrf(client)}
    assert client.open(url, method=method, data=data).status_code == 400
