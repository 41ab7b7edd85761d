"""The grading queue: committed before grading, claimed once, exactly one verdict in effect after anything."""

import os
import socket
import threading
from concurrent.futures import ThreadPoolExecutor
from datetime import timedelta

import pytest
from sqlalchemy import func, select

from grader.jobs import queue
from grader.store.models import Submission, User, Verdict, utcnow
from grader.store.problems import save_problem
from grader.store.users import create_user

# Worker ids name their host and process (grader/jobs/processes.py); no process ever has this pid.
DEAD = f"{socket.gethostname()}:{2 ** 22 + 7}:pool/0"
ALIVE = f"{socket.gethostname()}:{os.getpid()}:pool/0"

RESULT = {"verdict": "correct", "certainty": "proved", "reason": "equal", "parsed": None,
          "counterexample": None, "feedback": None, "ms": 1.0}


@pytest.fixture
def setup(database, yoyo):
    """The yo-yo problem and a student, as ids."""
    with database.write() as session:
        version, _ = save_problem(session, yoyo)
        student = create_user(session, role="student", name="Ada")
        return {"version": version.id, "student": student.id}


def _submit(database, setup, text="g*m/3", answer="tension", key=None, user=None):
    from grader.store.models import ProblemVersion

    with database.read() as session:
        version = session.get(ProblemVersion, setup["version"])
        student = session.get(User, user or setup["student"])
    return queue.submit(database, user=student, version=version, answer=answer, text=text, idempotency_key=key)


def _record(database, task, worker="w1", result=RESULT):
    return queue.record(database, task, worker, result, score=1.0, grade_ms=1.0, started_at=utcnow())


def _verdicts(database, submission_id):
    with database.read() as session:
        return session.scalars(select(Verdict).where(Verdict.submission_id == submission_id)).all()


def test_a_submission_is_committed_as_queued_before_anything_grades_it(database, setup):
    submission_id, created = _submit(database, setup)
    with database.read() as session:  # a different session sees it: it was committed
        assert created and session.get(Submission, submission_id).status == "queued"


@pytest.mark.parametrize("answer, text, message", [
    ("speed", "1", "has no answer 'speed'"),
    ("tension", "m" * (queue.MAX_ANSWER_CHARS + 1), "the limit is"),
])
def test_unusable_submissions_are_refused_with_a_reason(database, setup, answer, text, message):
    with pytest.raises(queue.SubmissionRejected, match=message):
        _submit(database, setup, answer=answer, text=text)


def test_a_retried_request_with_the_same_key_returns_the_same_submission(database, setup):
    first, created = _submit(database, setup, key="abc")
    again, created_again = _submit(database, setup, key="abc")
    assert (again, created, created_again) == (first, True, False)
    with pytest.raises(queue.IdempotencyConflict):
        _submit(database, setup, key="abc", text="m*g")


def test_claims_are_exclusive_under_concurrency(database, setup):
    ids = {_submit(database, setup, text=f"{n}*g*m")[0] for n in range(40)}

    def drain(worker):
        taken = []
        while (task := queue.claim(database, worker)) is not None:
            taken.append(task.submission_id)
        return taken

    with ThreadPoolExecutor(8) as pool:
        results = list(pool.map(drain, [f"w{n}" for n in range(8)]))
    claimed = [i for taken in results for i in taken]
    assert sorted(claimed) == sorted(ids)  # every one claimed, none twice


def test_record_commits_the_verdict_and_done_together_and_only_once(database, setup):
    submission_id, _ = _submit(database, setup)
    task = queue.claim(database, "w1")
    assert _record(database, task) is True
    assert _record(database, task) is False  # a second report of the same round changes nothing
    with database.read() as session:
        assert session.get(Submission, submission_id).status == "done"
    assert [v.verdict for v in _verdicts(database, submission_id)] == ["correct"]


def test_a_result_from_a_worker_that_lost_its_claim_is_dropped(database, setup):
    submission_id, _ = _submit(database, setup)
    stale = queue.claim(database, DEAD)
    queue.recover(database)  # a restart found DEAD's process gone (it was only slow elsewhere...)
    fresh = queue.claim(database, "w2")
    assert _record(database, stale, worker=DEAD) is False
    assert _record(database, fresh, worker="w2") is True
    assert len(_verdicts(database, submission_id)) == 1


def test_recover_queues_again_what_a_crash_left_running(database, setup):
    submission_id, _ = _submit(database, setup)
    task = queue.claim(database, DEAD)
    assert queue.recover(database) == 1
    again = queue.claim(database, "w2")
    assert (again.submission_id, again.grading_round, again.attempts) == (task.submission_id, 1, 2)


@pytest.mark.parametrize("holder", [ALIVE, "other-host:1234:pool/0", "unreadable"],
                         ids=["live-process-here", "other-host", "unreadable-id"])
def test_recover_leaves_claims_that_a_live_or_unknown_process_holds_to_their_lease(database, setup, holder):
    # Several web processes share the database: one starting up must not take work from another.
    _submit(database, setup)
    queue.claim(database, holder)
    assert queue.recover(database) == 0
    assert queue.claim(database, "w2") is None
    assert queue.requeue_expired(database, now=utcnow() + timedelta(seconds=queue.LEASE_S + 1)) == 1


def test_expired_leases_are_queued_again(database, setup):
    _submit(database, setup)
    queue.claim(database, "w1", lease_s=60)
    assert queue.requeue_expired(database) == 0
    assert queue.requeue_expired(database, now=utcnow() + timedelta(seconds=61)) == 1


