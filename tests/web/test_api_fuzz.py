"""A property-based fuzzer over the JSON API: whatever a client sends to any operation of the OpenAPI
document, the answer is valid JSON, has a status the document lists for that operation, matches the
documented schema, is never a 5xx, and comes within a bounded time.

Bodies are generated near the published schemas (so that many reach the views and the real,
sandboxed checker, with a short budget) and far from them (any JSON, hostile strings with lone
surrogates and control characters, NaN, huge numbers, deep nesting, bytes that are not UTF-8).
Bounded for CI: a fixed number of examples per database, about 15-25 s each.
"""

from __future__ import annotations

import json
import re
import string
import time
from pathlib import Path
from urllib.parse import quote

import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from grader.web.api import spec
from grader.web.api.bodies import validator_for
from grader.web.api.spec import PROBLEM_DOCUMENT

EXAMPLES = {"sqlite": 400, "postgresql": 300}  # about 12 s each on the project's machine
BUDGET_S = 0.5  # the checker's budget in this app; a request may take it plus a sandbox restart
SLOWEST_S = BUDGET_S + 8.0
SPHERE = (Path(__file__).resolve().parents[2] / "problems" / "sphere.toml").read_text()

OPERATIONS = list(spec.operations)
COMPONENTS = {**spec.schemas, "Problem": PROBLEM_DOCUMENT}
# Operations with a body are drawn more often: they have more to go wrong.
WEIGHTED_OPERATIONS = OPERATIONS + [op for op in OPERATIONS if op.request] * 4

# -- hostile pieces ----------------------------------------------------------------------------------
HOSTILE_TEXT = [
    "", " ", "\x00", "\ud800", "\udfff", "a\ud83d", "\u202e", "\ufeff", "🙂", "θ̇", "x" * 5000,
    "(" * 300, "sin(" * 120 + "x" + ")" * 120, "9^9^9^9^9", "m^(10^10)", "exp(exp(exp(exp(m))))",
    "1e308*1e308", "m/0", "x + 1", "x", "atan2(x)", "atan2(x, 1)", "x = 1", "=", "==", "m*g*(3*cos(theta) - 2)",
    "mg(3cos θ - 2)", "__import__('os').system('true')", "m.__class__", "lambda_c1", "\\frac{m}{g}",
    "0." + "0" * 500 + "1", "1" * 400, "m" * 64, "<script>alert(1)</script>", "%s%n", "NaN", "Infinity",
]
HOSTILE_NUMBERS = [0, -1, 1e308, -1e308, 5e-324, 2**63, -(2**63), 10**39, 0.01, 60, 61, 1e-9]

expression_text = st.text(alphabet="mgxlθ()*+-/^=., 0123456789sincoexptaheRl_", max_size=40)
hostile_text = st.one_of(st.sampled_from(HOSTILE_TEXT), st.text(max_size=30),
                         st.text(st.characters(min_codepoint=0xD800, max_codepoint=0xDFFF), min_size=1, max_size=3),
                         expression_text)
# Mostly text a view can use, so that many requests get past validation to the views and the checker.
usable_text = st.one_of(expression_text, expression_text, expression_text, st.sampled_from(HOSTILE_TEXT), hostile_text)
hostile_scalar = st.one_of(st.none(), st.booleans(), st.integers(min_value=-(10**50), max_value=10**50),
                           st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(HOSTILE_NUMBERS),
                           hostile_text)
any_json = st.recursive(hostile_scalar, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(hostile_text, inner, max_size=4)), max_leaves=12)


def _deep(depth: int) -> str:
    return "[" * depth + "]" * depth


