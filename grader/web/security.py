"""CSRF tokens for forms, bearer tokens for the API, and per-user rate limits.

- CSRF: ``{{ csrf_token() }}`` in a form (a hidden ``csrf_token`` field) or the ``X-CSRF-Token``
  header; every unsafe request outside the API must carry the session's token. The API is exempt:
  it authenticates with bearer tokens, which a browser never sends on its own.
- API tokens: ``Authorization: Bearer <secret>``; :func:`api_user` resolves it to a user and checks
  the role.
- Rate limits: per user (or account and address) and action, kept by Flask-Limiter's storage (in
  memory, or Redis shared by every web process), answered with 429 and ``Retry-After``.
"""

from __future__ import annotations

import hashlib
import hmac
import math
import secrets
import time

from flask import Flask, current_app, g, request, session

from grader.store.db import db
from grader.store.models import User
from grader.store.users import user_for_token
from grader.web.errors import ApiProblem

__all__ = ["RateLimiter", "api_user", "csrf_exempt", "csrf_token", "init_app", "limiter"]

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


def csrf_exempt(view):
    """Mark a page another site form-posts to by design (an LMS's LTI login and launch): it proves
    itself otherwise (a signed id_token bound to a state cookie), never with this site's CSRF token."""
    view.csrf_exempt = True
    return view


def _check_csrf() -> None:
    if (request.method not in _UNSAFE or not current_app.config["CSRF_ENABLED"]
            or request.routing_exception is not None  # a 404/405 says more than a CSRF refusal
            or request.blueprint == "api" or request.path.startswith("/api/")
            or getattr(current_app.view_functions.get(request.endpoint), "csrf_exempt", False)):
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


class RateLimiter:
    """Rate limits per (action, key), kept by Flask-Limiter's storage: in memory (one process) by
    default, shared by every web process with ``LAGRADE_RATELIMIT_STORAGE_URI=redis://...``.

    Limits come from ``app.config["RATE_LIMITS"]`` = {action: (per_minute, burst)} and are off when
    ``RATE_LIMITS_ENABLED`` is false. Each is a moving window: at most ``burst`` in any span of
    ``60 * burst / per_minute`` seconds (the time a token bucket of that size takes to refill).
    """

    def init_app(self, app: Flask) -> None:
        from flask_limiter import Limiter

        app.config.setdefault("RATELIMIT_STORAGE_URI", "memory://")
        app.config.setdefault("RATELIMIT_STRATEGY", "moving-window")
        app.config.setdefault("RATELIMIT_KEY_PREFIX", "lagrade")
        # Only its storage and strategy are used: the limits are charged by the calls below, where
        # the action, the key and the cost of a request are known.
        app.extensions["lagrade.flask_limiter"] = Limiter(lambda: "", app=app, headers_enabled=False)

    @staticmethod
    def _window(per_minute: float, burst: float):
        from limits import RateLimitItemPerSecond

        # ``burst`` in any span of the time a bucket takes to refill: the same average rate.
        return RateLimitItemPerSecond(int(burst), max(1, math.ceil(60.0 * burst / per_minute)))

    def hit(self, action: str, key: object, cost: float = 1.0) -> None:
        """Charge ``cost`` to ``key``'s limit for ``action``, or raise a 429 problem.

        An expensive request (a check with many feedback items) costs more than one; the cost is
        capped at the burst, so that any single request can pass once the limit has recovered.
        """
        self._draw(action, key, cost, take=True)

    def refusal(self, action: str, key: object, earlier: str | None) -> str | None:
        """Why the next of several items of one request is refused by ``action``'s limit, or None
        (charging it): the first refusal's detail, which holds for the rest of the request too (the
        limit does not recover within it). For a submit of several answers, each one an attempt."""
        if earlier is not None:
            return earlier
        try:
            self.hit(action, key)
        except ApiProblem as error:
            return error.detail
        return None

    def check(self, action: str, key: object) -> None:
        """Raise the 429 problem if ``key``'s limit for ``action`` is used up, without charging it.

        For limits that count only failures (sign-in): look before the attempt, :meth:`hit` after it fails.
        """
        self._draw(action, key, 1.0, take=False)

    def _draw(self, action: str, key: object, cost: float, take: bool) -> None:
        config = current_app.config
        if not config["RATE_LIMITS_ENABLED"] or action not in config["RATE_LIMITS"]:
            return
        per_minute, burst = config["RATE_LIMITS"][action]
        charge = min(max(math.ceil(cost), 1), int(burst))
        strategy = current_app.extensions["lagrade.flask_limiter"].limiter
        identifiers = (action, hashlib.sha256(repr(key).encode("utf-8", "surrogatepass")).hexdigest()[:32])
        window = self._window(per_minute, burst)
        allowed = (strategy.hit(window, *identifiers, cost=charge) if take
                   else strategy.test(window, *identifiers, cost=charge))
        if not allowed:
            reset = strategy.get_window_stats(window, *identifiers).reset_time
            wait = max(1, math.ceil(reset - time.time()))
            raise ApiProblem(429, f"Too many {action} requests: at most {per_minute} a minute (bursts of "
                                  f"{burst}). Try again in {wait} s.", kind="rate-limited",
                             headers={"Retry-After": str(wait)})


# The extension: storage per app (memory, or Redis shared by every web process).
limiter = RateLimiter()


def init_app(app: Flask) -> None:
    limiter.init_app(app)
    app.before_request(_check_csrf)
    app.jinja_env.globals["csrf_token"] = csrf_token

