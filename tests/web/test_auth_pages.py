"""Signing in and out: session cookie, role homes, CSRF, no account enumeration, friendly errors."""

import pytest

from grader.store.models import User
from grader.store.users import create_user, set_password
from tests.web.conftest_pages import PASSWORD, accounts, as_student, csrf, form_token, sign_in  # noqa: F401


def test_the_sign_in_page_has_a_form_with_a_csrf_token(client):
    page = client.get("/login")
    assert page.status_code == 200
    html = page.get_data(as_text=True)
    assert 'name="username"' in html and 'name="password"' in html and form_token(html)


@pytest.mark.parametrize("who, home", [("ada", "/problems"), ("ine", "/instructor/")])
def test_each_role_lands_on_its_own_home(client, accounts, who, home):
    response = sign_in(client, accounts[who])
    assert response.status_code == 302 and response.headers["Location"] == home
    assert client.get("/").headers["Location"] == home


def test_a_wrong_password_and_an_unknown_user_get_the_same_answer(client, accounts):
    token = form_token(client.get("/login").get_data(as_text=True))
    wrong = client.post("/login", data={"username": "ada@example.org", "password": "nope", "csrf_token": token})
    unknown = client.post("/login", data={"username": "nobody@example.org", "password": "nope", "csrf_token": token})
    assert wrong.status_code == unknown.status_code == 401
    assert "do not match an account" in wrong.get_data(as_text=True)
    assert wrong.get_data(as_text=True).replace("ada@", "X@") == unknown.get_data(as_text=True).replace("nobody@", "X@")


def test_signing_in_without_the_csrf_token_is_refused(client, accounts):
    client.get("/login")
    response = client.post("/login", data={"username": "ada@example.org", "password": PASSWORD})
    assert response.status_code == 400
    assert client.get("/problems").status_code == 302  # still signed out


def test_a_page_asked_for_while_signed_out_comes_back_after_signing_in(client, accounts):
    response = client.get("/problems")
    assert response.status_code == 302 and response.headers["Location"] == "/login?next=/problems"
    token = form_token(client.get("/login?next=/problems").get_data(as_text=True))
    back = client.post("/login?next=/problems", data={"username": "ada@example.org", "password": PASSWORD,
                                                      "csrf_token": token})
    assert back.headers["Location"] == "/problems"


@pytest.mark.parametrize("target", ["//evil.example/x", "https://evil.example/", "/\\evil.example"])
def test_next_never_leads_off_the_site(client, accounts, target):
    token = form_token(client.get("/login").get_data(as_text=True))
    response = client.post("/login", query_string={"next": target},
                           data={"username": "ada@example.org", "password": PASSWORD, "csrf_token": token})
    assert response.headers["Location"] == "/problems"


def test_signing_out_needs_a_post_with_the_token(as_student):
    assert as_student.get("/logout").status_code == 405
    assert as_student.post("/logout").status_code == 400
    assert as_student.get("/problems").status_code == 200
    assert as_student.post("/logout", data={"csrf_token": csrf(as_student)}).status_code == 302
    assert as_student.get("/problems").status_code == 302


def test_an_lms_account_cannot_sign_in_on_the_pages(app, client):
    with app.extensions["lagrade.db"].write() as session:
        create_user(session, role="lms", name="Moodle", email="lms@example.org", password=PASSWORD)
    token = form_token(client.get("/login").get_data(as_text=True))
    response = client.post("/login", data={"username": "lms@example.org", "password": PASSWORD, "csrf_token": token})
    assert response.status_code == 401


def test_changing_the_password_signs_out_other_browsers(app, as_student, accounts):
    assert as_student.get("/problems").status_code == 200
    with app.extensions["lagrade.db"].write() as session:
        set_password(session.get(User, accounts["ada"].id), "a new password")
    assert as_student.get("/problems").status_code == 302


def test_errors_are_friendly_pages_without_a_trace(app, client):
    def boom():
        raise RuntimeError("secret internals")

    app.add_url_rule("/boom", "boom", boom)
    missing = client.get("/no/such/page")
    assert missing.status_code == 404 and "Not Found" in missing.get_data(as_text=True)
    assert 'class="error-page"' in missing.get_data(as_text=True)
    crashed = client.get("/boom")
    body = crashed.get_data(as_text=True)
    assert crashed.status_code == 500 and 'class="error-page"' in body
    assert "Traceback" not in body and "secret internals" not in body and "RuntimeError" not in body
