"""LTI 1.3 launches: OIDC login initiation, and the id_token's validation and what it opens.

The launch is the OpenID Connect implicit flow of the LTI 1.3 core specification, in three legs:

1. the platform sends the browser to ``/lti/login`` (``iss``, ``login_hint``, ``target_link_uri``...);
   :func:`login_redirect` answers with a redirect to the platform's authorisation URL carrying a
   fresh ``state`` and ``nonce``, and a signed cookie binding both to this browser for ten minutes;
2. the platform authenticates the user and form-posts an ``id_token`` (a JWT it signed) and the
   ``state`` to ``/lti/launch``;
3. :func:`validate` refuses the launch unless: the state matches the cookie; the token's RS256
   signature verifies with a key of the platform's JWKS; ``iss`` is the platform that started the
   login; ``aud`` holds our client id (and ``azp`` is it when there are several audiences); ``exp``
   and ``iat`` hold within ``LEEWAY_S``; the ``nonce`` is the one we issued and was never used
   before (it is stored in ``lti_nonces``, unique per platform); the LTI version is 1.3.0, the
   message type one we serve and the deployment one the administrator registered.

Each refusal is a :class:`LaunchRefused` with a status (400 malformed, 403 not trusted) and a
sentence for the person in front of the LMS; the views show it as a page, never a 500.
"""

from __future__ import annotations

import base64
import json
import secrets
import time
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import Any
from urllib.parse import parse_qs, urlencode, urlsplit

from itsdangerous import BadSignature, URLSafeTimedSerializer
from sqlalchemy import delete, select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from grader.store.db import Database
from grader.store.lti_models import LtiContext, LtiLaunch, LtiNonce, LtiPlatform, LtiResourceLink
from grader.store.models import Course, Problem, utcnow
from grader.store.problems import problem_by_slug
from grader.web.lti import keys
from grader.web.lti.accounts import AccountTaken, course_role, enrol, lti_user
from grader.web.lti.platforms import find_platform, platform_keys

__all__ = ["CLAIM", "Launch", "LaunchRefused", "link_target", "login_redirect", "open_context", "open_resource_link",
           "validate"]

CLAIM = "https://purl.imsglobal.org/spec/lti/claim/"
DEEP_LINKING_SETTINGS = "https://purl.imsglobal.org/spec/lti-dl/claim/deep_linking_settings"
AGS_ENDPOINT = "https://purl.imsglobal.org/spec/lti-ags/claim/endpoint"
NRPS_SERVICE = "https://purl.imsglobal.org/spec/lti-nrps/claim/namesroleservice"
AGS_SCORE_SCOPE = "https://purl.imsglobal.org/spec/lti-ags/scope/score"
RESOURCE_LINK_REQUEST = "LtiResourceLinkRequest"
DEEP_LINKING_REQUEST = "LtiDeepLinkingRequest"
MESSAGE_TYPES = (RESOURCE_LINK_REQUEST, DEEP_LINKING_REQUEST)

LEEWAY_S = 60  # clock difference tolerated between the platform and us
STATE_MAX_AGE_S = 600
STATE_COOKIE = "lti1p3-state-"
MAX_TOKEN_CHARS = 64 * 1024


class LaunchRefused(Exception):
    """A login or launch we refuse; ``str()`` says why in a sentence for the user."""

    def __init__(self, status: int, message: str):
        super().__init__(message)
        self.status = status


@dataclass(frozen=True)
class Launch:
    """A validated launch: the platform it came from and the token's claims."""

    platform_id: int
    claims: dict[str, Any]

    def claim(self, name: str, default: Any = None) -> Any:
        return self.claims.get(CLAIM + name, default)

    @property
    def message_type(self) -> str:
        return self.claim("message_type")

    @property
    def role(self) -> str:
        roles = self.claim("roles", [])
        return course_role(roles if isinstance(roles, list) else [])

    @property
    def name(self) -> str:
        name = self.claims.get("name") or " ".join(
            str(self.claims.get(k, "")) for k in ("given_name", "family_name")).strip()
        return name if isinstance(name, str) else ""


def _serializer(secret_key: str) -> URLSafeTimedSerializer:
    return URLSafeTimedSerializer(secret_key, salt="lagrade-lti-state")