VARIABLES = st.one_of(
    st.just({"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"},
             "theta": {"dimension": "angle"}, "x": {"dimension": "dimensionless"}}),
    st.dictionaries(st.sampled_from(["m", "g", "x", "theta", "t", "lambda_c", "1x", "a b", "\ud800"]),
                    st.fixed_dictionaries({}, optional={
                        "dimension": st.sampled_from(["mass", "kg^999999", "", "length/time", "bogus", "\x00"]),
                        "domain": st.one_of(st.sampled_from(["positive", "real", "nonnegative", "Positive", "none"]),
                                            st.lists(st.one_of(st.floats(), st.sampled_from(["pi", "e", "1/0"])),
                                                     max_size=3)),
                        "kind": st.sampled_from(["parameter", "coordinate", "velocity", "nonsense"])}),
                    max_size=5),
    any_json,
)


# Members whose useful values are few: drawn from those most of the time.
FIELDS = {
    "variables": VARIABLES,
    "answer": st.one_of(st.sampled_from(["tension", "acceleration"]), expression_text, usable_text),
    "user": st.one_of(st.sampled_from(["fuzz-student", "s1", "s2"]), usable_text),
    "kind": st.one_of(st.sampled_from(["expression", "equation"]), hostile_scalar),
    "budget_s": st.one_of(st.floats(min_value=0.01, max_value=60), st.sampled_from(HOSTILE_NUMBERS)),
}


def near(schema: dict) -> st.SearchStrategy:
    """Values near ``schema``: valid-looking most of the time, hostile some of the time."""
    if "$ref" in schema:
        schema = spec.schemas[schema["$ref"].rsplit("/", 1)[1]]
    kind = schema.get("type")
    if kind == "object" and "properties" in schema:
        members = {}
        for name, member in schema["properties"].items():
            members[name] = FIELDS[name] if name in FIELDS else near(member)
        required = {n: members[n] for n in schema.get("required", [])}
        optional = {n: s for n, s in members.items() if n not in required}
        body = st.fixed_dictionaries(required, optional=optional)
        extra = st.dictionaries(hostile_text, hostile_scalar, max_size=2)
        return st.one_of(body, body, body, body, body, st.builds(lambda b, e: {**e, **b}, body, extra), any_json)
    if "enum" in schema:
        return st.one_of(st.sampled_from(schema["enum"]), hostile_scalar)
    if kind == "string":
        return st.one_of(usable_text, usable_text, usable_text, hostile_scalar)
    if kind == "number":
        return st.one_of(st.floats(min_value=0.01, max_value=60), st.sampled_from(HOSTILE_NUMBERS), hostile_scalar)
    if kind == "array":
        return st.one_of(st.lists(near(schema.get("items", {})), max_size=4), any_json)
    return any_json


def raw_body(op) -> st.SearchStrategy:
    """The bytes of a request body for ``op``, with its content type."""
    json_schema = (op.request or {}).get("application/json")
    as_json = st.one_of(near(json_schema) if json_schema else any_json, any_json).map(
        lambda v: json.dumps(v, allow_nan=True).encode("utf-8", "surrogatepass"))
    literal = st.sampled_from([b'{"budget_s": NaN}', b'{"budget_s": 1' + b"0" * 300 + b"}", b"", b"{",
                               _deep(5000).encode(), b'{"a":' * 3000 + b"1" + b"}" * 3000, b"\xff\xfe\x00",
                               b'{"reference": "x", "answer": "x + 1", "variables": {"x": {}}}',
                               b'{"reference": "atan2(x)", "answer": "x", "variables": {"x": {}}}'])
    toml = st.one_of(st.just(SPHERE), st.builds(lambda cut, piece: SPHERE[:cut] + piece + SPHERE[cut + 5:],
                                                st.integers(0, len(SPHERE)), hostile_text)).map(
        lambda t: t.encode("utf-8", "surrogatepass"))
    declared = next(iter(op.request or {"application/json": None}))
    content = (st.one_of(toml, toml, toml, as_json, literal, st.binary(max_size=200)) if declared == "application/toml"
               else st.one_of(as_json, as_json, as_json, as_json, literal, toml, st.binary(max_size=200)))
    types = st.sampled_from([declared] * 8 + ["application/json", "application/toml", "text/plain", None,
                                              "application/json; charset=latin-1"])
    return st.tuples(content, types)


