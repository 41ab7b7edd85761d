"""The LTI routes: the tool's JWKS, login initiation, launch, deep linking, roster sync, configuration.

The platform-facing routes (``/lti/login``, ``/lti/launch``) are posted to by the LMS, so they carry
no CSRF token of ours (``csrf_exempt``): the state cookie, the signed id_token and its single-use
nonce are their proof. Every refusal is an error page with a sentence saying why (4xx; 502 when the
LMS itself cannot be reached), never a 500. Access to problems and courses is the policy's to decide.
"""

from __future__ import annotations

import re
from urllib.parse import urlsplit

from flask import abort, current_app, flash, g, jsonify, redirect, render_template, request, session, url_for
from sqlalchemy import select

from grader.store.db import db
from grader.store.lti_models import LtiContext, LtiPlatform
from grader.store.problems import latest_version
from grader.web.auth.session import login_required, sign_in
from grader.web.headers import allow_framing, content_security_policy
from grader.web.lti import bp, keys
from grader.web.lti.deep_linking import DeepLinkRequest, content_item, pending_request, response_token
from grader.web.lti.http import PlatformUnreachable
from grader.web.lti.launch import (DEEP_LINKING_REQUEST, STATE_COOKIE, LaunchRefused, login_redirect, open_context,
                                   open_resource_link, validate)
from grader.web.lti.nrps import apply_roster, fetch_roster
from grader.web.policy import (INSTRUCTOR_ROLES, Action, Principal, allowed, current_principal, find_problem,
                               find_version, managed_problems, require)
from grader.web.security import csrf_exempt

FRAME_ORIGIN = "lti_frame_origin"  # session key: the LMS origin allowed to frame this session's pages
DEEP_LINK = "lti_deep_link"  # session key: the content selection waiting for the instructor
# An origin a CSP source list may name: scheme, host, port; nothing that could end the directive.
_ORIGIN = re.compile(r"https?://[A-Za-z0-9.-]+(?::\d{1,5})?")


def _origin(url: str) -> str | None:
    parts = urlsplit(url)
    origin = f"{parts.scheme}://{parts.netloc}"
    return origin if _ORIGIN.fullmatch(origin) else None


def _frame_for(platform: LtiPlatform) -> str | None:
    """Let the platform's pages frame this response (its OIDC host is where the LMS runs)."""
    origin = _origin(platform.auth_url)
    if origin and origin.startswith("https://"):
        allow_framing(origin)
        return origin
    return None  # plain http (a test platform): stays unframable


@bp.before_app_request
def _framed_session() -> None:
    """Pages of a session that came in through an LMS may be framed by that LMS (and only it)."""
    origin = session.get(FRAME_ORIGIN)
    if origin and not request.path.startswith("/api/"):
        try:
            allow_framing(origin)
        except ValueError:
            session.pop(FRAME_ORIGIN, None)


def _refuse(error: Exception) -> None:
    db.session.rollback()
    if isinstance(error, LaunchRefused):
        abort(error.status, str(error))
    abort(502, f"The LMS could not be reached or answered an error: {error}")


@bp.get("/jwks")
def jwks():
    """The tool's public keys: platforms verify its client assertions and deep-linking answers with them."""
    return jsonify(keys.tool_jwks(db))


@bp.route("/login", methods=["GET", "POST"])
@csrf_exempt
def login():
    """OIDC login initiation (the launch's first leg): on to the platform's authorisation URL."""
    params = {k: v for k, v in request.values.items() if isinstance(v, str)}
    try:
        with db.read() as reading:
            target, name, value, platform = login_redirect(
                reading, params, launch_url=url_for("lti.launch", _external=True), host=request.host,
                secret_key=current_app.secret_key)
            _frame_for(platform)
    except LaunchRefused as refused:
        abort(refused.status, str(refused))
    response = redirect(target)
    # The launch comes back as a cross-site POST from the LMS: only a SameSite=None cookie (which
    # browsers accept only when Secure) travels with it; without HTTPS (development) it is Lax.
    https = current_app.config["HTTPS"]
    response.set_cookie(name, value, max_age=600, path="/lti", httponly=True, secure=https,
                        samesite="None" if https else "Lax")
    return response


