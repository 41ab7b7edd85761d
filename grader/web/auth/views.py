"""``/`` (a redirect to the right home), ``/login`` and ``/logout``."""

from __future__ import annotations

from flask import flash, g, redirect, render_template, request, url_for

from grader.store.db import db
from grader.store.users import authenticate
from grader.web.auth import bp
from grader.web.auth.redirects import safe_next
from grader.web.auth.session import PAGE_ROLES, home_for, sign_in, sign_out
from grader.web.auth.throttle import record_failed_sign_in, refuse_if_throttled
from grader.web.errors import ApiProblem

MAX_FIELD = 320


@bp.get("/")
def home():
    return redirect(home_for(g.user))


@bp.route("/login", methods=["GET", "POST"])
def login():
    next_url = safe_next(request.args.get("next")) or None  # only a path on this site
    if request.method == "GET":
        if g.user is not None:
            return redirect(next_url or home_for(g.user))
        return render_template("auth/login.html", next=next_url)
    username = request.form.get("username", "").strip()[:MAX_FIELD]
    password = request.form.get("password", "")[:1024]
    try:
        refuse_if_throttled(username, request.remote_addr)
    except ApiProblem as problem:
        return (render_template("auth/login.html", next=next_url, username=username, error=problem.detail),
                429, problem.headers)
    user = None
    if username and password:
        with db.read() as session:  # a short read: checking a password hash is slow on purpose
            user = authenticate(session, username, password)
    if user is None or user.role not in PAGE_ROLES:
        record_failed_sign_in(username, request.remote_addr)
        # One message for an unknown user and a wrong password: no hint about which accounts exist.
        return render_template("auth/login.html", next=next_url, username=username,
                               error="That email and password do not match an account."), 401
    sign_in(user)
    return redirect(next_url or home_for(user))


@bp.post("/logout")
def logout():
    sign_out()
    flash("You are signed out.", "success")
    return redirect(url_for("auth.login"))
