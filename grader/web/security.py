"""CSRF tokens for forms, bearer tokens for the API, and per-user rate limits.

- CSRF: ``{{ csrf_token() }}`` in a form (a hidden ``csrf_token`` field) or the ``X-CSRF-Token``
  header; every unsafe request outside the API must carry the session's token. The API is exempt:
  it authenticates with bearer tokens, which a browser never sends on its own.
- API tokens: ``Authorization: Bearer <secret>``; :func:`api_user` resolves it to a user and checks
  the role.
- Rate limits: a token bucket per user and action, in memory (one server process), answered with
  429 and ``Retry-After``.
"""

from __future__ import annotations

import hmac
import math
import secrets
import threading
import time
from dataclasses import dataclass

from flask import Flask, current_app, g, request, session

from grader.store.db import db
from grader.store.models import User
from grader.store.users import user_for_token
from grader.web.errors import ApiProblem

__all__ = ["RateLimiter", "api_user", "csrf_token", "init_app", "limiter"]

CSRF_FIELD = "csrf_token"
CSRF_HEADER = "X-CSRF-Token"
_UNSAFE = frozenset({"POST", "PUT", "PATCH", "DELETE"})
# Admins may do whatever instructors may.
_IMPLIED_ROLES = {"admin": {"admin", "instructor"}}


def csrf_token() -> str:
    """The CSRF token of this browser session (created on first use); a Jinja global."""
    token = session.get("_csrf")
    if token is None:
        token = session["_csrf"] = secrets.token_urlsafe(32)
    return token


def _check_csrf() -> None:
    if (request.method not in _UNSAFE or not current_app.config["CSRF_ENABLED"]
            or request.routing_exception is not None  # a 404/405 says more than a CSRF refusal
            or request.blueprint == "api" or request.path.startswith("/api/")):
        return
    expected = session.get("_csrf")
    sent = request.form.get(CSRF_FIELD) or request.headers.get(CSRF_HEADER)
    if not expected or not sent or not hmac.compare_digest(expected, sent):
        from flask import abort

        abort(400, "The form was missing its security token or it had expired; reload the page and try again.")


def api_user(roles: frozenset[str] | set[str]) -> User:
    """The user behind the request's bearer token, if its role is one of ``roles``; else 401/403."""
    header = request.headers.get("Authorization", "")
    scheme, _, secret = header.partition(" ")
    challenge = {"WWW-Authenticate": 'Bearer realm="lagrade"'}
    if scheme.lower() != "bearer" or not secret.strip():
        raise ApiProblem(401, "This endpoint needs an 'Authorization: Bearer <token>' header.",
                         kind="unauthenticated", headers=challenge)
    # A short session of its own: the request's session must not hold a transaction (on SQLite, a
    # write lock) while a slow view derives a scene or runs a check.
    with db.read() as session:
        found = user_for_token(session, secret.strip())
    if found is None:
        raise ApiProblem(401, "The bearer token is unknown or revoked.", kind="unauthenticated",
                         headers={"WWW-Authenticate": 'Bearer realm="lagrade", error="invalid_token"'})
    user, token = found
    if not (_IMPLIED_ROLES.get(token.role, {token.role}) & set(roles)):
        raise ApiProblem(403, f"A {token.role} token cannot do this; it needs one of: {', '.join(sorted(roles))}.",
                         kind="forbidden")
    g.api_user, g.api_role = user, token.role  # detached: read its columns, or db.session.get() it
    return user


MAX_BUCKETS = 10_000  # beyond this many, refilled buckets are forgotten


@dataclass
class _Bucket:
    tokens: float
    updated: float


class RateLimiter:
    """Token buckets per (action, user): ``rate`` requests per second on average, ``burst`` at once.

    Limits come from ``app.config["RATE_LIMITS"]`` = {action: (per_minute, burst)} and are off when
    ``RATE_LIMITS_ENABLED`` is false.
    """

    def __init__(self):
        self._lock = threading.Lock()
        self._pruned_at = float("-inf")

    def init_app(self, app: Flask) -> None:
        app.extensions["lagrade.rate_buckets"] = {}

    def hit(self, action: str, key: object, cost: float = 1.0) -> None:
        """Take ``cost`` tokens from ``key``'s bucket for ``action``, or raise a 429 problem.

        An expensive request (a check with many feedback items) costs more than one token; the
        cost is capped at the burst, so that any single request can pass once the bucket is full.
        """
        self._draw(action, key, cost, take=True)

    def check(self, action: str, key: object) -> None:
        """Raise the 429 problem if ``key``'s bucket for ``action`` is empty, without taking a token.

        For limits that count only failures (sign-in): look before the attempt, :meth:`hit` after it fails.
        """
        self._draw(action, key, 1.0, take=False)

    def _draw(self, action: str, key: object, cost: float, take: bool) -> None:
        config = current_app.config
        if not config["RATE_LIMITS_ENABLED"] or action not in config["RATE_LIMITS"]:
            return
        per_minute, burst = config["RATE_LIMITS"][action]
        rate = per_minute / 60.0
        cost = min(max(float(cost), 1.0), float(burst))
        now = time.monotonic()
        buckets: dict[tuple[str, object], _Bucket] = current_app.extensions["lagrade.rate_buckets"]
        with self._lock:
            if len(buckets) > MAX_BUCKETS and now - self._pruned_at > 1.0:  # a scan a second at most
                self._pruned_at = now
                self._forget_full(buckets, now)
            bucket = buckets.setdefault((action, key), _Bucket(float(burst), now))
            bucket.tokens = min(float(burst), bucket.tokens + (now - bucket.updated) * rate)
            bucket.updated = now
            if bucket.tokens >= cost:
                if take:
                    bucket.tokens -= cost
                return
            wait = math.ceil((cost - bucket.tokens) / rate)
        raise ApiProblem(429, f"Too many {action} requests: at most {per_minute} a minute (bursts of {burst}). "
                              f"Try again in {wait} s.", kind="rate-limited", headers={"Retry-After": str(wait)})

    @staticmethod
    def _forget_full(buckets: dict, now: float) -> None:
        # Keys can come from request text (a sign-in name): drop buckets that have refilled, which a
        # new bucket would equal, so the table stays the size of the recent traffic.
        limits = current_app.config["RATE_LIMITS"]
        for (action, key), bucket in list(buckets.items()):
            per_minute, burst = limits.get(action, (1, 0))
            if bucket.tokens + (now - bucket.updated) * per_minute / 60.0 >= burst:
                del buckets[(action, key)]


# The extension: buckets in memory, per app (one server process).
limiter = RateLimiter()


def init_app(app: Flask) -> None:
    limiter.init_app(app)
    app.before_request(_check_csrf)
    app.jinja_env.globals["csrf_token"] = csrf_token

