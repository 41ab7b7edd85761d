"""A stand-in LTI 1.3 platform (an LMS) for the tests, served on 127.0.0.1 in a thread.

It has its own RSA key and JWKS, an OIDC authorisation endpoint that answers with the auto-post form
a real LMS sends (an id_token it signs for the scenario the test set in ``next_launch``), an OAuth 2
token endpoint that checks the tool's client assertion against the tool's JWKS, AGS line items and
scores (recorded; ``fail_scores`` answers the next n score posts with a 500), NRPS memberships over
two pages, and a deep-linking return endpoint that verifies and records the tool's answer.
"""

from __future__ import annotations

import functools
import html
import re
import secrets
import threading
import time
from dataclasses import dataclass, field
from typing import Any

import pytest
import requests
from flask import Flask, abort, jsonify, request
from joserfc import jwk, jwt
from werkzeug.serving import make_server

CLAIM = "https://purl.imsglobal.org/spec/lti/claim/"
CLIENT_ID = "lagrade-tool"
DEPLOYMENT = "deployment-1"
LEARNER = "http://purl.imsglobal.org/vocab/lis/v2/membership#Learner"
INSTRUCTOR = "http://purl.imsglobal.org/vocab/lis/v2/membership#Instructor"
SCORE_SCOPE = "https://purl.imsglobal.org/spec/lti-ags/scope/score"
LINEITEM_SCOPE = "https://purl.imsglobal.org/spec/lti-ags/scope/lineitem"
NRPS_SCOPE = "https://purl.imsglobal.org/spec/lti-nrps/scope/contextmembership.readonly"


def rsa_key(kid: str) -> jwk.RSAKey:
    return jwk.RSAKey.generate_key(2048, private=True, parameters={"kid": kid, "alg": "RS256", "use": "sig"})


@functools.lru_cache(maxsize=None)
def shared_key(kid: str) -> jwk.RSAKey:
    """One key per kid for the whole run: making RSA keys is the slow part of each test's set-up."""
    return rsa_key(kid)


@dataclass
class Platform:
    base: str = ""
    key: jwk.RSAKey = field(default_factory=lambda: shared_key("platform-key-1"))
    tool_jwks: dict | None = None  # set by the test: what the tool publishes at /lti/jwks
    next_launch: dict[str, Any] = field(default_factory=dict)  # claims to add or override in the next id_token
    sign_with: jwk.RSAKey | None = None  # sign the next id_token with another key (a forgery)
    scores: list[dict] = field(default_factory=list)
    score_urls: list[str] = field(default_factory=list)
    fail_scores: int = 0
    lineitems: list[dict] = field(default_factory=list)
    tokens: dict[str, set[str]] = field(default_factory=dict)
    deep_link_answers: list[dict] = field(default_factory=list)
    members: list[dict] = field(default_factory=list)
    auth_requests: list[dict] = field(default_factory=list)
    jwks_fetches: int = 0

    @property
    def issuer(self) -> str:
        return self.base

    def url(self, path: str) -> str:
        return self.base + path

    def id_token(self, issued_nonce: str, overrides: dict[str, Any]) -> str:
        now = int(time.time())
        claims = {
            "iss": self.issuer, "aud": CLIENT_ID, "sub": "student-1", "iat": now, "exp": now + 300, "nonce": issued_nonce,
            "name": "Ada Lovelace",
            CLAIM + "message_type": "LtiResourceLinkRequest", CLAIM + "version": "1.3.0",
            CLAIM + "deployment_id": DEPLOYMENT, CLAIM + "roles": [LEARNER],
            CLAIM + "context": {"id": "course-7", "title": "Analytical Mechanics"},
            CLAIM + "resource_link": {"id": "link-1", "title": "Yo-yo"},
            CLAIM + "custom": {"problem": "yoyo"},
            "https://purl.imsglobal.org/spec/lti-ags/claim/endpoint": {
                "scope": [SCORE_SCOPE, LINEITEM_SCOPE], "lineitems": self.url("/lineitems"),
                "lineitem": self.url("/lineitems/1")},
            "https://purl.imsglobal.org/spec/lti-nrps/claim/namesroleservice": {
                "context_memberships_url": self.url("/memberships"), "service_versions": ["2.0"]},
        }
        claims.update(overrides)
        claims = {k: v for k, v in claims.items() if v is not None}
        key = self.sign_with or self.key
        return jwt.encode({"alg": "RS256", "kid": self.key.kid}, claims, key)

    def check_token(self, scope: str) -> None:
        header = request.headers.get("Authorization", "")
        token = header.removeprefix("Bearer ")
        if scope not in self.tokens.get(token, set()):
            abort(401)


