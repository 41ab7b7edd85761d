"""Deep Linking: an instructor picks a lagrade problem, and the LMS gets a signed link to it.

A deep-linking launch (``LtiDeepLinkingRequest``) carries the platform's settings: where to send
the answer (``deep_link_return_url``) and an opaque ``data`` to echo. The answer is a JWT signed
with the tool's key, holding one ``ltiResourceLink`` content item: the launch URL, the problem as
the custom parameter ``problem`` (how the link's later launches find it), and a line item so the
LMS makes a gradebook column whose scores come from AGS.
"""

from __future__ import annotations

import secrets
import time
from dataclasses import asdict, dataclass
from typing import Any

from grader.store.models import ProblemVersion
from grader.web.lti import keys
from grader.web.lti.launch import CLAIM, DEEP_LINKING_SETTINGS, Launch, LaunchRefused
from grader.web.lti.platforms import PlatformError, valid_url

__all__ = ["DeepLinkRequest", "content_item", "pending_request", "response_token"]

CONTENT_ITEMS = "https://purl.imsglobal.org/spec/lti-dl/claim/content_items"
DATA = "https://purl.imsglobal.org/spec/lti-dl/claim/data"
RESPONSE_LIFETIME_S = 300


@dataclass(frozen=True)
class DeepLinkRequest:
    """A content selection waiting for the instructor's choice (kept in their session)."""

    platform_id: int
    issuer: str
    client_id: str
    deployment_id: str
    return_url: str
    data: str | None

    def to_session(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_session(cls, value: Any) -> DeepLinkRequest | None:
        try:
            return cls(**value) if isinstance(value, dict) else None
        except TypeError:
            return None


def pending_request(launch: Launch, issuer: str, client_id: str) -> DeepLinkRequest:
    """The settings of a deep-linking launch; :class:`LaunchRefused` unless a teacher sent it with a
    usable return URL."""
    if launch.role != "instructor":
        raise LaunchRefused(403, "Only an instructor can choose lagrade content for the LMS.")
    settings = launch.claims.get(DEEP_LINKING_SETTINGS)
    if not isinstance(settings, dict):
        raise LaunchRefused(400, "The deep-linking launch has no deep_linking_settings.")
    try:
        return_url = valid_url(str(settings.get("deep_link_return_url") or ""), "deep_link_return_url")
    except PlatformError as error:
        raise LaunchRefused(400, f"The deep-linking launch is unusable: {error}.") from None
    accepted = settings.get("accept_types") or ["ltiResourceLink"]
    if "ltiResourceLink" not in accepted:
        raise LaunchRefused(400, "The LMS accepts no LTI resource links here; lagrade offers only those.")
    data = settings.get("data")
    return DeepLinkRequest(launch.platform_id, issuer, client_id, str(launch.claim("deployment_id")), return_url,
                           data if isinstance(data, str) else None)


def content_item(version: ProblemVersion, launch_url: str) -> dict[str, Any]:
    """The ``ltiResourceLink`` for a problem version, scored out of 1 (as grader.store.scores scores a problem)."""
    slug = version.problem.slug
    return {"type": "ltiResourceLink", "title": version.title, "url": f"{launch_url}?problem={slug}",
            "custom": {"problem": slug},
            "lineItem": {"scoreMaximum": 1, "label": version.title, "resourceId": slug,
                         "tag": "lagrade"}}


def response_token(request: DeepLinkRequest, items: list[dict[str, Any]], key: keys.RSAKey,
                   now: float | None = None) -> str:
    """The signed ``LtiDeepLinkingResponse`` carrying ``items`` back to the platform."""
    issued = int(time.time() if now is None else now)
    claims: dict[str, Any] = {
        "iss": request.client_id, "aud": request.issuer, "iat": issued, "exp": issued + RESPONSE_LIFETIME_S,
        "nonce": secrets.token_urlsafe(16), CLAIM + "message_type": "LtiDeepLinkingResponse",
        CLAIM + "version": "1.3.0", CLAIM + "deployment_id": request.deployment_id, CONTENT_ITEMS: items}
    if request.data is not None:
        claims[DATA] = request.data
    return keys.sign(claims, key)
