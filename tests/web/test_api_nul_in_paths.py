"""A NUL character in a URL's path segment names nothing: 404 on every route that takes a text id,
pages and API alike, on SQLite and PostgreSQL (whose text cannot hold NUL: each was a 500 there)."""

from __future__ import annotations

import re
import tempfile

import pytest

from grader.web import create_app


def _routes() -> list[tuple[str, str]]:
    """Every (method, rule) of the app with a text (not ``int``) path parameter, its ids filled in with
    the ones the fixtures make and the first text parameter holding a NUL."""
    with tempfile.TemporaryDirectory() as folder:
        return _rules_of(create_app({"TESTING": True, "DATABASE_URL": f"sqlite:///{folder}/routes.sqlite",
                                     "SECRET_KEY": "x", "INSTANCE_PATH": folder}))


def _rules_of(app) -> list[tuple[str, str]]:
    found = []
    for rule in app.url_map.iter_rules():
        texts = [name for name, converter in rule._converters.items() if type(converter).__name__ == "UnicodeConverter"]
        if not texts or rule.endpoint == "static":
            continue
        for method in sorted(rule.methods - {"HEAD", "OPTIONS"}):
            found.append((method, rule.rule))
    app.extensions["lagrade.checkers"].close()
    app.extensions["lagrade.db"].dispose()
    return sorted(found)


ROUTES = _routes()


def _url(rule: str) -> str:
    first = [True]

    def fill(match: re.Match) -> str:
        name = match.group(1).split(":")[-1]
        if first[0] and not match.group(1).startswith("int:"):
            first[0] = False
            return "a%00b"
        return {"number": "1", "code": "MECH", "assignment": "hw1", "slug": "yoyo"}.get(name, "1")

    return re.sub(r"<([^>]+)>", fill, rule)


def test_a_nul_in_a_path_names_nothing_on_every_route(app, client, make_token, yoyo_version, database_kind):
    _, headers = make_token("admin")  # the one who may call everything: only the NUL refuses
    with client.session_transaction() as session:
        session["_csrf"] = "t"
    assert len(ROUTES) > 30  # every problem, course, assignment and LTI route with a text id
    answered = {}
    for method, rule in ROUTES:
        url = _url(rule)
        response = client.open(url, method=method, headers={**headers, "X-CSRF-Token": "t"})
        problem_json = not url.startswith("/api/") or response.mimetype == "application/problem+json"
        answered[f"{method} {url}"] = (response.status_code, problem_json)
    assert {k: v for k, v in answered.items() if v != (404, True)} == {}
