"""A route registry that is also the OpenAPI 3 document.

Each API view is declared once with :meth:`ApiSpec.route`, carrying who may call it, its request
and response schemas and (from its docstring) its summary and description. The decorator registers
the Flask rule, checks the bearer token's role before the view runs, and records the operation, so
``/api/v1/openapi.json`` is generated from the code and cannot drift from it.
"""

from __future__ import annotations

import inspect
import re
from dataclasses import dataclass, field
from functools import wraps
from typing import Any, Callable

from flask import Blueprint, g

from grader.store.models import Problem
from grader.web.api.bodies import LIMITS_TEXT, validated_body
from grader.web.converters import MAX_ID
from grader.web.errors import ApiProblem
from grader.web.security import api_user, limiter

__all__ = ["ApiSpec", "Operation"]

_CONVERTER = re.compile(r"<(?:(\w+):)?(\w+)>")
# Path parameters, as documented and enforced: ids by the app's `int` converter (converters.py),
# slugs below. Either out of range names nothing: 404, before any query.
MAX_SLUG_CHARS = Problem.__table__.c.slug.type.length
_TYPES = {"int": {"type": "integer", "format": "int32", "minimum": 0, "maximum": MAX_ID},
          "string": {"type": "string", "maxLength": MAX_SLUG_CHARS},
          None: {"type": "string", "maxLength": MAX_SLUG_CHARS}}
_PROBLEM = {"$ref": "#/components/schemas/Problem"}


@dataclass
class Operation:
    rule: str
    method: str
    view: Callable
    roles: frozenset[str] | None
    request: dict[str, dict] | None  # content type -> schema
    responses: dict[int, tuple[str, dict[str, dict] | None]]  # status -> (description, content)
    parameters: list[dict] = field(default_factory=list)
    headers: dict[int, dict[str, dict]] = field(default_factory=dict)
    errors: tuple[int, ...] = ()
    rate_limit: str | None = None  # the limiter's action charged for each call
    cost: Callable[[Any], float] | None = None  # tokens a valid body costs (default 1)

    def documented_errors(self) -> tuple[int, ...]:
        """The problem statuses this operation may answer: its own, and those of the registry's
        checks before the view (token, path, parameters, body, rate limit) and 500."""
        errors = set(self.errors) | {500}
        if self.roles is not None:
            errors |= {401, 403}
        if _CONVERTER.search(self.rule):
            errors.add(404)
        if any(p["in"] == "header" or p.get("schema", {}).get("type") == "string" for p in self.parameters):
            errors.add(422)
        if self.request and "application/json" in self.request:
            errors |= {400, 413, 415, 422}
        if self.rate_limit is not None:
            errors.add(429)
        return tuple(sorted(errors))

    @property
    def path(self) -> str:
        return _CONVERTER.sub(r"{\2}", self.rule)

    def to_openapi(self, errors: tuple[int, ...]) -> dict[str, Any]:
        doc = inspect.getdoc(self.view) or ""
        summary, _, description = doc.partition("\n\n")
        operation: dict[str, Any] = {"operationId": self.view.__name__, "summary": summary.strip()}
        if description.strip():
            operation["description"] = description.strip()
        if self.roles is not None:
            operation["description"] = (operation.get("description", "") +
                                        f"\n\nRoles: {', '.join(sorted(self.roles))}.").strip()
            operation["security"] = [{"bearer": []}]
        else:
            operation["security"] = []
        parameters = [{"name": name, "in": "path", "required": True, "schema": _TYPES.get(converter, _TYPES[None])}
                      for converter, name in _CONVERTER.findall(self.rule)]
        parameters += self.parameters
        if parameters:
            operation["parameters"] = parameters
        if self.request:
            operation["requestBody"] = {"required": True, "content": {
                content_type: {"schema": schema} for content_type, schema in self.request.items()}}
        responses: dict[str, Any] = {}
        for status, (description, content) in sorted(self.responses.items()):
            response: dict[str, Any] = {"description": description}
            if content:
                response["content"] = {t: {"schema": s} for t, s in content.items()}
            if status in self.headers:
                response["headers"] = self.headers[status]
            responses[str(status)] = response
        for status in errors:
            responses.setdefault(str(status), {"$ref": f"#/components/responses/{status}"})
        operation["responses"] = responses
        return operation


