"""Who is signed in: ``g.user`` for every page request, and the ``login_required`` guard.

The session cookie holds the user's id and a digest of their password hash, so changing a password
signs out every other browser (the cookie itself is signed by Flask, not encrypted: it holds no secret).
"""

from __future__ import annotations

import functools
import hashlib
from typing import Callable

from flask import abort, g, redirect, request, session, url_for

from grader.store.db import db
from grader.store.models import User
from grader.web.auth import bp
from grader.web.policy import INSTRUCTOR_ROLES, PAGE_ROLES  # the role sets live in the access policy

__all__ = ["INSTRUCTOR_ROLES", "home_for", "login_required", "sign_in", "sign_out"]


def _password_stamp(user: User) -> str:
    return hashlib.sha256((user.password_hash or "").encode()).hexdigest()[:16]


def sign_in(user: User) -> None:
    session.clear()  # a fresh session (and CSRF token) for the new user
    session["user_id"] = user.id
    session["stamp"] = _password_stamp(user)
    session.permanent = False


def sign_out() -> None:
    session.clear()


@bp.before_app_request
def _load_user() -> None:
    g.user = None
    if request.blueprint == "api" or request.endpoint == "static":
        return
    user_id = session.get("user_id")
    if user_id is None:
        return
    # A short session of its own: the request's session (a writer, for a POST) must not hold a
    # transaction open through a slow view. The user comes back detached, its columns loaded.
    with db.read() as reading:
        user = reading.get(User, user_id)
    if user is None or user.role not in PAGE_ROLES or session.get("stamp") != _password_stamp(user):
        session.pop("user_id", None)
        return
    g.user = user


def home_for(user: User | None) -> str:
    """Where a user lands after signing in."""
    if user is None:
        return url_for("auth.login")
    if user.role in INSTRUCTOR_ROLES and "instructor" in _blueprints():
        return url_for("instructor.dashboard")
    return url_for("student.problems") if "student" in _blueprints() else url_for("auth.login")


def _blueprints() -> dict:
    from flask import current_app

    return current_app.blueprints


def login_required(roles: frozenset[str] | set[str] = PAGE_ROLES) -> Callable:
    """A view decorator: signed-out visitors go to the sign-in page, other roles get 403."""

    def decorate(view: Callable) -> Callable:
        @functools.wraps(view)
        def guarded(*args, **kwargs):
            if g.get("user") is None:
                if request.method == "GET" and not request.is_json:
                    return redirect(url_for("auth.login", next=request.full_path.rstrip("?")))
                abort(401, "Sign in first.")
            if g.user.role not in roles:
                abort(403, "This page is not for your account.")
            return view(*args, **kwargs)

        return guarded

    return decorate