def make_app(platform: Platform) -> Flask:
    app = Flask("stand-in-platform")

    @app.get("/jwks")
    def jwks():
        platform.jwks_fetches += 1
        return jsonify({"keys": [platform.key.as_dict(private=False)]})

    @app.get("/auth")
    def auth():
        params = request.args.to_dict()
        platform.auth_requests.append(params)
        for name, value in (("scope", "openid"), ("response_type", "id_token"), ("response_mode", "form_post"),
                            ("prompt", "none"), ("client_id", CLIENT_ID)):
            if params.get(name) != value:
                abort(400, f"{name} must be {value}")
        overrides, platform.next_launch = platform.next_launch, {}
        token = platform.id_token(params["nonce"], overrides)
        platform.sign_with = None
        return (f'<form method="post" action="{html.escape(params["redirect_uri"])}">'
                f'<input type="hidden" name="id_token" value="{token}">'
                f'<input type="hidden" name="state" value="{html.escape(params["state"])}"></form>')

    @app.post("/token")
    def token():
        form = request.form
        if form.get("grant_type") != "client_credentials" or form.get("client_assertion_type") != \
                "urn:ietf:params:oauth:client-assertion-type:jwt-bearer":
            return jsonify({"error": "unsupported_grant_type"}), 400
        try:
            claims = jwt.decode(form["client_assertion"], jwk.KeySet.import_key_set(platform.tool_jwks)).claims
        except Exception:
            return jsonify({"error": "invalid_client"}), 401
        if claims.get("iss") != CLIENT_ID or claims.get("sub") != CLIENT_ID or claims.get("aud") != platform.url("/token") \
                or claims.get("exp", 0) < time.time():
            return jsonify({"error": "invalid_client"}), 401
        access = secrets.token_urlsafe(16)
        platform.tokens[access] = set(form.get("scope", "").split())
        return jsonify({"access_token": access, "token_type": "Bearer", "expires_in": 3600})

    @app.route("/lineitems", methods=["GET", "POST"])
    def lineitems():
        platform.check_token(LINEITEM_SCOPE)
        if request.method == "GET":
            wanted = request.args.get("resource_link_id")
            return jsonify([i for i in platform.lineitems if wanted in (None, i.get("resourceLinkId"))])
        item = dict(request.get_json(force=True), id=platform.url(f"/lineitems/{len(platform.lineitems) + 100}"))
        platform.lineitems.append(item)
        return jsonify(item), 201

    @app.post("/lineitems/<int:number>/scores")
    def scores(number: int):
        platform.check_token(SCORE_SCOPE)
        if request.mimetype != "application/vnd.ims.lis.v1.score+json":
            abort(415)
        if platform.fail_scores:
            platform.fail_scores -= 1
            return "platform trouble", 500
        platform.scores.append(request.get_json(force=True))
        platform.score_urls.append(request.path)
        return "", 204

    @app.get("/memberships")
    def memberships():
        platform.check_token(NRPS_SCOPE)
        page = int(request.args.get("page", "1"))
        half = len(platform.members) // 2
        members = platform.members[:half] if page == 1 else platform.members[half:]
        response = jsonify({"id": platform.url("/memberships"), "context": {"id": "course-7"}, "members": members})
        if page == 1:
            response.headers["Link"] = f'<{platform.url("/memberships?page=2")}>; rel="next"'
        return response

    @app.post("/deep_link_return")
    def deep_link_return():
        claims = jwt.decode(request.form["JWT"], jwk.KeySet.import_key_set(platform.tool_jwks)).claims
        platform.deep_link_answers.append(claims)
        return "received"

    return app


class Served:
    """The platform's app on a free port of 127.0.0.1, in a thread, until :meth:`stop`."""

    def __init__(self):
        self.platform = Platform()
        self.server = make_server("127.0.0.1", 0, make_app(self.platform), threaded=True)
        self.platform.base = f"http://127.0.0.1:{self.server.server_port}"
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()

    def stop(self) -> None:
        self.server.shutdown()
        self.server.server_close()


def auto_post_form(page: str) -> dict[str, str]:
    """The hidden fields of the platform's auto-post form (what a browser would post on)."""
    return {name: html.unescape(value) for name, value in re.findall(r'name="([^"]+)" value="([^"]*)"', page)}


# --- fixtures and helpers shared by the tests/web/test_lti_*.py modules (import them there) ---------------

TOOL_LAUNCH = "http://localhost/lti/launch"  # the Flask test client's host


@pytest.fixture
def lms():
    """The stand-in platform, served for one test; the tool's key and token caches start empty."""
    from grader.web.lti.platforms import forget_keys
    from grader.web.lti.tokens import forget_tokens

    forget_keys()
    forget_tokens()
    served = Served()
    yield served.platform
    served.stop()
    forget_keys()
    forget_tokens()


@pytest.fixture
def tool(app, lms, yoyo_version):
    """The app with the stand-in platform registered (the yo-yo problem published, in no course)."""
    from grader.store.lti_models import LtiToolKey
    from grader.web.lti.platforms import register_platform

    tool_key = shared_key("tool-key-1")
    with app.extensions["lagrade.db"].write() as session:
        session.add(LtiToolKey(kid=tool_key.kid, private_pem=tool_key.as_pem(private=True).decode()))
        register_platform(session, name="Stand-in LMS", issuer=lms.issuer, client_id=CLIENT_ID,
                          auth_url=lms.url("/auth"), token_url=lms.url("/token"), jwks_url=lms.url("/jwks"),
                          deployment_ids=[DEPLOYMENT])
    lms.tool_jwks = app.test_client().get("/lti/jwks").get_json()
    return app


def login(client, lms, **params):
    """The LMS's login initiation, as the browser follows it; the tool's answer."""
    query = {"iss": lms.issuer, "login_hint": "hint-1", "target_link_uri": TOOL_LAUNCH, "client_id": CLIENT_ID,
             "lti_deployment_id": DEPLOYMENT, **params}
    return client.get("/lti/login", query_string={k: v for k, v in query.items() if v is not None})


def launch(client, lms, claims: dict | None = None):
    """A whole launch: login initiation, the platform's authorisation, the form it posts back.

    Returns ``(the tool's answer to the launch, the posted form)``.
    """
    lms.next_launch = dict(claims or {})
    started = login(client, lms)
    assert started.status_code == 302, started.get_data(as_text=True)
    page = requests.get(started.headers["Location"], timeout=10)
    assert page.status_code == 200, page.text
    form = auto_post_form(page.text)
    return client.post("/lti/launch", data=form), form
