"""Grading workers: every queued submission gets exactly one verdict, from the sandboxed checker."""

import socket
import time

import pytest
from sqlalchemy import func, select

from grader.jobs import WorkerPool, queue
from grader.store.models import ProblemVersion, Submission, User, Verdict
from grader.store.problems import save_problem
from grader.store.users import create_user


@pytest.fixture
def setup(database, yoyo):
    with database.write() as session:
        version, _ = save_problem(session, yoyo)
        student = create_user(session, role="student", name="Ada")
        return {"version": version.id, "student": student.id}


def _submit_all(database, setup, texts):
    with database.read() as session:
        version = session.get(ProblemVersion, setup["version"])
        student = session.get(User, setup["student"])
    return [queue.submit(database, user=student, version=version, answer="tension", text=text)[0] for text in texts]


def _wait_until_graded(database, ids, timeout=60.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with database.read() as session:
            pending = session.scalar(select(func.count()).select_from(Submission)
                                     .where(Submission.id.in_(ids), Submission.status.in_(("queued", "running"))))
        if pending == 0:
            return
        time.sleep(0.05)
    raise AssertionError(f"{pending} submissions still not graded after {timeout} s")


# The yo-yo's tension is T = mg/3 (the string carries a third of the weight).
@pytest.mark.parametrize("text, verdict, score", [
    ("m*g/3", "equivalent", 1.0),
    ("(1/3) m g", "equivalent", 1.0),
    ("m*g", "not_equivalent", 0.0),
])  # an unreadable "m*g/" is refused by queue.submit and never reaches a worker (tests/jobs/test_queue.py)
def test_workers_grade_with_the_sandboxed_checker(database, setup, text, verdict, score):
    [submission_id] = _submit_all(database, setup, [text])
    pool = WorkerPool(database, workers=1, poll_s=0.1).start()
    try:
        _wait_until_graded(database, [submission_id])
    finally:
        pool.stop()
    with database.read() as session:
        submission = session.get(Submission, submission_id)
        assert (submission.status, submission.verdict.verdict, submission.verdict.score) == ("done", verdict, score)
        assert submission.verdict.wait_ms >= 0 and submission.verdict.grade_ms > 0


def test_many_submissions_each_get_exactly_one_verdict(database, setup):
    ids = _submit_all(database, setup, [f"m*g/{n}" for n in range(1, 31)])
    pool = WorkerPool(database, workers=2, poll_s=0.1).start()
    try:
        _wait_until_graded(database, ids)
    finally:
        pool.stop()
    with database.read() as session:
        counts = dict(session.execute(select(Verdict.submission_id, func.count()).group_by(Verdict.submission_id)).all())
        correct = session.scalars(select(Verdict.submission_id).where(Verdict.verdict == "equivalent")).all()
    assert counts == {i: 1 for i in ids}
    assert correct == [ids[2]]  # only m*g/3


def test_start_queues_again_what_a_crash_left_running(database, setup):
    [submission_id] = _submit_all(database, setup, ["m*g/3"])
    queue.claim(database, f"{socket.gethostname()}:{2 ** 22 + 7}:pool/0")  # no process has that pid
    pool = WorkerPool(database, workers=1, poll_s=0.1).start()
    try:
        _wait_until_graded(database, [submission_id])
    finally:
        pool.stop()
    with database.read() as session:
        assert session.get(Submission, submission_id).verdict.verdict == "equivalent"


class BrokenChecker:
    """A checker whose child cannot work at all: it raises (not an answer's fault)."""

    closed = 0

    def run(self, request, budget_s=None):
        raise OSError("the sandbox could not start")

    def close(self):
        BrokenChecker.closed += 1


class UnavailableChecker(BrokenChecker):
    """A checker that answers, but with a checker failure rather than a grade."""

    def run(self, request, budget_s=None):
        return {"verdict": "invalid", "certainty": "none", "reason": "checker unavailable: no memory",
                "parsed": {"text": "", "latex": "", "notes": []}, "counterexample": None, "feedback": [],
                "ms": 0.0, "checker_failure": True}


@pytest.mark.parametrize("checker", [BrokenChecker, UnavailableChecker], ids=["raises", "reports-failure"])
def test_a_failing_checker_is_retried_and_the_submission_ends_failed_not_lost(database, setup, checker):
    """Never stored as the student's grade (an "invalid" 0): retried, then failed with an error verdict."""
    BrokenChecker.closed = 0
    [submission_id] = _submit_all(database, setup, ["m*g/3"])
    pool = WorkerPool(database, workers=1, poll_s=0.05, checker_factory=checker).start()
    try:
        _wait_until_graded(database, [submission_id], timeout=20)
    finally:
        pool.stop()
    with database.read() as session:
        submission = session.get(Submission, submission_id)
        assert submission.status == "failed" and submission.verdict.verdict == "error"
        assert submission.attempts > queue.MAX_ATTEMPTS
    assert BrokenChecker.closed >= queue.MAX_ATTEMPTS
