"""Errors are RFC 9457 problem documents under /api/, and no client ever sees a stack trace."""

import logging

import pytest

PROBLEM_MEMBERS = {"type", "title", "status", "detail", "instance"}


@pytest.mark.parametrize("method, url, status", [
    ("GET", "/api/v1/nothing-here", 404),
    ("DELETE", "/api/v1/problems", 405),
    ("GET", "/api/v1/problems", 401),
])
def test_http_errors_under_the_api_are_problem_documents(client, method, url, status):
    response = client.open(url, method=method)
    assert response.status_code == status
    assert response.mimetype == "application/problem+json"
    body = response.get_json()
    assert PROBLEM_MEMBERS <= set(body) and body["status"] == status and body["instance"] == url


@pytest.fixture
def broken_app(app):
    @app.get("/api/v1/boom")
    def boom():
        raise RuntimeError("secret internals: /etc/passwd line 42")

    @app.get("/boom")
    def page_boom():
        raise RuntimeError("secret internals: /etc/passwd line 42")

    app.config["PROPAGATE_EXCEPTIONS"] = False
    return app


@pytest.mark.parametrize("url, mimetype", [("/api/v1/boom", "application/problem+json"), ("/boom", "text/html")])
def test_an_unexpected_error_is_logged_and_answered_without_details(broken_app, caplog, url, mimetype):
    with caplog.at_level(logging.ERROR):
        response = broken_app.test_client().get(url)
    text = response.get_data(as_text=True)
    assert response.status_code == 500 and response.mimetype == mimetype
    assert "secret internals" not in text and "Traceback" not in text and "RuntimeError" not in text
    assert "secret internals" in caplog.text  # the trace went to the log


def test_an_api_500_is_a_problem_document_with_a_generic_detail(broken_app):
    body = broken_app.test_client().get("/api/v1/boom").get_json()
    assert body["status"] == 500 and body["title"] == "Internal Server Error"
    assert "logged" in body["detail"]


def test_pages_keep_html_errors(client):
    response = client.get("/no-such-page")
    assert response.status_code == 404 and response.mimetype == "text/html"


# -- refusals of the HTTP server itself (`grader serve` runs waitress) --------------------------

MIB = 1024 * 1024


@pytest.fixture
def served(app):
    """The app behind waitress as `grader serve` makes it (its body cap just over the app's): a port."""
    import threading

    from waitress import wasyncore as asyncore

    from grader.web.server_refusals import create_server

    server = create_server(app, host="127.0.0.1", port=0, threads=2,
                           max_request_body_size=app.config["MAX_CONTENT_LENGTH"] + 1)
    stopping = threading.Event()

    def run():
        try:
            server.run()
        except OSError:
            # the sockets closed below under a select() in progress (EBADF): the loop's end, not an error
            if not stopping.is_set():
                raise

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    yield server.effective_port
    stopping.set()
    server.task_dispatcher.shutdown()  # the answers written, then the sockets closed: the loop ends
    asyncore.close_all(server._map)
    thread.join(timeout=5)


def _raw(port: int, head: str, body: bytes = b""):
    """Send bytes as a client that writes what it likes (a DEL in a header) and read the answer."""
    import http.client
    import socket

    with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
        try:
            sock.sendall(head.encode("latin-1") + b"\r\n" + body)
        except (BrokenPipeError, ConnectionResetError):
            pass  # the server answered and closed before the whole body was sent
        response = http.client.HTTPResponse(sock)
        response.begin()
        return response.status, response.getheader("Content-Type"), dict(response.getheaders()), response.read()


def _chunked(size: int) -> bytes:
    chunk = b"x" * 65536
    return b"".join(b"%x\r\n%s\r\n" % (len(chunk), chunk) for _ in range(size // len(chunk))) + b"0\r\n\r\n"


# Over the 1 MiB cap waitress refuses the body unread (Content-Length) or as it grows (chunked);
# the answer is the app's: a problem document under /api/, a page elsewhere, the security headers on both.
@pytest.mark.parametrize("path, mimetype", [
    ("/api/v1/check", "application/problem+json"),
    ("/api/v1/problems", "application/problem+json"),
    ("/api/v1/courses/MECH/members", "application/problem+json"),
    ("/instructor/courses", "text/html"),
])
@pytest.mark.parametrize("framing", ["content-length", "chunked"])
def test_a_body_over_the_cap_is_the_apps_413(served, path, mimetype, framing):
    if framing == "chunked":
        head, body = "Transfer-Encoding: chunked\r\n", _chunked(2 * MIB)
    else:
        head, body = f"Content-Length: {2 * MIB}\r\n", b""  # declared, never sent: refused unread
    status, content_type, headers, text = _raw(
        served, f"POST {path} HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\n{head}", body)
    assert status == 413 and content_type.startswith(mimetype)
    assert "Content-Security-Policy" in headers and b"generated by waitress" not in text
    if mimetype == "application/problem+json":
        import json
        problem = json.loads(text)
        assert problem["status"] == 413 and problem["instance"] == path and "at most 1024 KiB" in problem["detail"]


@pytest.mark.parametrize("value", ["Bearer abc\x7fdef", "Bearer \x01abc"])
def test_a_header_the_server_cannot_read_is_the_apis_400_problem(served, value):
    status, content_type, headers, text = _raw(
        served, f"GET /api/v1/courses HTTP/1.1\r\nHost: localhost\r\nAuthorization: {value}\r\n")
    import json
    assert status == 400 and content_type == "application/problem+json"
    assert json.loads(text)["instance"] == "/api/v1/courses" and "Content-Security-Policy" in headers


def test_a_request_the_server_read_is_not_refused_on_its_way_through(served):
    status, content_type, _, _ = _raw(served, "GET /api/v1/courses HTTP/1.1\r\nHost: localhost\r\n")
    assert status == 401 and content_type == "application/problem+json"  # the API's own answer: no token


# Behind a server without a body cap of its own (gunicorn), the app's MAX_CONTENT_LENGTH answers.
@pytest.mark.parametrize("path, content_type", [
    ("/api/v1/check", "application/json"), ("/api/v1/problems", "application/toml"),
    ("/api/v1/courses", "application/json"),
])
def test_the_apps_own_413_is_a_problem_document_under_the_api(client, make_token, path, content_type):
    _, instructor = make_token("instructor")
    response = client.post(path, data=b"x" * (2 * MIB), content_type=content_type, headers=instructor)
    assert response.status_code == 413 and response.mimetype == "application/problem+json"
    assert response.get_json()["status"] == 413 and "Content-Security-Policy" in response.headers


def test_the_apps_own_413_is_a_page_elsewhere(client):
    response = client.post("/login", data=b"x" * (2 * MIB), content_type="application/x-www-form-urlencoded")
    assert response.status_code == 413 and response.mimetype == "text/html"
    assert "Content-Security-Policy" in response.headers
