"""The HTTP server's own refusals answered by the app, in the app's words and headers.

waitress refuses some requests before the app sees them: a body over its cap (from the
Content-Length, unread, or as a chunked body grows), a header it cannot parse (a DEL character in
``Authorization``). Its answer is ``text/plain`` without the security headers, where every other
error under ``/api/`` is a problem document and every page has a Content-Security-Policy.

:func:`create_server` keeps waitress's refusal (the body is still not read) but has the app write
the answer: the request, reduced to its method and path, goes through the app with the refusal in
``environ[REFUSAL]``, and :func:`refuse_early` (a ``before_request`` of :mod:`grader.web.errors`)
aborts it before any view, sign-in or rate limit: the app's error handlers answer, a problem
document under ``/api/`` and a page elsewhere, with the headers every response gets.
"""

from __future__ import annotations

import logging

from flask import Flask, abort, current_app, request
from waitress.channel import HTTPChannel
from waitress.parser import crack_first_line, split_uri
from waitress.task import ErrorTask
from werkzeug.test import EnvironBuilder, run_wsgi_app

__all__ = ["REFUSAL", "create_server", "refuse_early"]

log = logging.getLogger(__name__)

REFUSAL = "lagrade.server_refusal"  # environ key: (status, why); set only by the server, never from a header


def refuse_early() -> None:
    """Abort a request the server refused, with its status, before anything else reads it."""
    refusal = request.environ.get(REFUSAL)
    if refusal is None:
        return
    status, why = refusal
    if status == 413:
        limit = current_app.config["MAX_CONTENT_LENGTH"]
        abort(413, f"A request body may be at most {limit // 1024} KiB.")
    abort(status, f"The server could not read this request: {why}.")


def _method_and_path(parsed) -> tuple[str, str]:
    """The method and path of a request waitress refused, as far as it read them."""
    path, method = getattr(parsed, "path", None), getattr(parsed, "command", None)
    if not path:  # a bad header stops waitress before it splits the first line
        try:
            command, uri, _ = crack_first_line(parsed.first_line)
            method, path = command.decode("latin-1"), split_uri(uri)[2]
        except Exception:  # no readable first line: the refusal is still answered, at the root
            return "GET", "/"
    method = method if method and method.isalpha() and method.isupper() else "GET"
    return method, path or "/"


class _AppErrorTask(ErrorTask):
    """waitress's error response, written by the app (:func:`refuse_early`)."""

    def execute(self):
        error = self.request.error
        try:
            status, headers, body = self._answer(error)
        except Exception:  # the app failed to answer: waitress's own words rather than none
            log.exception("answering a refused request through the app failed")
            return super().execute()
        self.status = status
        self.response_headers.extend(headers)
        self.set_close_on_finish()
        self.content_length = len(body)
        self.write(body)

    def _answer(self, error) -> tuple[str, list[tuple[str, str]], bytes]:
        method, path = _method_and_path(self.request)
        adj = self.channel.server.adj
        environ = EnvironBuilder(method=method, base_url=f"{adj.url_scheme}://{adj.host or 'localhost'}",
                                 headers={}).get_environ()
        environ.update({"PATH_INFO": path, "REMOTE_ADDR": str(self.channel.addr[0]) if self.channel.addr else "",
                        REFUSAL: (error.code, error.reason.lower() + (f" ({error.body})" if error.body else ""))})
        app_iter, status, headers = run_wsgi_app(self.channel.server.application, environ, buffered=True)
        body = b"".join(app_iter)
        kept = [(k, v) for k, v in headers.items() if k.lower() not in ("content-length", "connection")]
        return status, kept, body if method != "HEAD" else b""


class _Channel(HTTPChannel):
    error_task_class = _AppErrorTask


def create_server(app: Flask, **options):
    """``waitress.create_server(app, **options)`` whose refusals the app answers (see the module)."""
    import waitress

    server = waitress.create_server(app, **options)
    server.channel_class = _Channel
    return server
