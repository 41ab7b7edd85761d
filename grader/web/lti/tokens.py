"""OAuth 2 access tokens for the LTI services (AGS, NRPS): client credentials with a signed JWT.

The tool proves who it is to the platform's token endpoint with a short-lived JWT signed by its own
key (``client_assertion``, RFC 7523), as LTI Advantage requires; the access token is cached until
shortly before it expires.
"""

from __future__ import annotations

import secrets
import threading
import time
from dataclasses import dataclass

from grader.store.db import Database
from grader.web.lti import keys
from grader.web.lti.http import PlatformUnreachable, post

__all__ = ["ASSERTION_TYPE", "PlatformAccess", "access_token", "forget_tokens"]

ASSERTION_TYPE = "urn:ietf:params:oauth:client-assertion-type:jwt-bearer"
ASSERTION_LIFETIME_S = 300


@dataclass(frozen=True)
class PlatformAccess:
    """What the tool needs to call one platform's services (plain data: no session attached)."""

    platform_id: int
    issuer: str
    client_id: str
    token_url: str


_tokens: dict[tuple[int, frozenset[str]], tuple[str, float]] = {}
_lock = threading.Lock()


def access_token(database: Database, platform: PlatformAccess, scopes: set[str]) -> str:
    """A bearer token for ``scopes`` on ``platform``: from the cache, or a new client-credentials grant."""
    cache_key = (platform.platform_id, frozenset(scopes))
    now = time.monotonic()
    with _lock:
        cached = _tokens.get(cache_key)
    if cached is not None and cached[1] > now:
        return cached[0]
    issued = int(time.time())
    assertion = keys.sign({"iss": platform.client_id, "sub": platform.client_id, "aud": platform.token_url,
                           "iat": issued, "exp": issued + ASSERTION_LIFETIME_S, "jti": secrets.token_urlsafe(16)},
                          keys.active_key(database))
    answer = post(platform.token_url, data={
        "grant_type": "client_credentials", "client_assertion_type": ASSERTION_TYPE,
        "client_assertion": assertion, "scope": " ".join(sorted(scopes))})
    if not isinstance(answer, dict) or not isinstance(answer.get("access_token"), str):
        raise PlatformUnreachable(f"the token endpoint {platform.token_url} gave no access_token")
    lifetime = answer.get("expires_in", 3600)
    lifetime = float(lifetime) if isinstance(lifetime, (int, float)) else 3600.0
    with _lock:
        _tokens[cache_key] = (answer["access_token"], now + max(0.0, lifetime - 30.0))
    return answer["access_token"]


def forget_tokens() -> None:
    """Drop cached access tokens (tests; after a platform revoked them)."""
    with _lock:
        _tokens.clear()
