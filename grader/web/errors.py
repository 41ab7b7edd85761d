"""Errors as ``application/problem+json`` (RFC 9457) for the API, and no stack trace for anyone.

Raise :class:`ApiProblem` anywhere in a request; HTTP errors (``abort(404)``) and unexpected
exceptions under ``/api/`` become problem documents too. An unexpected exception is logged with its
trace and answered with a generic 500, in JSON or HTML.
"""

from __future__ import annotations

import logging
from http import HTTPStatus
from typing import Any

from flask import Flask, Response, current_app, json, render_template, request
from werkzeug.exceptions import HTTPException, InternalServerError, UnprocessableEntity

from grader.store.lengths import StoredValueError

__all__ = ["ApiProblem", "init_app", "problem_response", "wants_problem_json"]

log = logging.getLogger(__name__)

PROBLEM_JSON = "application/problem+json"


class ApiProblem(Exception):
    """An error answered as a problem document.

    Parameters
    ----------
    status : the HTTP status.
    detail : what went wrong with this request, in words for the client.
    kind : a short slug naming the kind of problem (its ``type`` is ``urn:lagrade:error:<kind>``);
        None means the plain HTTP meaning of ``status`` (``about:blank``).
    headers : extra response headers (``Retry-After``, ``WWW-Authenticate``).
    extensions : extra members of the document (``errors``, ``submission``...).
    """

    def __init__(self, status: int, detail: str, *, kind: str | None = None, title: str | None = None,
                 headers: dict[str, str] | None = None, **extensions: Any):
        super().__init__(detail)
        self.status, self.detail, self.kind = status, detail, kind
        self.title = title or HTTPStatus(status).phrase
        self.headers = headers or {}
        self.extensions = extensions


def problem_response(status: int, detail: str, *, kind: str | None = None, title: str | None = None,
                     headers: dict[str, str] | None = None, **extensions: Any) -> Response:
    body = {
        "type": f"urn:lagrade:error:{kind}" if kind else "about:blank",
        "title": title or HTTPStatus(status).phrase,
        "status": status,
        "detail": detail,
        "instance": request.path,
        **extensions,
    }
    response = Response(json.dumps(body), status=status, mimetype=PROBLEM_JSON)
    response.headers.update(headers or {})
    return response


def wants_problem_json() -> bool:
    return request.blueprint == "api" or request.path.startswith("/api/")


def init_app(app: Flask) -> None:
    from grader.web.server_refusals import refuse_early

    # First of the app's before_request functions: a request the server refused reaches no view.
    app.before_request(refuse_early)

    @app.errorhandler(ApiProblem)
    def _api_problem(error: ApiProblem):
        return problem_response(error.status, error.detail, kind=error.kind, title=error.title,
                                headers=error.headers, **error.extensions)

    @app.errorhandler(StoredValueError)
    def _unstorable(error: StoredValueError):
        # Inputs are capped before this (schemas); a value that still does not fit its column is the
        # client's data, not a server failure.
        detail = f"A value cannot be stored: {error}."
        if wants_problem_json():
            return problem_response(422, detail, kind="invalid-request")
        return _html_page(UnprocessableEntity(detail))

    @app.errorhandler(HTTPException)
    def _http_error(error: HTTPException):
        if not wants_problem_json():
            return _html_page(error)
        headers = {k: v for k, v in error.get_headers() if k.lower() not in ("content-type", "content-length")}
        return problem_response(error.code or 500, error.description or "", headers=headers)

    @app.errorhandler(Exception)
    def _unexpected(error: Exception):
        log.exception("unhandled error in %s %s", request.method, request.path)
        detail = "The server could not complete this request; the error was logged."
        if wants_problem_json():
            return problem_response(500, detail)
        return _html_page(InternalServerError(detail))


def _html_page(error: HTTPException):
    """The pages' own error template when the HTML blueprints are there, else Werkzeug's plain page."""
    app = current_app
    if "auth" not in app.blueprints or "errors/error.html" not in app.jinja_env.list_templates():
        return error
    try:
        page = render_template("errors/error.html", code=error.code, title=HTTPStatus(error.code).phrase,
                               message=error.description)
    except Exception:  # the error page itself failed: fall back rather than raise from a handler
        log.exception("rendering the error page failed")
        return error
    return page, error.code, {k: v for k, v in error.get_headers() if k.lower() != "content-type"}
