"""``/account``: a signed-in user changes their own password (the current one first, the new one twice),
as slowly as sign-ins allow guesses; other browsers are signed out, this one stays."""

import pytest

from grader.store.users import authenticate
from tests.web.conftest_pages import PASSWORD, accounts, as_student, csrf, sign_in  # noqa: F401  (fixtures)

NEW = "a new passphrase"


def _change(client, current=PASSWORD, new=NEW, again=None, with_token=True):
    data = {"current": current, "new": new, "again": new if again is None else again}
    if with_token:
        data["csrf_token"] = csrf(client)
    return client.post("/account", data=data)


def _signs_in(app, email, password) -> bool:
    with app.extensions["lagrade.db"].read() as session:
        return authenticate(session, email, password) is not None


def test_the_account_page_says_how_one_signs_in_and_links_from_every_page(as_student):
    page = as_student.get("/account").get_data(as_text=True)
    assert "ada@example.org" in page and 'name="current"' in page and 'autocomplete="new-password"' in page
    assert 'href="/account"' in as_student.get("/problems").get_data(as_text=True)


def test_a_changed_password_signs_in_the_old_one_no_longer(app, as_student):
    response = _change(as_student)
    assert response.status_code == 302 and response.headers["Location"] == "/account"
    assert "Your password is changed" in as_student.get("/account").get_data(as_text=True)
    assert _signs_in(app, "ada@example.org", NEW) and not _signs_in(app, "ada@example.org", PASSWORD)


def test_other_browsers_are_signed_out_and_this_one_stays(app, accounts, as_student):
    elsewhere = app.test_client()
    sign_in(elsewhere, accounts["ada"])
    assert elsewhere.get("/problems").status_code == 200
    _change(as_student)
    assert as_student.get("/problems").status_code == 200
    assert elsewhere.get("/problems").status_code == 302  # to the sign-in page


@pytest.mark.parametrize("current, new, again, status, message", [
    ("wrong password", NEW, NEW, 403, "not your current password"),
    (PASSWORD, "short", "short", 422, "at least 10 characters"),
    (PASSWORD, NEW, NEW + "!", 422, "two new passwords differ"),
    (PASSWORD, "", "", 422, "Fill in all three fields"),
    ("", NEW, NEW, 422, "Fill in all three fields"),
    (PASSWORD, "x" * 1025, "x" * 1025, 422, "at most 1024 characters"),
])
def test_a_refused_change_says_why_and_changes_nothing(app, as_student, current, new, again, status, message):
    response = _change(as_student, current, new, again)
    assert response.status_code == status and message in response.get_data(as_text=True)
    assert 'role="alert"' in response.get_data(as_text=True)
    assert _signs_in(app, "ada@example.org", PASSWORD)


def test_changing_needs_the_csrf_token_and_a_session(app, client, as_student):
    assert _change(as_student, with_token=False).status_code == 400
    assert client.post("/account", data={"current": PASSWORD, "new": NEW, "again": NEW}).status_code in (400, 401)
    assert client.get("/account").headers["Location"] == "/login?next=/account"
    assert _signs_in(app, "ada@example.org", PASSWORD)


def test_guessing_the_current_password_is_throttled_like_signing_in(app, as_student):
    app.config.update(RATE_LIMITS_ENABLED=True,
                      RATE_LIMITS={**app.config["RATE_LIMITS"], "login": (1, 3), "login_address": (1, 6)})
    statuses = [_change(as_student, current=f"guess {n}").status_code for n in range(4)]
    assert statuses == [403, 403, 403, 429]
    refused = _change(as_student)  # even the right password waits now
    assert refused.status_code == 429 and "Retry-After" in refused.headers
    assert _signs_in(app, "ada@example.org", PASSWORD)



def test_an_account_that_signs_in_through_an_lms_has_no_password_to_change(app):
    from grader.store.users import create_user
    from grader.web.auth.session import _password_stamp

    with app.extensions["lagrade.db"].write() as session:
        user = create_user(session, role="student", name="From the LMS", external_id="lms-42")
        user_id, stamp = user.id, _password_stamp(user)
    browser = app.test_client()
    with browser.session_transaction() as cookie:  # what an LTI launch leaves behind
        cookie.update(user_id=user_id, stamp=stamp)
    page = browser.get("/account")
    assert page.status_code == 200 and "LMS; it has no password here" in page.get_data(as_text=True)
    assert 'name="current"' not in page.get_data(as_text=True)
    refused = browser.post("/account", data={"current": "", "new": NEW, "again": NEW, "csrf_token": csrf(browser)})
    assert refused.status_code == 403
    with app.extensions["lagrade.db"].read() as session:
        from grader.store.models import User

        assert session.get(User, user_id).password_hash is None
