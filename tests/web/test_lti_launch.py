"""LTI 1.3 launches end to end against the stand-in platform: a learner lands on the problem, and
every launch that cannot be trusted is refused with a page saying why (4xx, never a 500)."""

from __future__ import annotations

import base64
import json
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from sqlalchemy import select

from grader.store.lti_models import LtiAccount, LtiContext, LtiLaunch, LtiNonce, LtiResourceLink
from grader.store.models import Enrolment, User
from grader.web.lti.launch import STATE_COOKIE
from tests.web.lti_platform import (CLAIM, CLIENT_ID, INSTRUCTOR, launch, lms, login, rsa_key,  # noqa: F401
                                    tool)


def _db(app):
    return app.extensions["lagrade.db"]


def test_a_learner_launch_signs_in_enrols_and_opens_the_problem(tool, lms):
    client = tool.test_client()
    response, _ = launch(client, lms)
    assert response.status_code == 302 and response.headers["Location"] == "/problems/yoyo"
    page = client.get("/problems/yoyo")
    assert page.status_code == 200 and "Yo-yo" in page.get_data(as_text=True)
    with _db(tool).read() as session:
        account = session.scalar(select(LtiAccount).where(LtiAccount.sub == "student-1"))
        user = session.get(User, account.user_id)
        context = session.scalar(select(LtiContext).where(LtiContext.context_id == "course-7"))
        enrolment = session.scalar(select(Enrolment).where(Enrolment.user_id == user.id))
        link = session.scalar(select(LtiResourceLink))
        assert (user.role, user.name, user.password_hash) == ("student", "Ada Lovelace", None)
        assert (enrolment.course_id, enrolment.role) == (context.course_id, "student")
        assert link.problem.slug == "yoyo" and link.lineitem_url == lms.url("/lineitems/1")
        assert session.scalar(select(LtiLaunch.user_id)) == user.id


def test_the_login_redirect_carries_state_nonce_and_our_launch_url(tool, lms):
    client = tool.test_client()
    response = login(client, lms)
    location = response.headers["Location"]
    assert location.startswith(lms.url("/auth?"))
    for part in ("response_mode=form_post", "redirect_uri=http%3A%2F%2Flocalhost%2Flti%2Flaunch", "nonce=", "state="):
        assert part in location
    cookie = response.headers["Set-Cookie"]
    assert cookie.startswith(STATE_COOKIE) and "HttpOnly" in cookie and "Path=/lti" in cookie


def test_a_second_launch_of_the_same_person_reuses_their_account(tool, lms):
    launch(tool.test_client(), lms)
    response, _ = launch(tool.test_client(), lms)
    assert response.status_code == 302
    with _db(tool).read() as session:
        assert len(session.scalars(select(LtiAccount)).all()) == 1
        assert len(session.scalars(select(LtiContext)).all()) == 1


def test_an_instructor_launch_opens_the_instructor_page_of_the_problem(tool, lms):
    client = tool.test_client()
    response, _ = launch(client, lms, {"sub": "teacher-1", CLAIM + "roles": [INSTRUCTOR]})
    assert response.status_code == 302 and response.headers["Location"] == "/instructor/problems/yoyo"
    assert client.get("/instructor/problems/yoyo").status_code == 200


REFUSALS = [
    pytest.param({"aud": "another-tool"}, 403, "meant for another tool", id="wrong aud"),
    pytest.param({"aud": [CLIENT_ID, "another-tool"]}, 403, "authorised party", id="several audiences, no azp"),
    pytest.param({"exp": int(time.time()) - 3600, "iat": int(time.time()) - 3900}, 403, "expired", id="expired"),
    pytest.param({"iat": int(time.time()) + 3600}, 403, "in the future", id="issued in the future"),
    pytest.param({"iss": "https://impostor.example.org"}, 403, "issuer", id="other issuer"),
    pytest.param({"nonce": "not-the-one-we-issued"}, 403, "nonce", id="another nonce"),
    pytest.param({CLAIM + "deployment_id": "unknown"}, 403, "deployment", id="unregistered deployment"),
    pytest.param({CLAIM + "version": "1.1"}, 400, "1.3.0", id="wrong version"),
    pytest.param({CLAIM + "message_type": "LtiSubmissionReviewRequest"}, 400, "serves", id="unknown message"),
    pytest.param({"sub": None}, 400, "names no user", id="anonymous"),
    pytest.param({CLAIM + "custom": {"problem": "no-such-problem"}}, 404, "not connected", id="link to nothing"),
    pytest.param({CLAIM + "custom": {}, CLAIM + "roles": [INSTRUCTOR], CLAIM + "message_type": "LtiDeepLinkingRequest"},
                 400, "deep_linking_settings", id="deep linking without settings"),
]


