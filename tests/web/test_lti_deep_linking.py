"""Deep Linking end to end: an instructor picks a problem in lagrade, the LMS receives a signed link to
it, and the LMS link then opens that problem for students."""

from __future__ import annotations

import re

import pytest

from tests.web.conftest_pages import form_token
from tests.web.lti_platform import CLAIM, CLIENT_ID, DEPLOYMENT, INSTRUCTOR, launch, lms, tool  # noqa: F401

DL_SETTINGS = "https://purl.imsglobal.org/spec/lti-dl/claim/deep_linking_settings"
CONTENT_ITEMS = "https://purl.imsglobal.org/spec/lti-dl/claim/content_items"


def _deep_linking(lms, **settings):
    return {"sub": "teacher-1", CLAIM + "roles": [INSTRUCTOR], CLAIM + "message_type": "LtiDeepLinkingRequest",
            CLAIM + "resource_link": None, CLAIM + "custom": None,
            DL_SETTINGS: {"deep_link_return_url": lms.url("/deep_link_return"), "accept_types": ["ltiResourceLink"],
                          "data": "opaque-42", **settings}}


def test_an_instructor_picks_a_problem_and_the_lms_receives_a_signed_link(tool, lms):
    import requests

    client = tool.test_client()
    response, _ = launch(client, lms, _deep_linking(lms))
    assert response.status_code == 302 and response.headers["Location"] == "/lti/deep-link"
    page = client.get("/lti/deep-link")
    assert page.status_code == 200 and 'value="yoyo"' in page.get_data(as_text=True)
    answer = client.post("/lti/deep-link", data={"problem": "yoyo", "csrf_token": form_token(page.get_data(as_text=True))})
    html = answer.get_data(as_text=True)
    assert answer.status_code == 200
    assert f"form-action 'self' {lms.base}" in answer.headers["Content-Security-Policy"]
    action = re.search(r'<form method="post" action="([^"]+)"', html).group(1)
    token = re.search(r'name="JWT" value="([^"]+)"', html).group(1)
    assert action == lms.url("/deep_link_return")
    requests.post(action, data={"JWT": token}, timeout=10)  # what the page's script makes the browser do
    [claims] = lms.deep_link_answers  # the platform verified the tool's signature with its JWKS
    assert (claims["iss"], claims["aud"], claims[CLAIM + "deployment_id"]) == (CLIENT_ID, lms.issuer, DEPLOYMENT)
    assert claims[CLAIM + "message_type"] == "LtiDeepLinkingResponse"
    assert claims["https://purl.imsglobal.org/spec/lti-dl/claim/data"] == "opaque-42"
    [item] = claims[CONTENT_ITEMS]
    assert (item["type"], item["custom"], item["lineItem"]["scoreMaximum"]) == ("ltiResourceLink", {"problem": "yoyo"}, 1)
    assert item["url"] == "http://localhost/lti/launch?problem=yoyo"
    assert client.get("/lti/deep-link").status_code == 400  # the selection was used up


def test_the_chosen_link_opens_the_problem_for_a_learner(tool, lms):
    # The link the LMS made from the content item: its target URL names the problem, no custom parameter.
    response, _ = launch(tool.test_client(), lms, {CLAIM + "custom": None, CLAIM + "resource_link": {"id": "new-link"},
                                                   CLAIM + "target_link_uri": "http://localhost/lti/launch?problem=yoyo"})
    assert response.status_code == 302 and response.headers["Location"] == "/problems/yoyo"


def test_a_learner_cannot_start_a_content_selection(tool, lms):
    settings = _deep_linking(lms)
    settings.update({"sub": "student-1", CLAIM + "roles": ["http://purl.imsglobal.org/vocab/lis/v2/membership#Learner"]})
    response, _ = launch(tool.test_client(), lms, settings)
    assert response.status_code == 403 and "Only an instructor" in response.get_data(as_text=True)


@pytest.mark.parametrize("settings, words", [
    ({"deep_link_return_url": "javascript:alert(1)"}, "http(s) URL"),
    ({"accept_types": ["file"]}, "accepts no LTI resource links"),
])
def test_a_content_selection_the_tool_cannot_answer_is_refused(tool, lms, settings, words):
    response, _ = launch(tool.test_client(), lms, _deep_linking(lms, **settings))
    assert response.status_code == 400 and words in response.get_data(as_text=True)


def test_an_instructor_may_link_only_problems_they_manage(tool, lms):
    from grader.store.models import Course, Problem

    with tool.extensions["lagrade.db"].write() as session:  # yoyo now belongs to a course they do not teach
        course = Course(code="ELSEWHERE", title="Elsewhere")
        session.add(course)
        session.flush()
        session.query(Problem).filter_by(slug="yoyo").update({"course_id": course.id})
    client = tool.test_client()
    launch(client, lms, _deep_linking(lms))
    page = client.get("/lti/deep-link").get_data(as_text=True)
    assert 'value="yoyo"' not in page
    answer = client.post("/lti/deep-link", data={"problem": "yoyo", "csrf_token": form_token(page)})
    assert answer.status_code == 404


def test_the_tool_makes_its_key_on_first_use_when_answering(tool, lms):
    import requests
    from sqlalchemy import delete

    from grader.store.lti_models import LtiToolKey

    with tool.extensions["lagrade.db"].write() as session:
        session.execute(delete(LtiToolKey))
    client = tool.test_client()
    launch(client, lms, _deep_linking(lms))
    page = client.get("/lti/deep-link").get_data(as_text=True)
    answer = client.post("/lti/deep-link", data={"problem": "yoyo", "csrf_token": form_token(page)})
    assert answer.status_code == 200
    lms.tool_jwks = client.get("/lti/jwks").get_json()  # the LMS reads the new key from the tool's JWKS
    token = re.search(r'name="JWT" value="([^"]+)"', answer.get_data(as_text=True)).group(1)
    requests.post(lms.url("/deep_link_return"), data={"JWT": token}, timeout=10)
    assert len(lms.deep_link_answers) == 1
