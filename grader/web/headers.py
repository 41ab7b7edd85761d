"""Security headers on every response, HTTPS-only cookies, and the one way to allow framing.

- ``Content-Security-Policy``: scripts, styles, fonts and connections only from this site, no inline
  script or style (the templates keep both in ``static/``), no plugins, forms posting only here, and
  ``frame-ancestors 'none'`` with ``X-Frame-Options: DENY`` so no other site can frame a page to
  click-jack it. Images may also come over HTTPS: a problem statement may show a figure from elsewhere.
- ``X-Content-Type-Options: nosniff``, ``Referrer-Policy: same-origin`` (no page address, which may
  hold a problem slug, leaks to a linked site), ``Cross-Origin-Opener-Policy: same-origin``.
- With ``LAGRADE_HTTPS=true`` (``docker-compose.yml`` sets it; TLS ends at the proxy in front):
  ``Strict-Transport-Security`` and the session cookie marked ``Secure``.

A page meant to be embedded (an LMS showing a problem through LTI) opts in per response with
:func:`allow_framing` or the :func:`framable` decorator, naming the origins that may frame it.
"""

from __future__ import annotations

import functools
import re
from typing import Callable, Iterable

from flask import Flask, Response, current_app, g

__all__ = ["CONTENT_SECURITY_POLICY", "allow_framing", "content_security_policy", "framable", "init_app"]

CONTENT_SECURITY_POLICY = {
    "default-src": "'self'",
    "script-src": "'self'",
    "style-src": "'self'",
    "img-src": "'self' https:",
    "object-src": "'none'",
    "base-uri": "'none'",
    "form-action": "'self'",
    "frame-ancestors": "'none'",
}
HSTS = "max-age=31536000; includeSubDomains"
# An origin as CSP writes it: scheme, host, optional port; nothing that could end the directive.
_ORIGIN = re.compile(r"https://[A-Za-z0-9.-]+(?::\d{1,5})?|'self'")


def content_security_policy(frame_ancestors: Iterable[str] | None = None) -> str:
    """The policy as a header value; ``frame_ancestors`` replaces ``'none'`` when given.

    >>> "frame-ancestors https://lms.example.org" in content_security_policy(["https://lms.example.org"])
    True
    """
    directives = dict(CONTENT_SECURITY_POLICY)
    if frame_ancestors is not None:
        directives["frame-ancestors"] = " ".join(frame_ancestors) or "'none'"
    return "; ".join(f"{name} {value}" for name, value in directives.items())


def allow_framing(*origins: str) -> None:
    """Let ``origins`` (``"https://lms.example.org"`` or ``"'self'"``) frame this request's response.

    Raises ``ValueError`` for anything that is not such an origin, so a value taken from a launch
    request cannot widen or break the policy.
    """
    for origin in origins:
        if not _ORIGIN.fullmatch(origin):
            raise ValueError(f"not an https origin: {origin!r}")
    g.frame_ancestors = tuple(dict.fromkeys(origins))


def framable(*origins: str) -> Callable:
    """A view decorator: :func:`allow_framing` by ``origins`` for every response of the view."""

    def decorate(view: Callable) -> Callable:
        @functools.wraps(view)
        def framed(*args, **kwargs):
            allow_framing(*origins)
            return view(*args, **kwargs)

        return framed

    return decorate


def _set_headers(response: Response) -> Response:
    headers = response.headers
    ancestors = g.get("frame_ancestors")
    headers.setdefault("Content-Security-Policy", content_security_policy(ancestors))
    if ancestors is None:
        headers.setdefault("X-Frame-Options", "DENY")  # for browsers that ignore frame-ancestors
    headers.setdefault("X-Content-Type-Options", "nosniff")
    headers.setdefault("Referrer-Policy", "same-origin")
    headers.setdefault("Cross-Origin-Opener-Policy", "same-origin")
    if current_app.config["HTTPS"]:
        headers.setdefault("Strict-Transport-Security", HSTS)
    return response


def init_app(app: Flask) -> None:
    """Add the headers to every response; behind HTTPS, make cookies ``Secure`` and URLs ``https``."""
    if app.config["HTTPS"]:
        app.config["SESSION_COOKIE_SECURE"] = True
        app.config["PREFERRED_URL_SCHEME"] = "https"
    app.after_request(_set_headers)
