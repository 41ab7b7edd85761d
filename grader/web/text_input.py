"""Form fields and query parameters hold text: a NUL character in any of them is a 400, for every page.
A path segment holding one (``/problems/a%00b``) names nothing: 404, on the pages and the API alike.

PostgreSQL cannot hold NUL in text, nor take it as a query parameter: a sign-in name or a typed
answer carrying ``%00`` reached it and was a 500, and so was every id in a URL (a problem's, a
course's, an assignment's). JSON bodies are checked by the API's own parser
(:mod:`grader.web.api.bodies`); this covers paths, forms and query strings, in one place.
"""

from __future__ import annotations

from flask import Flask, abort, request

__all__ = ["init_app"]


def _refuse_nul() -> None:
    if any(isinstance(value, str) and "\x00" in value for value in (request.view_args or {}).values()):
        abort(404, "The address holds a NUL character: it names nothing here.")
    fields = list(request.args.values())
    if request.method in ("POST", "PUT", "PATCH") and request.mimetype in (
            "application/x-www-form-urlencoded", "multipart/form-data"):
        fields += request.form.values()
    if any("\x00" in value for value in fields):
        abort(400, "A field holds a NUL character, which is not text.")


def init_app(app: Flask) -> None:
    app.before_request(_refuse_nul)