@pytest.mark.parametrize("claims, status, words", REFUSALS)
def test_an_untrustworthy_launch_is_refused_with_a_page_saying_why(tool, lms, claims, status, words):
    client = tool.test_client()
    response, _ = launch(client, lms, claims)
    text = response.get_data(as_text=True)
    assert response.status_code == status and words in text, text[-600:]
    assert response.mimetype == "text/html"
    assert client.get("/problems").status_code == 302  # nobody was signed in


def test_a_token_signed_with_another_key_is_refused_as_forged(tool, lms):
    lms.sign_with = rsa_key(lms.key.kid)  # the platform's key id, an attacker's key
    client = tool.test_client()
    response, _ = launch(client, lms)
    assert response.status_code == 403 and "forged" in response.get_data(as_text=True)
    assert client.get("/problems").status_code == 302


def test_a_replayed_launch_is_refused_even_with_its_state_cookie(tool, lms):
    client = tool.test_client()
    first, form = launch(client, lms)
    assert first.status_code == 302
    attacker = tool.test_client()
    started = login(attacker, lms)  # any cookie would do; the one the first launch was bound to:
    attacker.set_cookie(STATE_COOKIE + form["state"], _state_cookie(client, lms, form), path="/lti")
    replay = attacker.post("/lti/launch", data=form)
    assert started.status_code == 302
    assert replay.status_code == 403 and "used already" in replay.get_data(as_text=True)
    assert attacker.get("/problems").status_code == 302
    with _db(tool).read() as session:
        assert len(session.scalars(select(LtiNonce)).all()) == 1


def _state_cookie(client, lms, form) -> str:
    """The signed state cookie that the tool gave the first browser for ``form``'s state."""
    from grader.store.lti_models import LtiPlatform
    from grader.web.lti.launch import _serializer  # the tool's own signing of the state

    with _db(client.application).read() as session:
        platform_id = session.scalar(select(LtiPlatform.id))
    bound = {"state": form["state"], "nonce": _nonce_of(form["id_token"]), "platform": platform_id}
    return _serializer(client.application.secret_key).dumps(bound)


def _nonce_of(token: str) -> str:
    from grader.web.lti.launch import _unverified

    return _unverified(token)[1]["nonce"]


def test_a_launch_without_the_state_cookie_is_refused(tool, lms):
    client = tool.test_client()
    lms.next_launch = {}
    started = login(client, lms)
    import requests

    from tests.web.lti_platform import auto_post_form

    form = auto_post_form(requests.get(started.headers["Location"], timeout=10).text)
    stranger = tool.test_client()  # another browser: no state cookie
    response = stranger.post("/lti/launch", data=form)
    assert response.status_code == 400 and "did not start in this browser" in response.get_data(as_text=True)


@pytest.mark.parametrize("params, status, words", [
    ({"iss": "https://unknown-lms.example.org"}, 403, "not registered"),
    ({"client_id": "someone-else"}, 403, "not registered"),
    ({"lti_deployment_id": "unknown"}, 403, "deployment"),
    ({"target_link_uri": "https://evil.example.org/lti/launch"}, 400, "another site"),
    ({"login_hint": None}, 400, "login_hint"),
])
def test_a_login_from_an_unknown_lms_or_for_another_site_is_refused(tool, lms, params, status, words):
    response = login(tool.test_client(), lms, **params)
    assert response.status_code == status and words in response.get_data(as_text=True)


def test_login_and_launch_take_the_lms_post_without_our_csrf_token(tool, lms):
    client = tool.test_client()
    response = client.post("/lti/login", data={"iss": lms.issuer, "login_hint": "h", "target_link_uri": TOOL,
                                               "client_id": CLIENT_ID})
    assert response.status_code == 302  # not the 400 of a missing CSRF token


TOOL = "http://localhost/lti/launch"


def test_an_unreachable_jwks_is_a_502_page_not_a_500(tool, lms):
    from grader.store.lti_models import LtiPlatform

    with _db(tool).write() as session:
        session.scalar(select(LtiPlatform)).jwks_url = "http://127.0.0.1:9/jwks"  # nothing listens on port 9
    response, _ = launch(tool.test_client(), lms)
    assert response.status_code == 502 and "could not be reached" in response.get_data(as_text=True)