# --- leg 1: login initiation ---------------------------------------------------------------------------

def login_redirect(session: Session, params: dict[str, str], *, launch_url: str, host: str,
                   secret_key: str) -> tuple[str, str, str, LtiPlatform]:
    """Where to send the browser (the platform's authorisation URL) and the state cookie to set.

    Returns ``(redirect URL, cookie name, cookie value, platform)``.
    """
    issuer, login_hint, target = params.get("iss"), params.get("login_hint"), params.get("target_link_uri")
    if not issuer or not login_hint or not target:
        raise LaunchRefused(400, "This is not an LTI login: it needs iss, login_hint and target_link_uri. "
                                 "Start the tool from your LMS.")
    platform = find_platform(session, issuer, params.get("client_id"))
    if platform is None:
        raise LaunchRefused(403, f"The LMS {issuer[:200]!r} is not registered with this lagrade (or not with this "
                                 "client id). An administrator registers it with `grader lti add-platform`.")
    if urlsplit(target).netloc != host:
        raise LaunchRefused(400, "The launch names a target on another site; this tool only opens its own pages.")
    deployment = params.get("lti_deployment_id")
    if deployment and deployment not in {d.deployment_id for d in platform.deployments}:
        raise LaunchRefused(403, f"The deployment {deployment[:100]!r} of this LMS is not registered with lagrade.")
    state, nonce = secrets.token_urlsafe(24), secrets.token_urlsafe(24)
    query = {"scope": "openid", "response_type": "id_token", "response_mode": "form_post", "prompt": "none",
             "client_id": platform.client_id, "redirect_uri": launch_url, "login_hint": login_hint,
             "state": state, "nonce": nonce}
    if params.get("lti_message_hint"):
        query["lti_message_hint"] = params["lti_message_hint"]
    separator = "&" if urlsplit(platform.auth_url).query else "?"
    cookie = _serializer(secret_key).dumps({"state": state, "nonce": nonce, "platform": platform.id})
    return platform.auth_url + separator + urlencode(query), STATE_COOKIE + state, cookie, platform


# --- leg 3: the launch -----------------------------------------------------------------------------------

def _segment(part: str) -> Any:
    return json.loads(base64.urlsafe_b64decode(part + "=" * (-len(part) % 4)))


def _unverified(token: str) -> tuple[dict[str, Any], dict[str, Any]]:
    """The header and claims of a compact JWS, *not verified*: only to choose the keys to verify it with."""
    try:
        header, payload, _ = token.split(".")
        header_json, claims = _segment(header), _segment(payload)
    except (ValueError, UnicodeDecodeError):
        raise LaunchRefused(400, "The launch's id_token is not a JSON Web Token.") from None
    if not isinstance(header_json, dict) or not isinstance(claims, dict):
        raise LaunchRefused(400, "The launch's id_token is not a JSON Web Token.")
    return header_json, claims


def validate(database: Database, session: Session, form: dict[str, str], cookies: dict[str, str], *,
             secret_key: str, now: float | None = None) -> Launch:
    """Check a launch (``form``: the posted fields; ``cookies``: the request's) and use up its nonce.

    The platform is read in a short session of ``database`` and its keys fetched before ``session``
    (the request's writer) is touched: no write transaction waits on the LMS. The nonce row is
    flushed in ``session`` and committed with the rest of the launch.
    """
    if form.get("error"):
        description = str(form.get("error_description") or form["error"])[:300]
        raise LaunchRefused(403, f"The LMS refused to launch the tool: {description}")
    state, token = form.get("state", ""), form.get("id_token", "")
    if not state or not token:
        raise LaunchRefused(400, "This is not an LTI launch: it has no state or id_token. Start the tool from your LMS.")
    if len(token) > MAX_TOKEN_CHARS:
        raise LaunchRefused(400, "The launch's id_token is too long.")
    try:
        bound = _serializer(secret_key).loads(cookies.get(STATE_COOKIE + state, ""), max_age=STATE_MAX_AGE_S)
    except BadSignature:
        raise LaunchRefused(400, "This launch did not start in this browser, or took more than ten minutes. "
                                 "Start it again from your LMS; if this repeats, your browser may be blocking the "
                                 "tool's cookies inside the LMS: open the tool in a new window.") from None
    if not isinstance(bound, dict) or bound.get("state") != state:
        raise LaunchRefused(400, "The launch's state does not match this browser's.")
    header, unverified = _unverified(token)
    with database.read() as reading:
        platform = reading.get(LtiPlatform, bound.get("platform"))
        deployments = {d.deployment_id for d in platform.deployments} if platform is not None else set()
    if platform is None or unverified.get("iss") != platform.issuer:
        raise LaunchRefused(403, "The launch's issuer is not the LMS that started the login; it is refused.")
    key_set = platform_keys(platform.jwks_url, header.get("kid") if isinstance(header.get("kid"), str) else None)
    try:
        claims = keys.verify(token, key_set).claims
    except (keys.JoseError, ValueError, TypeError):
        raise LaunchRefused(403, "The launch's signature does not verify with the LMS's published keys: it may be "
                                 "forged. It is refused.") from None
    _check_claims(platform, deployments, claims, expected_nonce=bound.get("nonce"),
                  now=time.time() if now is None else now)
    _use_nonce(session, platform, claims)
    return Launch(platform.id, claims)


