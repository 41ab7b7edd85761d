"""Score passback (AGS) end to end: after each verdict of a student who came through an LMS link, the
stand-in platform receives their score exactly once, after retries when it failed first."""

from __future__ import annotations

from datetime import timedelta

import pytest
from sqlalchemy import select

from grader.jobs import lti_passback, queue
from grader.store.lti_models import LtiAccount, LtiResourceLink, LtiScorePassback
from grader.store.models import ProblemVersion, User, utcnow
from grader.web.lti.ags import deliverer
from tests.web.lti_platform import LINEITEM_SCOPE, SCORE_SCOPE, launch, lms, tool  # noqa: F401


# The outbox's uniqueness and savepoints on the two databases the service supports.
BOTH_DATABASES = pytest.mark.parametrize("database_kind", ["sqlite", "postgresql"])


def _db(app):
    return app.extensions["lagrade.db"]


def _student(app, sub="student-1"):
    with _db(app).read() as session:
        account = session.scalar(select(LtiAccount).where(LtiAccount.sub == sub))
        return session.get(User, account.user_id)


TEXTS = {"tension": "g*m/3", "acceleration": "2*g/3"}  # answers the yo-yo's names can express


def _grade(app, user, answer: str, score: float, text: str | None = None) -> None:
    """A submission of ``user`` graded ``score`` by the queue's own record (which queues the passback)."""
    database = _db(app)
    with database.read() as session:
        version = session.scalar(select(ProblemVersion))
        session.expunge_all()
    queue.submit(database, user=user, version=version, answer=answer, text=text or TEXTS[answer])
    task = queue.claim(database, "w1")
    verdict = "correct" if score == 1.0 else "incorrect"
    assert queue.record(database, task, "w1", {"verdict": verdict}, score=score, grade_ms=1.0, started_at=utcnow())


def _send(app, now=None):
    return lti_passback.deliver_due(_db(app), deliverer(_db(app)), now=now)


@pytest.fixture
def launched(tool, lms):
    response, _ = launch(tool.test_client(), lms)
    assert response.status_code == 302
    return _student(tool)


@BOTH_DATABASES
def test_a_verdict_sends_the_problem_score_to_the_lms_exactly_once(tool, lms, launched, database_kind):
    _grade(tool, launched, "tension", 1.0)
    assert _send(tool).sent == 1
    assert _send(tool).sent == 0  # nothing is sent twice
    assert lms.score_urls == ["/lineitems/1/scores"]
    [score] = lms.scores
    assert (score["userId"], score["scoreGiven"], score["scoreMaximum"]) == ("student-1", 0.5, 1.0)  # 1 of 2 answers
    assert (score["activityProgress"], score["gradingProgress"]) == ("Completed", "FullyGraded")
    assert score["timestamp"].endswith("Z")


def test_a_score_the_lms_refused_is_retried_with_backoff_until_it_is_taken(tool, lms, launched):
    lms.fail_scores = 2
    _grade(tool, launched, "tension", 1.0)
    start = utcnow()
    assert _send(tool, start).failed == 1
    assert _send(tool, start + timedelta(seconds=10)).sent == 0  # not due before its backoff (30 s)
    assert _send(tool, start + timedelta(seconds=31)).failed == 1
    assert _send(tool, start + timedelta(seconds=31 + 59)).sent == 0  # doubled: 60 s
    assert _send(tool, start + timedelta(seconds=31 + 61)).sent == 1
    assert len(lms.scores) == 1
    with _db(tool).read() as session:
        row = session.scalar(select(LtiScorePassback))
        assert (row.attempts, row.sent_at is not None, row.last_error) == (3, True, None)


@BOTH_DATABASES
def test_the_same_score_again_is_not_queued_and_a_new_score_is(tool, lms, launched, database_kind):
    _grade(tool, launched, "tension", 1.0)
    _grade(tool, launched, "tension", 0.0, "m*g/2")  # a worse attempt: the best score stays 1 answer of 2
    _send(tool)
    _grade(tool, launched, "acceleration", 1.0)
    _send(tool)
    assert [s["scoreGiven"] for s in lms.scores] == [0.5, 1.0]
    with _db(tool).read() as session:
        versions = session.scalars(select(LtiScorePassback.score_version).order_by(LtiScorePassback.id)).all()
    assert versions == [1, 2]


def test_an_unsent_score_is_superseded_by_a_newer_one(tool, lms, launched):
    lms.fail_scores = 1
    _grade(tool, launched, "tension", 1.0)
    start = utcnow()
    assert _send(tool, start).failed == 1
    _grade(tool, launched, "acceleration", 1.0)
    assert _send(tool, start + timedelta(seconds=1)).sent == 1  # the newer score; the older one is dropped
    assert _send(tool, start + timedelta(hours=2)).sent == 0
    assert [s["scoreGiven"] for s in lms.scores] == [1.0]


def test_a_student_who_never_came_through_the_lms_has_nothing_sent(tool, lms, launched):
    from grader.store.users import create_user

    with _db(tool).write() as session:
        local = create_user(session, role="student", name="Local")
        session.expunge(local)
    _grade(tool, local, "tension", 1.0)
    assert _send(tool).sent == 0 and lms.scores == []


def test_a_link_without_a_line_item_gets_one_made_on_the_platform(tool, lms):
    ags = {"scope": [SCORE_SCOPE, LINEITEM_SCOPE], "lineitems": lms.url("/lineitems")}
    response, _ = launch(tool.test_client(), lms, {"https://purl.imsglobal.org/spec/lti-ags/claim/endpoint": ags})
    assert response.status_code == 302
    _grade(tool, _student(tool), "tension", 1.0)
    assert _send(tool).sent == 1
    [item] = lms.lineitems
    assert (item["resourceLinkId"], item["resourceId"], item["scoreMaximum"]) == ("link-1", "yoyo", 1.0)
    assert lms.score_urls == ["/lineitems/100/scores"]
    with _db(tool).read() as session:
        assert session.scalar(select(LtiResourceLink.lineitem_url)) == item["id"]


def test_a_launch_without_the_grade_service_queues_no_score(tool, lms):
    response, _ = launch(tool.test_client(), lms, {"https://purl.imsglobal.org/spec/lti-ags/claim/endpoint": None})
    assert response.status_code == 302
    _grade(tool, _student(tool), "tension", 1.0)
    with _db(tool).read() as session:
        assert session.scalars(select(LtiScorePassback)).all() == []


def test_the_background_sender_delivers_on_its_own(tool, lms, launched):
    import time

    sender = lti_passback.PassbackSender(_db(tool), deliverer(_db(tool)), interval_s=0.05).start()
    try:
        _grade(tool, launched, "tension", 1.0)
        deadline = time.monotonic() + 10
        while not lms.scores and time.monotonic() < deadline:
            time.sleep(0.05)
    finally:
        sender.stop()
    assert len(lms.scores) == 1