def test_a_submission_that_keeps_crashing_its_grader_ends_failed_with_one_verdict(database, setup):
    submission_id, _ = _submit(database, setup)
    for _ in range(queue.MAX_ATTEMPTS):
        assert queue.claim(database, DEAD) is not None
        queue.recover(database)  # the grader died each time
    assert queue.claim(database, DEAD) is None
    with database.read() as session:
        assert session.get(Submission, submission_id).status == "failed"
    [verdict] = _verdicts(database, submission_id)
    assert verdict.verdict == "error" and "interrupted" in verdict.reason


def test_regrade_starts_a_new_round_and_drops_the_running_one(database, setup, yoyo):
    import dataclasses

    from grader.store.models import ProblemVersion

    submission_id, _ = _submit(database, setup)
    _record(database, queue.claim(database, "w1"))
    running_id, _ = _submit(database, setup, text="m*g")
    running = queue.claim(database, "w1")
    with database.write() as session:
        fixed, _ = save_problem(session, dataclasses.replace(yoyo, source=yoyo.source + "# fixed\n"))
    assert queue.regrade(database, fixed) == 2
    assert _record(database, running) is False  # graded against the old round: dropped
    tasks = [queue.claim(database, "w2"), queue.claim(database, "w2")]
    assert {(t.submission_id, t.grading_round, t.version_id) for t in tasks} == {
        (submission_id, 2, fixed.id), (running_id, 2, fixed.id)}
    for task in tasks:
        assert _record(database, task, worker="w2")
    with database.read() as session:
        rounds = session.execute(select(Verdict.submission_id, func.count()).group_by(Verdict.submission_id)).all()
        in_effect = [session.get(Submission, i).verdict.grading_round for i in (submission_id, running_id)]
    assert dict(rounds) == {submission_id: 2, running_id: 1} and in_effect == [2, 2]


def test_release_gives_a_task_back(database, setup):
    _submit(database, setup)
    task = queue.claim(database, "w1")
    queue.release(database, task, "w1")
    assert queue.claim(database, "w2").submission_id == task.submission_id


def test_a_new_submission_wakes_idle_workers(database, setup):
    woke = threading.Event()

    def idle_worker():
        queue.wait_for_work(5.0)
        woke.set()

    queue._new_work.clear()
    thread = threading.Thread(target=idle_worker)
    thread.start()
    _submit(database, setup)
    thread.join(5.0)
    assert woke.is_set()


@pytest.mark.postgresql_only
def test_a_claim_skips_a_row_another_transaction_has_locked(database, setup):
    # PostgreSQL: FOR UPDATE SKIP LOCKED lets a worker take the next row at once instead of waiting
    # for (or colliding with) another process's claim. SQLite serialises writers: nothing to skip.
    first, _ = _submit(database, setup, text="1*g*m")
    second, _ = _submit(database, setup, text="2*g*m")
    holder = database.writer()
    try:
        holder.execute(select(Submission.id).where(Submission.id == first).with_for_update())
        task = queue.claim(database, "w1")
        assert task is not None and task.submission_id == second
    finally:
        holder.rollback()
        holder.close()
    assert queue.claim(database, "w2").submission_id == first  # free again once the lock is gone


@pytest.mark.parametrize("text, code, column", [("m*g/", "syntax", 4), ("m*g/(3", "unbalanced", 5),
                                                ("m*q", "unknown_name", 3)])
def test_an_unreadable_answer_is_refused_and_stores_nothing(database, setup, text, code, column):
    with pytest.raises(queue.AnswerUnreadable, match=f"at character {column}") as refused:
        _submit(database, setup, text=text)
    assert (refused.value.error["code"], refused.value.error["column"]) == (code, column)
    assert isinstance(refused.value, queue.SubmissionRejected)  # callers that refuse any bad submission still do
    with database.read() as session:
        assert session.scalar(select(func.count(Submission.id))) == 0  # not an attempt


def test_the_same_text_again_is_the_same_attempt(database, setup):
    first, created = _submit(database, setup, text="m*g")
    again, created_again = _submit(database, setup, text="m*g")
    other, created_other = _submit(database, setup, text="m*g/2")
    as_tension, _ = _submit(database, setup, text="g")
    as_acceleration, _ = _submit(database, setup, text="g", answer="acceleration")
    assert (again, created, created_again) == (first, True, False)
    # Another text, or the same text for another answer: new attempts.
    assert created_other and len({first, other, as_tension, as_acceleration}) == 4
    with database.write() as session:
        other_student = create_user(session, role="student", name="Bob").id
    assert _submit(database, setup, text="m*g", user=other_student)[0] != first


def test_a_submission_that_could_not_be_graded_may_be_sent_again(database, setup):
    first, _ = _submit(database, setup, text="m*g")
    with database.write() as session:
        session.get(Submission, first).status = "failed"
    again, created = _submit(database, setup, text="m*g")
    assert created and again != first


def test_same_attempt_keeps_assignments_and_practice_apart(database, setup):
    first, _ = _submit(database, setup, text="m*g")
    with database.read() as session:
        found = queue.same_attempt(session, setup["student"], setup["version"], "tension", "m*g")
        in_assignment = queue.same_attempt(session, setup["student"], setup["version"], "tension", "m*g",
                                           assignment_id=1)
    assert (found.id, in_assignment) == (first, None)