def _check_claims(platform: LtiPlatform, deployments: set[str], claims: dict[str, Any], *,
                  expected_nonce: str | None, now: float) -> None:
    if claims.get("iss") != platform.issuer:
        raise LaunchRefused(403, "The launch's issuer is not the LMS that started the login; it is refused.")
    audience = claims.get("aud")
    audiences = audience if isinstance(audience, list) else [audience]
    if platform.client_id not in audiences:
        raise LaunchRefused(403, "The launch is meant for another tool (its audience is not this tool's client id).")
    if (len(audiences) > 1 or "azp" in claims) and claims.get("azp") != platform.client_id:
        raise LaunchRefused(403, "The launch's authorised party (azp) is not this tool.")
    exp, iat = claims.get("exp"), claims.get("iat")
    if not isinstance(exp, (int, float)) or not isinstance(iat, (int, float)):
        raise LaunchRefused(400, "The launch's id_token has no expiry or issue time.")
    if now > exp + LEEWAY_S:
        raise LaunchRefused(403, "This launch has expired. Start the tool again from your LMS.")
    if iat > now + LEEWAY_S:
        raise LaunchRefused(403, "The launch says it was issued in the future: the LMS's clock or the token is wrong.")
    if not expected_nonce or claims.get("nonce") != expected_nonce:
        raise LaunchRefused(403, "The launch's nonce is not the one this login issued; it is refused.")
    if claims.get(CLAIM + "version") != "1.3.0":
        raise LaunchRefused(400, "Only LTI 1.3.0 launches are served.")
    if claims.get(CLAIM + "message_type") not in MESSAGE_TYPES:
        raise LaunchRefused(400, f"This tool serves resource links and deep linking, not "
                                 f"{str(claims.get(CLAIM + 'message_type'))[:60]!r}.")
    if claims.get(CLAIM + "deployment_id") not in deployments:
        raise LaunchRefused(403, "This deployment of the tool in the LMS is not registered with lagrade. An administrator "
                                 "adds it with `grader lti add-platform --deployment ...`.")
    if not isinstance(claims.get("sub"), str) or not claims["sub"] or len(claims["sub"]) > 255:
        raise LaunchRefused(400, "The launch names no user (anonymous launches are not served).")


def _use_nonce(session: Session, platform: LtiPlatform, claims: dict[str, Any]) -> None:
    """Store the nonce, refusing one seen before; forget nonces whose tokens have expired anyway."""
    nonce = claims.get("nonce")
    if not isinstance(nonce, str) or len(nonce) > 255:
        raise LaunchRefused(400, "The launch's nonce is missing or too long.")
    expires = datetime.fromtimestamp(float(claims["exp"]) + LEEWAY_S, timezone.utc).replace(tzinfo=None)
    session.execute(delete(LtiNonce).where(LtiNonce.expires_at < utcnow()))
    try:
        with session.begin_nested():
            session.add(LtiNonce(platform_id=platform.id, nonce=nonce, expires_at=max(expires, utcnow())))
    except IntegrityError:
        raise LaunchRefused(403, "This launch was used already (its nonce has been seen): a replayed launch is "
                                 "refused. Start the tool again from your LMS.") from None