@bp.post("/launch")
@csrf_exempt
def launch():
    """The launch (the third leg): validate the id_token, sign the user in, open what the link opens."""
    form = {k: v for k, v in request.form.items()}
    writing = db.session
    try:
        result = validate(db, writing, form, request.cookies, secret_key=current_app.secret_key)
        platform = writing.get(LtiPlatform, result.platform_id)
        frame = _frame_for(platform)
        user, context = open_context(writing, result)
        if result.message_type == DEEP_LINKING_REQUEST:
            pending = pending_request(result, platform.issuer, platform.client_id)
            writing.commit()
            target = url_for("lti.deep_link")
        else:
            problem = open_resource_link(writing, result, context, user)
            writing.commit()
            # The policy decides whether the link's problem is open to this user (404 page if not).
            find_version(writing, Principal.of(writing, user), problem.slug, Action.SEE)
            endpoint = "instructor.problem" if user.role in INSTRUCTOR_ROLES else "student.problem"
            target, pending = url_for(endpoint, slug=problem.slug), None
    except (LaunchRefused, PlatformUnreachable) as error:
        _refuse(error)
    sign_in(user)
    if frame:
        session[FRAME_ORIGIN] = frame
    if pending is not None:
        session[DEEP_LINK] = pending.to_session()
    response = redirect(target)
    response.delete_cookie(STATE_COOKIE + form.get("state", ""), path="/lti")
    return response


def _pending() -> DeepLinkRequest:
    pending = DeepLinkRequest.from_session(session.get(DEEP_LINK))
    if pending is None:
        abort(400, "No content selection from an LMS is waiting. Start it from your LMS (add external tool content).")
    return pending


@bp.get("/deep-link")
@login_required(INSTRUCTOR_ROLES)
def deep_link():
    """The instructor picks the problem the LMS link will open (published problems they manage)."""
    _pending()
    principal = current_principal()
    choices = []
    for problem in managed_problems(db.session, principal):
        version = latest_version(db.session, problem, published_only=True)
        if version is not None:
            choices.append(version)
    return render_template("lti/deep_link.html", choices=choices)


@bp.post("/deep-link")
@login_required(INSTRUCTOR_ROLES)
def deep_link_choose():
    """Send the chosen problem back to the LMS: a signed deep-linking response, posted by the browser."""
    pending = _pending()
    key = keys.active_key(db)  # first: it may write (a first key) in a transaction of its own
    slug = request.form.get("problem", "")[:100]
    if not slug:
        abort(400, "Choose a problem first.")
    problem = find_problem(db.session, current_principal(), slug, Action.MANAGE)
    version = latest_version(db.session, problem, published_only=True)
    if version is None:
        abort(409, f"Problem {slug!r} has no published version yet; publish it before linking it into the LMS.")
    return_origin = _origin(pending.return_url)
    if return_origin is None:
        abort(400, "The LMS's return address cannot be used.")
    token = response_token(pending, [content_item(version, url_for("lti.launch", _external=True))], key)
    session.pop(DEEP_LINK, None)
    response = current_app.make_response(render_template(
        "lti/deep_link_return.html", return_url=pending.return_url, jwt=token, title=version.title))
    # This page's form posts to the LMS: the only place the CSP lets a form leave this site.
    policy = content_security_policy(g.get("frame_ancestors"))
    response.headers["Content-Security-Policy"] = policy.replace("form-action 'self'",
                                                                 f"form-action 'self' {return_origin}")
    return response


@bp.get("/config")
@login_required(INSTRUCTOR_ROLES)
def config():
    """What an LMS administrator pastes into the LMS, the registered platforms, and roster syncs."""
    principal = current_principal()
    key = keys.active_key(db)
    platforms = db.session.scalars(select(LtiPlatform).order_by(LtiPlatform.name)).all()
    contexts = [c for c in db.session.scalars(select(LtiContext).order_by(LtiContext.title))
                if allowed(principal, Action.MANAGE_COURSE, c.course)]
    urls = {
        "OIDC login initiation URL": url_for("lti.login", _external=True),
        "Redirect (launch) URL": url_for("lti.launch", _external=True),
        "Target link URI": url_for("lti.launch", _external=True),
        "Deep linking URL": url_for("lti.launch", _external=True),
        "Public JWKS URL": url_for("lti.jwks", _external=True),
    }
    return render_template("lti/config.html", urls=urls, public_pem=keys.public_pem(key), kid=key.kid,
                           platforms=platforms, contexts=contexts)


@bp.post("/contexts/<int:context_id>/roster")
@login_required(INSTRUCTOR_ROLES)
def roster(context_id: int):
    """Fill the course's roster from the LMS (Names and Role Provisioning)."""
    with db.read() as reading:  # a short read: the LMS is called with no transaction open
        context = reading.get(LtiContext, context_id)
        if context is None:
            abort(404, f"There is no LMS course {context_id}.")
        require(current_principal(), Action.MANAGE_COURSE, context.course)  # 404 outside it, 403 inside
    if not context.memberships_url:
        abort(409, "This LMS course offered no roster service at its launches; launch the tool from it once, "
                   "with Names and Role Provisioning enabled for the tool.")
    try:
        members = fetch_roster(db, context.id)
    except PlatformUnreachable as error:
        _refuse(error)
    result = apply_roster(db.session, context.id, members)
    db.session.commit()
    flash(f"Roster of {context.title}: {result.members} members ({result.students} students, "
          f"{result.instructors} instructors), {result.skipped} skipped.", "success")
    return redirect(url_for("lti.config"))
