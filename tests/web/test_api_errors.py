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