class ApiSpec:
    """The operations of one API blueprint and the OpenAPI document they make."""

    def __init__(self, blueprint: Blueprint, *, title: str, version: str, description: str = ""):
        self.blueprint, self.title, self.version, self.description = blueprint, title, version, description
        self.operations: list[Operation] = []
        self.schemas: dict[str, dict] = {}

    def schema(self, name: str, schema: dict) -> dict:
        """Name a component schema; returns a ``$ref`` to it."""
        self.schemas[name] = schema
        return {"$ref": f"#/components/schemas/{name}"}

    def route(self, rule: str, method: str, *, roles: set[str] | None,
              request: dict[str, dict] | None = None, responses: dict[int, tuple[str, dict | None]],
              parameters: list[dict] | None = None, headers: dict[int, dict[str, dict]] | None = None,
              errors: tuple[int, ...] = (), rate_limit: str | None = None,
              cost: Callable[[Any], float] | None = None):
        """Declare an API operation. ``roles=None`` means no token is needed; ``errors`` lists the
        problem statuses it may answer besides 401/403 (implied by roles) and 500.

        Before the view runs: the token's role is checked; an ``application/json`` request body is
        parsed strictly and validated against its published schema (:mod:`.bodies`), and is then
        ``g.api_body``; declared header parameters are validated too; ``rate_limit`` names the
        limiter action charged, ``cost(body)`` tokens for a valid body, one for an invalid one.
        """
        allowed = frozenset(roles) if roles is not None else None

        def decorator(view: Callable) -> Callable:
            operation = Operation(rule, method, view, allowed, request, responses, parameters or [],
                                  headers or {}, errors, rate_limit, cost)

            @wraps(view)
            def guarded(**kwargs):
                if allowed is not None:
                    api_user(allowed)
                _check_path(operation, kwargs)
                self._validate(operation)
                return view(**kwargs)

            self.blueprint.add_url_rule(rule, endpoint=view.__name__, view_func=guarded, methods=[method])
            self.operations.append(operation)
            return view

        return decorator

    def _validate(self, op: Operation) -> None:
        """The registry's one validation step: headers, then the JSON body, then the rate limit."""
        from flask import request

        charge = 1.0
        try:
            for parameter in op.parameters:
                # Headers, and query parameters documented as strings (enum, length, pattern); other
                # query types are read leniently by their views (published=0/no/false).
                if parameter["in"] == "header":
                    value = request.headers.get(parameter["name"])
                elif parameter["in"] == "query" and parameter.get("schema", {}).get("type") == "string":
                    value = request.args.get(parameter["name"])
                else:
                    value = None
                if value is not None:
                    _check_parameter(parameter, value)
            g.api_body = None
            # An operation that also takes another body type (a CSV roster) validates JSON bodies only;
            # a body of a type it does not declare is refused here, so its view never sees one.
            if op.request and "application/json" in op.request:
                if len(op.request) > 1 and request.mimetype not in op.request:
                    raise ApiProblem(415, f"Send the body as one of: {', '.join(op.request)}.",
                                     kind="unsupported-media-type")
                if len(op.request) == 1 or request.mimetype == "application/json":
                    g.api_body = validated_body(op.request["application/json"], self.schemas)
                    charge = float(op.cost(g.api_body)) if op.cost else 1.0
        finally:  # an invalid request is charged too: a flood of them is limited like any other
            if op.rate_limit is not None and getattr(g, "api_user", None) is not None:
                limiter.hit(op.rate_limit, g.api_user.id, cost=charge)

    def openapi(self, server_url: str) -> dict[str, Any]:
        paths: dict[str, dict] = {}
        for op in self.operations:
            paths.setdefault(op.path, {})[op.method.lower()] = op.to_openapi(op.documented_errors())
        problem_content = {"application/problem+json": {"schema": _PROBLEM}}
        return {
            "openapi": "3.0.3",
            "info": {"title": self.title, "version": self.version,
                     "description": f"{self.description}\n\n{LIMITS_TEXT}".strip()},
            "servers": [{"url": server_url}],
            "paths": paths,
            "components": {
                "securitySchemes": {"bearer": {"type": "http", "scheme": "bearer",
                                               "description": "A token from `grader token create`."}},
                "schemas": {"Problem": PROBLEM_DOCUMENT, **self.schemas},
                "responses": {
                    str(status): {"description": description, "content": problem_content}
                    for status, description in _ERROR_RESPONSES.items()
                },
            },
        }


def _check_path(op: Operation, values: dict[str, Any]) -> None:
    """A slug longer than any stored one names no resource: 404, before any query."""
    for name, value in values.items():
        if isinstance(value, str) and len(value) > MAX_SLUG_CHARS:
            raise ApiProblem(404, f"There is no such resource ({name} is longer than {MAX_SLUG_CHARS} characters).",
                             kind="not-found")


def _check_parameter(parameter: dict, value: str) -> None:
    """A header or query parameter against its (string) schema: its length, pattern and enum."""
    from grader.web.api.bodies import problems_of

    where = "header" if parameter["in"] == "header" else "query parameter"
    problems = problems_of(value, parameter.get("schema", {}))
    if any(ord(c) < 0x20 or 0xD800 <= ord(c) <= 0xDFFF for c in value):  # NUL: PostgreSQL cannot store it
        problems = [{"detail": "body holds a control character"}]
    if problems:
        detail = problems[0]["detail"].replace("body", f"The {parameter['name']} {where}", 1)
        raise ApiProblem(422, detail, kind="invalid-request",
                         errors=[{"parameter": parameter["name"], "detail": detail}])


PROBLEM_DOCUMENT = {
    "type": "object",
    "description": "An error (RFC 9457 problem details).",
    "required": ["type", "title", "status"],
    "properties": {
        "type": {"type": "string", "description": "urn:lagrade:error:<kind>, or about:blank"},
        "title": {"type": "string"},
        "status": {"type": "integer"},
        "detail": {"type": "string"},
        "instance": {"type": "string"},
    },
}

_ERROR_RESPONSES = {
    400: "The request is malformed (not JSON, wrong types).",
    401: "No bearer token, or an unknown one.",
    403: "The token's role, or the access policy for this resource, does not allow this.",
    404: "No such resource (or not one this token may see).",
    409: "The request conflicts with the resource's state.",
    413: "The body is too large.",
    415: "The body has the wrong content type.",
    422: "The request is well-formed but cannot be accepted (e.g. an invalid scene or unknown answer).",
    429: "Too many requests; see Retry-After.",
    500: "The server failed; the error was logged (no details are given).",
    503: "Every checker is busy; see Retry-After.",
}