def test_a_platform_key_rotation_is_followed_by_one_refetch_of_its_jwks(tool, lms, monkeypatch):
    from grader.web.lti import platforms
    from tests.web.lti_platform import shared_key

    monkeypatch.setattr(platforms, "REFRESH_MIN_S", 0.0)
    assert launch(tool.test_client(), lms)[0].status_code == 302
    assert launch(tool.test_client(), lms)[0].status_code == 302
    assert lms.jwks_fetches == 1  # cached
    lms.key = shared_key("platform-key-2")  # the LMS rotates its key
    assert launch(tool.test_client(), lms)[0].status_code == 302
    assert lms.jwks_fetches == 2


def test_unknown_key_ids_do_not_make_the_tool_refetch_the_jwks_each_time(tool, lms):
    from tests.web.lti_platform import shared_key

    assert launch(tool.test_client(), lms)[0].status_code == 302
    for _ in range(3):
        lms.sign_with = shared_key("attacker")
        lms.key, real = shared_key("made-up-kid"), lms.key  # a header kid the cache does not know
        response, _ = launch(tool.test_client(), lms)
        lms.key = real
        assert response.status_code == 403
    assert lms.jwks_fetches == 1  # at most one refetch every REFRESH_MIN_S (10 s)


def test_a_link_to_a_problem_the_learner_may_not_see_is_a_404_page_by_the_policy(tool, lms):
    from grader.store.models import ProblemVersion

    with _db(tool).write() as session:
        session.scalar(select(ProblemVersion)).published = False  # a draft: only its managers see it
    client = tool.test_client()
    response, _ = launch(client, lms)
    assert response.status_code == 404 and "There is no problem" in response.get_data(as_text=True)
    assert client.get("/problems").status_code == 302  # not signed in


def test_an_error_the_lms_posts_back_is_shown_not_followed(tool, lms):
    client = tool.test_client()
    response = client.post("/lti/launch", data={"error": "login_required",
                                                "error_description": "Sign in to the LMS first."})
    assert response.status_code == 403 and "Sign in to the LMS first." in response.get_data(as_text=True)



def _segment(value) -> str:
    return base64.urlsafe_b64encode(json.dumps(value).encode()).decode().rstrip("=")


JSON = st.recursive(st.none() | st.integers() | st.text(max_size=20),
                    lambda children: st.lists(children, max_size=3) | st.dictionaries(
                        st.sampled_from(["iss", "aud", "exp", "iat", "nonce", "sub", "kid", "alg", "azp",
                                         CLAIM + "deployment_id", CLAIM + "version"]), children, max_size=5),
                    max_leaves=8)
TOKENS = st.one_of(st.text(max_size=60), st.tuples(JSON, JSON, st.text(max_size=10)))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(token=TOKENS, ours=st.booleans(), extra=st.dictionaries(
    st.sampled_from(["error", "error_description", "state"]), st.text(max_size=30), max_size=2))
def test_any_posted_launch_is_refused_with_a_4xx_page_never_a_500(tool, lms, token, ours, extra):
    from grader.store.lti_models import LtiPlatform
    from grader.web.lti.launch import _serializer

    client = tool.test_client()
    with _db(tool).read() as session:
        platform_id = session.scalar(select(LtiPlatform.id))
    # A state cookie the tool really issued, so the token itself is what gets judged.
    client.set_cookie(STATE_COOKIE + "s1", _serializer(tool.secret_key).dumps(
        {"state": "s1", "nonce": "n1", "platform": platform_id}), path="/lti")
    if isinstance(token, tuple):  # header and claims of any shape, maybe naming our platform and its key
        header, claims, signature = token
        if ours and isinstance(header, dict) and isinstance(claims, dict):
            header, claims = {**header, "kid": lms.key.kid}, {**claims, "iss": lms.issuer}
        token = f"{_segment(header)}.{_segment(claims)}.{signature}"
    response = client.post("/lti/launch", data={"state": "s1", "id_token": token, **extra})
    assert 400 <= response.status_code < 500, response.get_data(as_text=True)[-400:]


def test_a_launch_whose_id_another_account_holds_is_refused_with_a_page_not_a_500(tool, lms):
    # made before such ids were reserved (an LMS token or a roster naming "lti:<sha256>"): the person
    # is told what to ask for, and the other account is never handed to them
    from grader.store.lti_models import LtiPlatform
    from grader.web.lti.accounts import external_id

    with _db(tool).write() as session:
        issuer = session.scalar(select(LtiPlatform.issuer))
        session.add(User(role="student", name="squatter", external_id=external_id(issuer, "student-1")))
    response, _ = launch(tool.test_client(), lms)
    assert response.status_code == 409
    assert "held by another account" in response.get_data(as_text=True)
    with _db(tool).read() as session:
        assert session.scalar(select(LtiAccount)) is None
