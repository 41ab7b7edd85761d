"""Where ``/login?next=`` may send a user back to: a path on this site, parsed and normalised.

A browser reading a ``Location`` header drops tabs and newlines anywhere in it, reads ``\\`` as ``/`` and
``//host`` as another site, so ``/%09/evil.example/`` (a tab between the slashes) leaves the site and a
newline breaks the header itself. Rather than list the tricks, :func:`safe_next` keeps only what parses
as a path without scheme or host, rebuilds it from its parts and percent-encodes it, so what the browser
reads is what was checked.
"""

from __future__ import annotations

import re
from urllib.parse import quote, urlsplit

__all__ = ["MAX_NEXT_LENGTH", "safe_next"]

MAX_NEXT_LENGTH = 2048
# ASCII control characters (tab, CR, LF among them) and the backslash: browsers drop or reinterpret them.
_REFUSED = re.compile(r"[\x00-\x1f\x7f\\]")
# Characters left as they are when re-encoding; everything else (spaces, non-ASCII...) is percent-encoded.
_PATH_SAFE = "/%:@!$&'()*+,;=-._~"
_QUERY_SAFE = _PATH_SAFE + "?"


def safe_next(url: str | None) -> str:
    """``url`` as a same-site path to redirect to, or ``""`` when it is anything else.

    Parameters
    ----------
    url : str or None
        The ``next`` value as received (already percent-decoded once by the query-string parser).

    Returns
    -------
    str
        A path starting with a single ``/``, with dot segments resolved and unsafe characters
        percent-encoded; ``""`` for a URL with a scheme or host, control characters, backslashes,
        or more than ``MAX_NEXT_LENGTH`` characters.

    Examples
    --------
    >>> safe_next("/problems/sphere?tab=answers")
    '/problems/sphere?tab=answers'
    >>> safe_next("/\\t/evil.example/"), safe_next("//evil.example"), safe_next("https://evil.example/")
    ('', '', '')
    >>> safe_next("/problems/../problèmes/a b")
    '/probl%C3%A8mes/a%20b'
    """
    if (not isinstance(url, str) or not url.startswith("/") or url.startswith("//")
            or len(url) > MAX_NEXT_LENGTH or _REFUSED.search(url)):
        return ""
    try:
        parts = urlsplit(url)
    except ValueError:  # e.g. an unbalanced "[" read as an IPv6 host
        return ""
    if parts.scheme or parts.netloc or not parts.path.startswith("/"):
        return ""
    path = _resolve_dots(re.sub(r"/{2,}", "/", parts.path))
    target = quote(path, safe=_PATH_SAFE)
    if parts.query:
        target += "?" + quote(parts.query, safe=_QUERY_SAFE)
    return target


def _resolve_dots(path: str) -> str:
    """``path`` with ``.`` and ``..`` segments resolved (RFC 3986, 5.2.4), never above the root."""
    segments: list[str] = []
    for segment in path.split("/")[1:]:
        if segment == "..":
            if segments:
                segments.pop()
        elif segment != ".":
            segments.append(segment)
    trailing = path.endswith(("/", "/.", "/..")) and segments and segments[-1] != ""
    return "/" + "/".join(segments) + ("/" if trailing else "")
