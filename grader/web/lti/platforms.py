"""Registered platforms (LMSs): adding one, finding the one a request names, and its public keys.

An administrator registers a platform once (``grader lti add-platform``) with what its LTI
registration page shows: issuer, client id, deployment ids, and the OIDC authorisation, token and
JWKS URLs. The platform's keys are fetched from its JWKS URL and cached; a token signed with a key
id the cache does not know makes one refetch (platforms rotate keys), at most every
``REFRESH_MIN_S`` per platform so that tokens with made-up key ids cannot make us hammer it.
"""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass
from urllib.parse import urlsplit

from sqlalchemy import select
from sqlalchemy.orm import Session

from grader.store.lti_models import LtiDeployment, LtiPlatform
from grader.web.lti import keys
from grader.web.lti.http import PlatformUnreachable, get_json

__all__ = ["PlatformError", "find_platform", "platform_keys", "register_platform", "valid_url"]

JWKS_TTL_S = 3600.0
REFRESH_MIN_S = 10.0


class PlatformError(ValueError):
    """A platform registration that cannot be stored, or a platform that cannot be used; says why."""


def valid_url(url: str, what: str) -> str:
    """``url`` if it is an absolute http(s) URL, else :class:`PlatformError` naming ``what``.

    >>> valid_url("https://lms.example.org/auth", "auth URL")
    'https://lms.example.org/auth'
    """
    parts = urlsplit(url or "")
    if parts.scheme not in ("https", "http") or not parts.hostname:
        raise PlatformError(f"the {what} must be an http(s) URL, not {url!r}")
    return url


def register_platform(session: Session, *, name: str, issuer: str, client_id: str, auth_url: str, token_url: str,
                      jwks_url: str, deployment_ids: list[str]) -> LtiPlatform:
    """Add (or update) the platform ``(issuer, client_id)`` and add its deployment ids; flushed, not committed."""
    if not issuer or not client_id:
        raise PlatformError("a platform needs its issuer and the client id it gave this tool")
    for value in (issuer, client_id, *deployment_ids):
        if len(value) > 255:
            raise PlatformError(f"LTI ids are at most 255 characters: {value[:40]!r}...")
    urls = {"auth_url": valid_url(auth_url, "OIDC authorisation URL"), "token_url": valid_url(token_url, "token URL"),
            "jwks_url": valid_url(jwks_url, "JWKS URL")}
    platform = session.scalar(select(LtiPlatform).where(LtiPlatform.issuer == issuer,
                                                        LtiPlatform.client_id == client_id))
    if platform is None:
        platform = LtiPlatform(issuer=issuer, client_id=client_id, name=name[:200] or issuer[:200], **urls)
        session.add(platform)
        session.flush()
    else:
        platform.name = name[:200] or platform.name
        for field, value in urls.items():
            setattr(platform, field, value)
    known = {d.deployment_id for d in platform.deployments}
    for deployment_id in deployment_ids:
        if deployment_id not in known:
            platform.deployments.append(LtiDeployment(deployment_id=deployment_id))
            known.add(deployment_id)
    session.flush()
    return platform


def find_platform(session: Session, issuer: str, client_id: str | None = None) -> LtiPlatform | None:
    """The platform registered for ``issuer`` (and ``client_id``, when the request names one).

    Without a client id, the issuer must be registered once only: with two registrations the
    request is ambiguous and gets None.
    """
    query = select(LtiPlatform).where(LtiPlatform.issuer == issuer)
    if client_id:
        query = query.where(LtiPlatform.client_id == client_id)
    found = session.scalars(query.limit(2)).all()
    return found[0] if len(found) == 1 else None


@dataclass
class _Cached:
    keys: keys.KeySet
    kids: frozenset[str]
    fetched: float


_cache: dict[str, _Cached] = {}
_lock = threading.Lock()


def platform_keys(jwks_url: str, kid: str | None) -> keys.KeySet:
    """The platform's public keys, from the cache unless it is stale or does not know ``kid``.

    Raises :class:`PlatformUnreachable` if the JWKS cannot be fetched or read.
    """
    now = time.monotonic()
    with _lock:
        cached = _cache.get(jwks_url)
    if cached is not None:
        fresh = now - cached.fetched < JWKS_TTL_S
        if fresh and (kid is None or kid in cached.kids or now - cached.fetched < REFRESH_MIN_S):
            return cached.keys
    try:
        document = get_json(jwks_url)
        key_set = keys.import_key_set(document)
    except ValueError as error:
        raise PlatformUnreachable(f"the platform's JWKS at {jwks_url} cannot be read: {error}") from error
    kids = frozenset(k.get("kid") for k in document["keys"] if isinstance(k, dict) and k.get("kid"))
    with _lock:
        _cache[jwks_url] = _Cached(key_set, kids, now)
    return key_set


def forget_keys() -> None:
    """Empty the key cache (tests; an administrator after a platform's emergency key change)."""
    with _lock:
        _cache.clear()
