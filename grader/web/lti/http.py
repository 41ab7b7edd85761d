"""Calls from the tool to a platform (JWKS, OAuth token, AGS, NRPS): JSON over HTTP, short timeouts.

The platform is another organisation's server: every call has a connect and a read timeout, a cap
on the body it reads, and turns every failure into :class:`PlatformUnreachable` with a message for
the person who asked (an instructor syncing a roster) or the log (the score sender).
"""

from __future__ import annotations

import json
from typing import Any

import requests

__all__ = ["MAX_BODY", "PlatformUnreachable", "TIMEOUT", "get_json", "get_page", "post"]

TIMEOUT = (3.05, 10.0)  # (connect, read) seconds
MAX_BODY = 4 * 1024 * 1024


class PlatformUnreachable(RuntimeError):
    """The platform could not be reached, answered an error, or answered something unreadable."""

    def __init__(self, message: str, status: int | None = None):
        super().__init__(message)
        self.status = status


def _read(response: requests.Response) -> bytes:
    body = b""
    for chunk in response.iter_content(64 * 1024):
        body += chunk
        if len(body) > MAX_BODY:
            raise PlatformUnreachable(f"{response.url} answered more than {MAX_BODY} bytes")
    return body


def _call(method: str, url: str, **kwargs) -> tuple[requests.Response, bytes]:
    try:
        with requests.request(method, url, timeout=TIMEOUT, stream=True, allow_redirects=False, **kwargs) as response:
            body = _read(response)
    except requests.RequestException as error:
        raise PlatformUnreachable(f"{method} {url} failed: {type(error).__name__}") from error
    if response.status_code >= 300:
        raise PlatformUnreachable(f"{method} {url} answered {response.status_code}: {body[:200]!r}",
                                  status=response.status_code)
    return response, body


def _json(url: str, body: bytes) -> Any:
    try:
        return json.loads(body)
    except ValueError as error:
        raise PlatformUnreachable(f"{url} answered something that is not JSON") from error


def get_json(url: str, *, headers: dict[str, str] | None = None) -> Any:
    """``GET url`` and its JSON body."""
    return get_page(url, headers=headers)[0]


def get_page(url: str, *, headers: dict[str, str] | None = None) -> tuple[Any, str | None]:
    """``GET url``: its JSON body and the URL of the next page (``Link: <...>; rel="next"``), if any."""
    response, body = _call("GET", url, headers=headers or {})
    return _json(url, body), response.links.get("next", {}).get("url")


def post(url: str, *, headers: dict[str, str] | None = None, data: Any = None, json_body: Any = None) -> Any:
    """``POST url`` (form ``data`` or a JSON body); its JSON answer, or None for an empty one."""
    kwargs: dict[str, Any] = {"headers": dict(headers or {})}
    if json_body is not None:
        kwargs["data"] = json.dumps(json_body)
        kwargs["headers"].setdefault("Content-Type", "application/json")
    else:
        kwargs["data"] = data
    _, body = _call("POST", url, **kwargs)
    return _json(url, body) if body.strip() else None
