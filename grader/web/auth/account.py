"""``/account``: the signed-in user's own account (change the password).

Changing a password asks for the current one, so a browser left signed in is not enough to take the
account over; wrong current passwords count as failed sign-ins (:mod:`grader.web.auth.throttle`),
so the form is no faster a way to guess a password than the sign-in form. The new password stamps
the session again: this browser stays signed in, every other one is signed out
(:mod:`grader.web.auth.session`).
"""

from __future__ import annotations

from flask import flash, redirect, render_template, request, url_for
from werkzeug.security import check_password_hash

from grader.store.db import db
from grader.store.models import User
from grader.store.users import MAX_PASSWORD_LENGTH, MIN_PASSWORD_LENGTH, new_password_problem, set_password
from grader.web.auth import bp
from grader.web.auth.session import PAGE_ROLES, login_required, sign_in
from grader.web.auth.throttle import record_failed_sign_in, refuse_if_throttled
from grader.web.errors import ApiProblem
from grader.web.policy import current_principal

__all__ = ["account"]


@bp.route("/account", methods=["GET", "POST"])
@login_required(PAGE_ROLES)
def account():
    me = current_principal()  # the policy says whose account this is: the caller's own, never another's
    with db.read() as session:
        user = session.get(User, me.user_id)
    if user.password_hash is None:  # signed in through an LMS: there is no password here to change
        return _page("Your account signs in through your course's LMS; it has no password here.",
                     status=200 if request.method == "GET" else 403, has_password=False)
    if request.method == "GET":
        return _page()
    current = request.form.get("current", "")[:MAX_PASSWORD_LENGTH + 1]
    new, again = (request.form.get(name, "")[:MAX_PASSWORD_LENGTH + 1] for name in ("new", "again"))
    try:
        refuse_if_throttled(user.email or f"user {user.id}", request.remote_addr)
    except ApiProblem as problem:
        return _page(problem.detail, field="current", status=429, headers=problem.headers)
    if not current or not new or not again:
        return _page("Fill in all three fields.", field="current" if not current else "new")
    problem = new_password_problem(new)
    if problem is not None:
        return _page(problem, field="new")
    if new != again:
        return _page("The two new passwords differ; type the same one twice.", field="again")
    if not check_password_hash(user.password_hash, current):
        record_failed_sign_in(user.email or f"user {user.id}", request.remote_addr)
        return _page("That is not your current password.", field="current", status=403)
    with db.write() as session:
        stored = session.get(User, me.user_id)
        set_password(stored, new)
    with db.read() as session:
        sign_in(session.get(User, me.user_id))  # a new stamp: other browsers are signed out, this one stays
    flash("Your password is changed. Other browsers signed in to this account are signed out.", "success")
    return redirect(url_for("auth.account"))


def _page(error: str | None = None, *, field: str | None = None, status: int | None = None,
          headers: dict[str, str] | None = None, has_password: bool = True):
    if status is None:
        status = 200 if error is None else 422
    return (render_template("auth/account.html", error=error, field=field, min_length=MIN_PASSWORD_LENGTH,
                            has_password=has_password), status, headers or {})