header_text = st.text(alphabet=string.ascii_letters + string.digits + string.punctuation + " ", max_size=250)
slug = st.one_of(st.just("yoyo"), st.text(alphabet=string.ascii_letters + string.digits + "-_%~ ", min_size=1,
                                          max_size=120))


def url_for_op(op, draw) -> str:
    path = re.sub(r"<int:\w+>", lambda _: str(draw(st.integers(-5, 10**20))), op.rule)
    path = re.sub(r"<\w+>", lambda _: quote(draw(slug), safe=""), path)
    return "/api/v1" + path


def documented(op) -> dict[str, dict | None]:
    """Status -> the documented content of the response (None: no content documented)."""
    document = op.to_openapi(op.documented_errors())
    out = {}
    for status, response in document["responses"].items():
        out[int(status)] = response.get("content") if "$ref" not in response else {
            "application/problem+json": {"schema": {"$ref": "#/components/schemas/Problem"}}}
    return out


@pytest.fixture
def fuzz_app(app, make_token, yoyo_version):
    app.config.update(RATE_LIMITS_ENABLED=False, CHECK_BUDGET_S=BUDGET_S, CHECK_QUEUE_TIMEOUT_S=5.0)
    tokens = {role: make_token(role, external_id=f"fuzz-{role}")[1] for role in ("student", "instructor", "admin", "lms")}
    client = app.test_client()
    # Start the sandbox children before the clock matters.
    client.post("/api/v1/check", json={"reference": "m", "answer": "m", "variables": {"m": {}}}, headers=tokens["student"])
    return client, tokens


@pytest.mark.slow
def test_any_request_to_any_operation_gets_a_documented_json_answer(fuzz_app, database_kind):
    client, tokens = fuzz_app

    # Hypothesis runs inside the test, so that one app and database serve every example.
    @settings(max_examples=EXAMPLES[database_kind], deadline=None, database=None,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
    @given(data=st.data())
    def one_request(data):
        op = data.draw(st.sampled_from(WEIGHTED_OPERATIONS), label="operation")
        body, content_type = data.draw(raw_body(op), label="body")
        headers = {}
        if op.roles is not None:
            who = data.draw(st.sampled_from(sorted(op.roles) * 4 + ["nobody", "bogus"]), label="token")
            headers.update(tokens.get(who, {"Authorization": "Bearer bogus"}) if who != "nobody" else {})
        if content_type:
            headers["Content-Type"] = content_type
        if data.draw(st.booleans(), label="idempotency key"):
            headers["Idempotency-Key"] = data.draw(header_text, label="key")
        url = url_for_op(op, data.draw)
        query = data.draw(st.dictionaries(st.sampled_from([p["name"] for p in op.parameters if p["in"] == "query"]
                                                          + ["x", "format", "version"]), header_text, max_size=2),
                          label="query")

        started = time.monotonic()
        response = client.open(url, method=op.method, data=body, headers=headers, query_string=query)
        elapsed = time.monotonic() - started
        event(f"{op.view.__name__} -> {response.status_code}")

        assert response.status_code < 500, response.get_data(as_text=True)[:500]
        statuses = documented(op)
        assert response.status_code in statuses, (response.status_code, sorted(statuses))
        assert elapsed < SLOWEST_S, f"{elapsed:.1f} s"
        if response.mimetype in ("application/json", "application/problem+json"):
            payload = json.loads(response.get_data(as_text=True))  # valid JSON, strictly
            content = statuses[response.status_code] or {}
            schema = (content.get(response.mimetype) or {}).get("schema")
            assert schema is not None, f"{response.mimetype} is not documented for {response.status_code}"
            errors = [e.message for e in validator_for(schema, COMPONENTS).iter_errors(payload)]
            assert errors == [], payload
        else:
            assert response.mimetype in {t for c in statuses.values() if c for t in c}, response.mimetype

    one_request()
