"""The derivation page: an uploaded scene's progress (queued, deriving, done or failed), without script."""

import re
from pathlib import Path

import pytest

from grader.jobs import derivation_queue as queue
from tests.web.conftest_pages import accounts, as_instructor, csrf, sign_in  # noqa: F401  (fixtures)
from tests.web.derive_in_process import derive_all, derive_one

YOYO_SCENE = (Path(__file__).resolve().parents[2] / "problems" / "yoyo.toml").read_text()
REFRESH = '<meta http-equiv="refresh" content="2">'


def _upload(client, source=YOYO_SCENE, course=""):
    return client.post("/instructor/problems/new", data={"source": source, "course": course,
                                                         "csrf_token": csrf(client)})


@pytest.fixture
def as_colleague(app, accounts):
    """Another instructor of the same course (MECH)."""
    from grader.store.models import Enrolment
    from grader.store.users import create_user
    from tests.web.conftest_pages import PASSWORD, Account

    with app.extensions["lagrade.db"].write() as session:
        user = create_user(session, role="instructor", name="Col", email="col@example.org", password=PASSWORD)
        session.add(Enrolment(user_id=user.id, course_id=accounts["course"], role="instructor"))
        account = Account(user.id, user.email, "instructor")
    client = app.test_client()
    sign_in(client, account)
    return client


def test_the_page_follows_the_scene_from_queued_through_deriving_to_a_review_link(app, as_instructor):
    location = _upload(as_instructor).headers["Location"]
    queued = as_instructor.get(location).get_data(as_text=True)
    assert REFRESH in queued and '<li class="reached" aria-current="step">Queued</li>' in queued
    # The strict CSP forbids inline script: a meta refresh does the polling (scripts are files only).
    assert re.search(r"<script(?![^>]*\bsrc=)", queued) is None

    task = queue.claim(app.extensions["lagrade.db"], "test-deriver", lease_s=60)
    running = as_instructor.get(location).get_data(as_text=True)
    assert REFRESH in running and '<li class="reached" aria-current="step">Deriving</li>' in running

    derive_one(app, task)
    done = as_instructor.get(location).get_data(as_text=True)
    assert REFRESH not in done and '<li class="reached" aria-current="step">Done</li>' in done
    assert "as draft version 1" in done and 'href="/instructor/problems/yoyo/review?version=1"' in done


def test_a_queued_scene_says_how_many_uploads_are_ahead(app, as_instructor, as_colleague, accounts):
    _upload(as_colleague)
    location = _upload(as_instructor, YOYO_SCENE.replace('id = "yoyo"', 'id = "yoyo2"')).headers["Location"]
    assert "1 upload ahead of this one" in as_instructor.get(location).get_data(as_text=True)


def test_a_failed_derivation_shows_the_error_with_the_source_to_fix(app, as_instructor):
    broken = YOYO_SCENE.replace('potential = "-m*g*s"', 'potential = "-m*g*tehta"')
    location = _upload(as_instructor, broken).headers["Location"]
    derive_all(app)
    page = as_instructor.get(location).get_data(as_text=True)
    assert "The scene could not be used" in page and "tehta" in page and REFRESH not in page
    assert "-m*g*tehta" in page  # the source is back in the form, to fix and send again


@pytest.mark.parametrize("source, message", [
    ('id = "x"\n[energy\n', "not valid TOML"),
    ("", "Upload a scene file or paste one."),
])
def test_a_file_that_is_not_a_scene_is_refused_without_queueing(app, as_instructor, source, message):
    response = _upload(as_instructor, source)
    assert response.status_code == 422 and message in response.get_data(as_text=True)
    assert queue.claim(app.extensions["lagrade.db"], "w", lease_s=60) is None


def test_a_third_upload_while_two_wait_is_refused_with_retry_after(as_instructor):
    assert [_upload(as_instructor).status_code for _ in range(2)] == [302, 302]
    refused = _upload(as_instructor)
    assert refused.status_code == 429 and int(refused.headers["Retry-After"]) > 0
    assert "You have 2 scenes being derived already" in refused.get_data(as_text=True)


def test_a_job_is_seen_by_its_courses_instructors_but_not_by_another_courses(app, as_instructor, as_colleague,
                                                                             accounts):
    location = _upload(as_instructor, course=str(accounts["course"])).headers["Location"]
    other = app.test_client()
    sign_in(other, accounts["oth"])
    assert as_colleague.get(location).status_code == 200
    assert other.get(location).status_code == 404


def test_the_dashboard_lists_my_uploads_that_wait_or_failed(app, as_instructor, as_colleague):
    done = _upload(as_instructor).headers["Location"]
    broken = _upload(as_instructor, YOYO_SCENE.replace('potential = "-m*g*s"', 'potential = "-m*g*tehta"'))
    derive_all(app)
    waiting = _upload(as_instructor, YOYO_SCENE.replace('id = "yoyo"', 'id = "yoyo2"')).headers["Location"]
    page = as_instructor.get("/instructor/").get_data(as_text=True)
    assert f'href="{done}"' not in page  # done: it is among the problems now
    assert f'href="{broken.headers["Location"]}"' in page and ">failed</span>" in page
    assert f'href="{waiting}"' in page and ">queued</span>" in page
    assert "Your uploads" not in as_colleague.get("/instructor/").get_data(as_text=True)  # only one's own
