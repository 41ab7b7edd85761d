"""What an LMS administrator needs: the configuration page with every URL to paste and the tool's
key, the ``grader lti`` commands, and pages that the LMS (only it) may frame after a launch."""

from __future__ import annotations

import requests
from click.testing import CliRunner
from sqlalchemy import select

from grader.store.lti_models import LtiPlatform
from tests.web.conftest_pages import accounts, as_instructor  # noqa: F401
from tests.web.lti_platform import CLIENT_ID, auto_post_form, lms, login, tool  # noqa: F401


def test_the_configuration_page_lists_every_url_and_the_public_key(tool, lms, as_instructor):
    page = as_instructor.get("/lti/config")
    text = page.get_data(as_text=True)
    assert page.status_code == 200
    for url in ("http://localhost/lti/login", "http://localhost/lti/launch", "http://localhost/lti/jwks"):
        assert url in text
    assert "BEGIN PUBLIC KEY" in text and "PRIVATE" not in text
    assert lms.issuer in text and CLIENT_ID in text


def test_the_jwks_holds_only_public_keys(tool):
    keys = tool.test_client().get("/lti/jwks").get_json()["keys"]
    assert [sorted(k) for k in keys] == [["alg", "e", "kid", "kty", "n", "use"]]


def test_grader_lti_add_platform_registers_and_updates_an_lms(tmp_path, monkeypatch):
    from grader.cli.lti import lti
    from grader.store.db import Database

    url = f"sqlite:///{tmp_path / 'cli.sqlite'}"
    monkeypatch.setenv("DATABASE_URL", url)
    args = ["add-platform", "--issuer", "https://lms.example.org", "--client-id", "c1", "--deployment", "d1",
            "--auth-url", "https://lms.example.org/auth", "--token-url", "https://lms.example.org/token",
            "--jwks-url", "https://lms.example.org/jwks"]
    first = CliRunner().invoke(lti, args)
    again = CliRunner().invoke(lti, [*args, "--deployment", "d2"])
    bad = CliRunner().invoke(lti, [*args[:-1], "ftp://lms.example.org/jwks"])
    listed = CliRunner().invoke(lti, ["list"])
    assert first.exit_code == 0 and "deployments d1" in first.output, first.output
    assert again.exit_code == 0 and "deployments d1, d2" in again.output
    assert bad.exit_code == 2 and "JWKS URL must be an http(s) URL" in bad.output
    assert "https://lms.example.org\tc1\td1, d2" in listed.output
    database = Database(url)
    with database.read() as session:
        assert len(session.scalars(select(LtiPlatform)).all()) == 1
    database.dispose()


def test_after_a_launch_the_lms_and_only_it_may_frame_the_pages(tool, lms):
    with tool.extensions["lagrade.db"].write() as session:
        session.scalar(select(LtiPlatform)).auth_url = "https://lms.example.org/auth"
    client = tool.test_client()
    started = login(client, lms)
    assert "frame-ancestors https://lms.example.org" in started.headers["Content-Security-Policy"]
    served_auth = started.headers["Location"].replace("https://lms.example.org/auth", lms.url("/auth"))
    form = auto_post_form(requests.get(served_auth, timeout=10).text)
    launched = client.post("/lti/launch", data=form)
    assert launched.status_code == 302
    page = client.get("/problems/yoyo")
    assert "frame-ancestors https://lms.example.org" in page.headers["Content-Security-Policy"]
    assert "X-Frame-Options" not in page.headers
    other = tool.test_client().get("/login")
    assert "frame-ancestors 'none'" in other.headers["Content-Security-Policy"]
    assert other.headers["X-Frame-Options"] == "DENY"


def test_an_lms_course_mapped_to_a_course_opens_that_courses_problems(tool, lms, monkeypatch):
    from grader.cli.lti import lti
    from grader.store.models import Course, Enrolment, Problem
    from tests.web.lti_platform import launch

    with tool.extensions["lagrade.db"].write() as session:
        course = Course(code="MECH", title="Mechanics")
        session.add(course)
        session.flush()
        session.query(Problem).filter_by(slug="yoyo").update({"course_id": course.id})  # only MECH sees it
        course_id = course.id
    monkeypatch.setenv("DATABASE_URL", tool.config["DATABASE_URL"])
    mapped = CliRunner().invoke(lti, ["map-context", "--platform", "1", "--context", "course-7", "--course", "MECH"])
    assert mapped.exit_code == 0, mapped.output
    client = tool.test_client()
    response, _ = launch(client, lms)
    assert response.status_code == 302 and client.get("/problems/yoyo").status_code == 200
    with tool.extensions["lagrade.db"].read() as session:
        assert session.scalar(select(Enrolment.course_id)) == course_id
