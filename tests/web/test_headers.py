"""Security headers on every response, no inline script or style anywhere, HTTPS mode, framing opt-in."""

import re
from html.parser import HTMLParser
from pathlib import Path

import pytest
from flask import url_for

from grader.web import create_app
from grader.web.headers import allow_framing, content_security_policy, framable
from tests.web.conftest_pages import (  # noqa: F401  (fixtures)
    PASSWORD, accounts, as_instructor, as_student, csrf, form_token, problems, sign_in, submit_answers,
)

TEMPLATES = Path(__file__).resolve().parents[2] / "grader" / "web" / "templates"
# A value for every URL argument of every route; a new argument fails the test until it is added here.
SAMPLE_ARGUMENTS = {"slug": "mech", "submission_id": 1, "job_id": 1, "number": 1, "filename": "css/lagrade.css",
                    "code": "MECH", "assignment": "hw1", "context_id": 1}


def _assert_security_headers(response, where: str) -> None:
    headers = response.headers
    csp = headers.get("Content-Security-Policy", "")
    directives = dict(d.strip().split(" ", 1) for d in csp.split(";"))
    assert directives.get("script-src") == "'self'" and directives.get("style-src") == "'self'", where
    assert "unsafe-inline" not in csp and "unsafe-eval" not in csp, where
    assert directives.get("frame-ancestors") == "'none'" and headers.get("X-Frame-Options") == "DENY", where
    assert directives.get("object-src") == "'none'" and directives.get("base-uri") == "'none'", where
    assert headers.get("X-Content-Type-Options") == "nosniff", where
    assert headers.get("Referrer-Policy") == "same-origin", where
    assert "Strict-Transport-Security" not in headers, where  # only when served over HTTPS


def _all_routes(app):
    """(method, path) of every route of the app, with sample arguments filled in."""
    with app.test_request_context():
        for rule in app.url_map.iter_rules():
            missing = rule.arguments - SAMPLE_ARGUMENTS.keys()
            assert not missing, f"add a sample value for {missing} ({rule.rule})"
            path = url_for(rule.endpoint, **{name: SAMPLE_ARGUMENTS[name] for name in rule.arguments})
            for method in sorted(rule.methods - {"HEAD", "OPTIONS"}):
                yield method, path


class _Inline(HTMLParser):
    """What a strict Content-Security-Policy would block in a page: inline script, style, handlers."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.found: list[str] = []

    def handle_starttag(self, tag, attrs):
        attributes = dict(attrs)
        if tag == "script" and not attributes.get("src"):
            self.found.append("inline <script>")
        if tag == "style":
            self.found.append("<style>")
        self.found += [f"{tag}[{name}]" for name in attributes if name == "style" or name.startswith("on")]
        self.found += [f"{tag}[{name}={value}]" for name, value in attributes.items()
                       if name in ("href", "src", "action") and re.match(r"\s*javascript:", value or "", re.I)]


def _inline_code(html: str) -> list[str]:
    parser = _Inline()
    parser.feed(html)
    parser.close()
    return parser.found


def test_every_route_answers_with_the_security_headers(app, client, as_student, as_instructor, problems):
    submit_answers(as_student, "mech", tension="m*g/3", acceleration="2*g/3")  # submission 1 exists
    pages = 0
    for who, browser in (("anonymous", client), ("student", as_student), ("instructor", as_instructor)):
        for method, path in _all_routes(app):
            response = browser.open(path, method=method)
            _assert_security_headers(response, f"{who} {method} {path} -> {response.status_code}")
            if response.mimetype == "text/html":
                assert _inline_code(response.get_data(as_text=True)) == [], f"{who} {method} {path}"
                pages += response.status_code == 200
    assert pages >= 6  # the loop really rendered the pages (8 today), not only refusals


@pytest.mark.parametrize("path", ["/no/such/page", "/api/v1/no/such", "/static/none.css"])
def test_error_answers_carry_the_headers_too(client, path):
    response = client.get(path)
    assert response.status_code == 404
    _assert_security_headers(response, path)


def test_a_failed_sign_in_carries_the_headers(client, accounts):
    token = form_token(client.get("/login").get_data(as_text=True))
    response = client.post("/login", data={"username": "ada@example.org", "password": "no", "csrf_token": token})
    assert response.status_code == 401
    _assert_security_headers(response, "POST /login")


@pytest.mark.parametrize("template", sorted(p.relative_to(TEMPLATES).as_posix() for p in TEMPLATES.rglob("*.html")))
def test_templates_hold_no_inline_script_style_or_handler(template):
    source = (TEMPLATES / template).read_text()
    assert not re.search(r"<script(?![^>]*\bsrc=)[^>]*>", source), "inline <script>"
    assert not re.search(r"<style\b|\sstyle=|\son[a-z]+=", source, re.I), "inline style or event handler"


def test_the_inline_check_sees_what_it_must():
    assert _inline_code('<script>x</script><p style="a" onclick="b"><a href=" javascript:x">') == [
        "inline <script>", "p[style]", "p[onclick]", "a[href= javascript:x]"]


def _app_with(database_url, tmp_path, monkeypatch, **config):
    monkeypatch.chdir(tmp_path)
    return create_app({"TESTING": True, "DATABASE_URL": database_url, "SECRET_KEY": "test-secret", **config})


def _close(app):
    app.extensions["lagrade.checkers"].close()
    app.extensions["lagrade.db"].dispose()


@pytest.mark.parametrize("https", [False, True])
def test_https_mode_adds_hsts_and_secure_cookies(database_url, tmp_path, monkeypatch, https):
    if https:
        monkeypatch.setenv("LAGRADE_HTTPS", "true")  # as docker-compose.yml sets it
    app = _app_with(database_url, tmp_path, monkeypatch)
    try:
        assert app.config["HTTPS"] is https and app.config["SESSION_COOKIE_SECURE"] is https
        client = app.test_client()
        response = client.get("/login", base_url="https://localhost" if https else "http://localhost")
        assert ("max-age=" in response.headers.get("Strict-Transport-Security", "")) is https
        cookie = response.headers["Set-Cookie"]  # the session, holding the form's CSRF token
        assert ("; Secure" in cookie) is https and "HttpOnly" in cookie and "SameSite=Lax" in cookie
    finally:
        _close(app)


def test_docker_compose_turns_https_on():
    compose = (TEMPLATES.parents[2] / "docker-compose.yml").read_text()
    assert re.search(r'^\s+LAGRADE_HTTPS:\s*"true"', compose, re.M)


def test_a_view_may_opt_in_to_being_framed_by_named_origins(app, client):
    app.add_url_rule("/embedded", "embedded", framable("https://lms.example.org", "'self'")(lambda: "in a frame"))
    response = client.get("/embedded")
    assert "frame-ancestors https://lms.example.org 'self'" in response.headers["Content-Security-Policy"]
    assert "X-Frame-Options" not in response.headers
    assert client.get("/login").headers["X-Frame-Options"] == "DENY"  # the opt-in is per response


@pytest.mark.parametrize("origin", ["*", "http://lms.example.org", "https://lms.example.org; script-src *",
                                    "https://lms.example.org/path", "https://*.example.org", "'unsafe-inline'",
                                    "https://lms.example.org 'unsafe-eval'", ""])
def test_framing_accepts_only_plain_https_origins(app, origin):
    with app.test_request_context(), pytest.raises(ValueError):
        allow_framing(origin)


def test_the_policy_names_frame_ancestors_once():
    policy = content_security_policy(["https://a.example"])
    assert policy.count("frame-ancestors") == 1 and "frame-ancestors 'none'" not in policy