# --- what a launch opens ---------------------------------------------------------------------------------

def open_context(session: Session, launch: Launch) -> tuple[Any, LtiContext | None]:
    """The launching user (made on first launch) and the launch's LMS course, mapped to a lagrade
    course (made on its first launch), with the user enrolled there in their LMS role."""
    platform = session.get(LtiPlatform, launch.platform_id)
    try:
        user = lti_user(session, platform, launch.claims["sub"], launch.name, launch.role)
    except AccountTaken as error:
        raise LaunchRefused(409, str(error)) from None
    context_claim = launch.claim("context")
    if not isinstance(context_claim, dict) or not isinstance(context_claim.get("id"), str):
        return user, None
    context_id = context_claim["id"][:255]
    context = session.scalar(select(LtiContext).where(LtiContext.platform_id == platform.id,
                                                      LtiContext.context_id == context_id))
    title = str(context_claim.get("title") or context_claim.get("label") or "LMS course")[:200]
    if context is None:
        course = Course(code=f"lti-{platform.id}-{secrets.token_hex(6)}", title=title)
        session.add(course)
        session.flush()
        context = LtiContext(platform_id=platform.id, context_id=context_id, title=title, course_id=course.id)
        session.add(context)
    context.title = title
    service = launch.claims.get(NRPS_SERVICE)
    if isinstance(service, dict) and isinstance(service.get("context_memberships_url"), str):
        context.memberships_url = service["context_memberships_url"]
    session.flush()
    enrol(session, user, context.course_id, launch.role)
    return user, context


def link_target(session: Session, link: LtiResourceLink, launch: Launch) -> Problem | None:
    """What an LMS link opens: its stored problem, else the problem its launch names (the custom
    parameter ``problem`` that deep linking set, or ``?problem=`` in its target URL), stored then.

    The one place a link's target is resolved: assignments join here when they exist.
    """
    if link.problem_id is not None:
        return session.get(Problem, link.problem_id)
    custom = launch.claim("custom")
    slug = custom.get("problem") if isinstance(custom, dict) else None
    if not isinstance(slug, str):
        target = launch.claim("target_link_uri")
        slug = (parse_qs(urlsplit(target).query).get("problem") or [None])[0] if isinstance(target, str) else None
    problem = problem_by_slug(session, slug[:100]) if isinstance(slug, str) else None
    if problem is not None:
        link.problem_id = problem.id
    return problem


def open_resource_link(session: Session, launch: Launch, context: LtiContext | None, user) -> Problem:
    """Record the LMS link (its AGS line item too) and that ``user`` launched it; its problem, or
    :class:`LaunchRefused` when the link opens nothing here yet."""
    link_claim = launch.claim("resource_link")
    if context is None or not isinstance(link_claim, dict) or not isinstance(link_claim.get("id"), str):
        raise LaunchRefused(400, "The launch names no LMS course or link.")
    link = session.scalar(select(LtiResourceLink).where(LtiResourceLink.context_id == context.id,
                                                        LtiResourceLink.resource_link_id == link_claim["id"][:255]))
    if link is None:
        link = LtiResourceLink(context_id=context.id, resource_link_id=link_claim["id"][:255])
        session.add(link)
    link.title = str(link_claim.get("title") or "")[:200]
    ags = launch.claims.get(AGS_ENDPOINT)
    if isinstance(ags, dict) and AGS_SCORE_SCOPE in (ags.get("scope") or []):
        if isinstance(ags.get("lineitem"), str):
            link.lineitem_url = ags["lineitem"]
        if isinstance(ags.get("lineitems"), str):
            link.lineitems_url = ags["lineitems"]
    session.flush()
    problem = link_target(session, link, launch)
    if problem is None:
        raise LaunchRefused(404, "This LMS link is not connected to a lagrade problem yet. An instructor connects it "
                                 "by choosing the problem through the LMS's content selection (Deep Linking).")
    launched = session.scalar(select(LtiLaunch).where(LtiLaunch.resource_link_id == link.id,
                                                      LtiLaunch.user_id == user.id))
    if launched is None:
        session.add(LtiLaunch(resource_link_id=link.id, user_id=user.id))
    else:
        launched.last_launched_at = utcnow()
    session.flush()
    return problem
