"""Failed sign-ins are limited per (account, address) and, looser, per address; timing hides accounts."""

import time

import pytest

from grader.store import users
from grader.store.users import authenticate
from grader.web import security
from grader.web.auth.throttle import account_key
from tests.web.conftest_pages import PASSWORD, accounts, form_token  # noqa: F401  (fixtures)

NAT = "10.0.0.1"  # a campus address many students share


@pytest.fixture
def limits(app):
    # One token a minute: no refill to speak of while a test runs.
    app.config.update(RATE_LIMITS_ENABLED=True,
                      RATE_LIMITS={**app.config["RATE_LIMITS"], "login": (1, 3), "login_address": (1, 6)})
    return app


def _attempt(app, address: str, username: str, password: str):
    browser = app.test_client()
    browser.environ_base["REMOTE_ADDR"] = address
    token = form_token(browser.get("/login").get_data(as_text=True))
    return browser.post("/login", data={"username": username, "password": password, "csrf_token": token})


def test_guessing_one_password_is_refused_but_others_behind_the_same_address_sign_in(limits, accounts):
    assert [_attempt(limits, NAT, "bob@example.org", "guess").status_code for _ in range(4)] == [401, 401, 401, 429]
    assert _attempt(limits, NAT, "ada@example.org", PASSWORD).status_code == 302  # same address, other account
    assert _attempt(limits, "192.0.2.7", "bob@example.org", PASSWORD).status_code == 302  # Bob, elsewhere


def test_a_refusal_says_when_to_retry_and_does_not_check_the_password(limits, accounts, monkeypatch):
    for _ in range(3):
        _attempt(limits, NAT, "bob@example.org", "guess")
    checked = []
    monkeypatch.setattr("grader.web.auth.views.authenticate", lambda *a: checked.append(a))
    refused = _attempt(limits, NAT, "bob@example.org", PASSWORD)  # even the right password
    assert refused.status_code == 429 and int(refused.headers["Retry-After"]) > 0
    assert "Too many failed sign-ins" in refused.get_data(as_text=True) and checked == []


@pytest.mark.parametrize("variant", ["BOB@example.org", "  bob@EXAMPLE.org ", "Bob@Example.Org"])
def test_case_and_spaces_do_not_open_a_fresh_bucket(limits, accounts, variant):
    for _ in range(3):
        _attempt(limits, NAT, "bob@example.org", "guess")
    assert account_key(variant) == account_key("bob@example.org")
    assert _attempt(limits, NAT, variant, "guess").status_code == 429


def test_one_address_trying_many_accounts_is_slowed_down_and_no_other_address(limits, accounts):
    answers = [_attempt(limits, NAT, f"user{i}@example.org", "guess").status_code for i in range(7)]
    assert answers == [401] * 6 + [429]  # the per-address bucket (burst 6) ran out
    assert _attempt(limits, NAT, "ada@example.org", PASSWORD).status_code == 429
    assert _attempt(limits, "192.0.2.7", "ada@example.org", PASSWORD).status_code == 302


def test_successful_sign_ins_cost_nothing(limits, accounts):
    # A lecture signing in at nine from one address: more sign-ins than either burst, all let in.
    for _ in range(8):
        assert _attempt(limits, NAT, "ada@example.org", PASSWORD).status_code == 302


def test_the_limits_live_in_the_shared_storage_not_in_the_process(limits):
    # Two apps (two web processes) on one storage see each other's charges; memory:// is per app,
    # so this holds with LAGRADE_RATELIMIT_STORAGE_URI=redis://... across processes (test_scale_out).
    storage = limits.extensions["lagrade.flask_limiter"].limiter.storage
    with limits.test_request_context():
        for _ in range(3):
            security.limiter.hit("login", ("ada", NAT))
    keys = [k for k in [*storage.events, *storage.storage] if "login" in k]  # memory://: moving windows
    assert keys and all("ada" not in k for k in keys)  # stored, keyed by a digest, not the account name


def test_an_unknown_account_checks_a_password_hash_as_a_known_one_does(database, monkeypatch):
    from werkzeug.security import check_password_hash

    calls = []
    monkeypatch.setattr(users, "check_password_hash", lambda h, p: calls.append(h) or check_password_hash(h, p))
    with database.write() as session:
        users.create_user(session, role="student", name="Ada", email="ada@example.org", password=PASSWORD)
    with database.read() as session:
        assert authenticate(session, "nobody@example.org", PASSWORD) is None
        assert authenticate(session, "ada@example.org", "wrong") is None
    assert len(calls) == 2 and calls[0].split("$")[0] == calls[1].split("$")[0]  # same method and cost


def test_an_unknown_account_answers_as_slowly_as_a_wrong_password(database):
    with database.write() as session:
        users.create_user(session, role="student", name="Ada", email="ada@example.org", password=PASSWORD)

    def fastest(email: str) -> float:  # the minimum of a few runs: least disturbed by other processes
        times = []
        for _ in range(3):
            with database.read() as session:
                start = time.perf_counter()
                authenticate(session, email, "wrong password")
                times.append(time.perf_counter() - start)
        return min(times)

    fastest("nobody@example.org")  # the stand-in hash is made once, on first use
    unknown, known = fastest("nobody@example.org"), fastest("ada@example.org")
    assert 0.5 < unknown / known < 2.0, (unknown, known)
