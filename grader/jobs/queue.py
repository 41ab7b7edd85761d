"""The grading queue, kept in the ``submissions`` table itself.

A submission's life: ``submit`` commits it as ``queued`` (nothing is graded before it is stored);
a worker ``claim``s it with a conditional UPDATE (``queued`` → ``running``, with its worker id and a
lease); the worker grades it with no session open, then ``record`` inserts the verdict and sets
``done`` in one transaction, but only if the row is still ``running`` under that worker and in the
same grading round. ``UNIQUE(submission_id, grading_round)`` on verdicts guards the rest, so after any
crash each submission has exactly one verdict in effect.

After a crash, ``recover`` (run when the server starts) puts every ``running`` row back to
``queued``; ``requeue_expired`` does the same for leases that ran out while the server runs. A
submission that was claimed ``MAX_ATTEMPTS`` times in one round without a verdict is recorded as
``failed`` with an ``error`` verdict, so a poisonous input cannot loop forever.
"""

from __future__ import annotations

import hashlib
import json
import logging
import threading
from dataclasses import dataclass
from datetime import datetime, timedelta
from typing import Any, Callable

from sqlalchemy import select, update
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from grader.answers.readable import read_error
from grader.jobs.processes import holder_is_dead
from grader.jobs import lti_passback
from grader.store.db import Database
from grader.store.draws import submission_values
from grader.store.models import ProblemVersion, Submission, User, Verdict, utcnow

log = logging.getLogger(__name__)

__all__ = [
    "AnswerUnreadable",
    "IdempotencyConflict",
    "MAX_ANSWER_CHARS",
    "MAX_ATTEMPTS",
    "SubmissionRejected",
    "Task",
    "add_publisher",
    "announce",
    "claim",
    "claim_submission",
    "holder_lease",
    "queued_since",
    "record",
    "recover",
    "regrade",
    "release",
    "requeue_expired",
    "same_attempt",
    "submit",
    "wake_workers",
]

MAX_ATTEMPTS = 3
MAX_ANSWER_CHARS = 4000
LEASE_S = 120.0

# Set when new work is committed, so idle workers claim it at once instead of at their next poll.
_new_work = threading.Event()


def wake_workers() -> None:
    _new_work.set()


# Where queued work is announced besides the in-process event: a task queue (Celery) when
# GRADER_BROKER_URL is set. Each publisher gets the (submission id, round) pairs just queued.
_publishers: list[Callable[[list[tuple[int, int]]], None]] = []


def add_publisher(publisher: Callable[[list[tuple[int, int]]], None]) -> None:
    """Announce every newly queued (submission, round) to ``publisher`` too (once per process)."""
    if publisher not in _publishers:
        _publishers.append(publisher)


def announce(work: list[tuple[int, int]]) -> None:
    """Tell the workers (in-process, and a broker's when one is set) that this work is queued."""
    wake_workers()
    for publisher in _publishers:
        try:
            publisher(work)
        except Exception:
            # The work is committed as queued; the workers' sweep sends it again later.
            log.exception("could not announce %d queued submissions; the sweep will", len(work))


def wait_for_work(timeout: float) -> None:
    if _new_work.wait(timeout):
        _new_work.clear()


class SubmissionRejected(ValueError):
    """A submission that cannot be accepted (unknown answer, text too long); the message says why."""


class AnswerUnreadable(SubmissionRejected):
    """An answer text the grader cannot read: a typo to fix, not an attempt, so nothing is stored.

    ``error`` is :func:`grader.answers.readable.read_error`'s ``{"message", "position", "column",
    "code", "hint"}`` (``column`` 1-based, as the caret shows it).
    """

    def __init__(self, error: dict[str, Any]):
        where = f" (at character {error['column']})" if error.get("column") else ""
        hint = f"; {error['hint']}" if error.get("hint") else ""
        super().__init__(f"the grader cannot read this answer: {error['message']}{where}{hint}")
        self.error = error


def same_attempt(session: Session, user_id: int, version_id: int, answer: str, text: str,
                 assignment_id: int | None = None) -> Submission | None:
    """The student's earlier submission of exactly this text for this answer (same problem version,
    same assignment or none), if any: sending it again is the same attempt, not a new one. A
    submission that could not be graded (``failed``) does not count, so sending it again retries.
    """
    where = Submission.assignment_id.is_(None) if assignment_id is None else Submission.assignment_id == assignment_id
    return session.scalar(select(Submission).where(
        Submission.user_id == user_id, Submission.problem_version_id == version_id,
        Submission.answer_name == answer, Submission.text == text, Submission.status != "failed", where)
        .order_by(Submission.id.desc()).limit(1))


class IdempotencyConflict(ValueError):
    """An Idempotency-Key reused with a different request."""

    def __init__(self, submission_id: int):
        super().__init__(f"this Idempotency-Key was already used for a different request (submission {submission_id})")
        self.submission_id = submission_id


def _fingerprint(version: ProblemVersion, user_id: int, answer: str, text: str) -> str:
    body = {"problem": version.problem_id, "user": user_id, "answer": answer, "text": text}
    return hashlib.sha256(json.dumps(body, sort_keys=True).encode()).hexdigest()


def submit(database: Database, *, user: User, version: ProblemVersion, answer: str, text: str,
           requester: User | None = None, idempotency_key: str | None = None) -> tuple[int, bool]:
    """Store a submission as ``queued`` in its own short transaction; returns ``(submission id, created)``.

    ``user`` (whose work it is), ``requester`` (who sent it: the student, or an LMS acting for one;
    default ``user``) and ``version`` may be detached objects: only their ids and the version's
    references are read. With an ``idempotency_key`` (scoped to the requester), a retry of the same
    request returns the stored submission (``created`` False) and a different request with the same
    key raises :class:`IdempotencyConflict`.

    A text the grader cannot read raises :class:`AnswerUnreadable` and stores nothing; the same text
    the student already sent for this answer returns that submission (``created`` False): neither
    is a new attempt.
    """
    requester_id = (requester or user).id
    reference = version.reference(answer)
    if reference is None:
        names = ", ".join(r["name"] for r in version.references)
        raise SubmissionRejected(f"this problem has no answer {answer!r}; its answers: {names}")
    if len(text) > MAX_ANSWER_CHARS:
        raise SubmissionRejected(f"the answer is {len(text)} characters long; the limit is {MAX_ANSWER_CHARS}")
    unreadable = read_error(reference, text)
    if unreadable is not None:
        raise AnswerUnreadable(unreadable)
    fingerprint = _fingerprint(version, user.id, answer, text)
    try:
        with database.write() as session:
            if idempotency_key is not None:
                existing = _by_key(session, requester_id, idempotency_key)
                if existing is not None:
                    return _replay(existing, fingerprint), False
            earlier = same_attempt(session, user.id, version.id, answer, text)
            if earlier is not None:
                return earlier.id, False
            submission = Submission(user_id=user.id, requester_id=requester_id, problem_version_id=version.id,
                                    grading_version_id=version.id, answer_name=answer, text=text, status="queued",
                                    idempotency_key=idempotency_key, request_sha256=fingerprint)
            session.add(submission)
            session.flush()
            submission_id = submission.id
    except IntegrityError:
        # A concurrent retry with the same key won the insert: answer as for a retry.
        with database.read() as session:
            existing = _by_key(session, requester_id, idempotency_key) if idempotency_key else None
            if existing is None:
                raise
            return _replay(existing, fingerprint), False
    announce([(submission_id, 1)])
    return submission_id, True


def _by_key(session: Session, requester_id: int, key: str) -> Submission | None:
    return session.scalar(select(Submission).where(Submission.requester_id == requester_id,
                                                   Submission.idempotency_key == key))


def _replay(existing: Submission, fingerprint: str) -> int:
    if existing.request_sha256 != fingerprint:
        raise IdempotencyConflict(existing.id)
    return existing.id


def regrade(database: Database, version: ProblemVersion) -> int:
    """Queue a new grading round for every submission to ``version``'s problem, in one transaction.

    Each submission is graded against ``version`` when it still has that answer, else against the
    version it was graded with before. Returns how many submissions were queued.
    """
    names = [r["name"] for r in version.references]
    problem_versions = select(ProblemVersion.id).where(ProblemVersion.problem_id == version.problem_id)
    queued = 0
    with database.write() as session:
        for moved in (True, False):
            match = Submission.answer_name.in_(names) if moved else Submission.answer_name.not_in(names)
            values: dict[str, Any] = dict(grading_round=Submission.grading_round + 1, status="queued", attempts=0,
                                          worker_id=None, lease_until=None, updated_at=utcnow())
            if moved:
                values["grading_version_id"] = version.id
            result = session.execute(update(Submission)
                                     .where(Submission.problem_version_id.in_(problem_versions), match)
                                     .values(**values))
            queued += result.rowcount
        work = [(row[0], row[1]) for row in session.execute(
            select(Submission.id, Submission.grading_round)
            .where(Submission.problem_version_id.in_(problem_versions), Submission.status == "queued"))]
    announce(work)
    return queued


@dataclass(frozen=True)
class Task:
    """What a worker needs to grade one submission, read in a short session and detached from it."""

    submission_id: int
    grading_round: int
    version_id: int
    attempts: int
    answer: str
    text: str
    reference: dict[str, Any] | None
    received_at: datetime
    # The student's parameter values when the submission was handed in for an assignment of a
    # randomised problem (numeric answers are checked at them); None: the problem's own values.
    values: dict[str, Any] | None = None


def claim(db: Database, worker_id: str, *, lease_s: float = LEASE_S) -> Task | None:
    """Take the oldest queued submission for ``worker_id``, or None if there is none.

    The write transaction is only the conditional UPDATE; the task's data is read afterwards. On
    PostgreSQL the row is locked with ``FOR UPDATE SKIP LOCKED``, so workers in other processes
    claim different rows without waiting for each other; SQLite has one writer at a time anyway.
    """
    while True:
        with db.write() as session:
            submission_id = session.scalar(select(Submission.id).where(Submission.status == "queued")
                                           .order_by(Submission.id).limit(1).with_for_update(skip_locked=True))
            if submission_id is None:
                return None
            now = utcnow()
            taken = session.execute(
                update(Submission)
                .where(Submission.id == submission_id, Submission.status == "queued")
                .values(status="running", worker_id=worker_id, lease_until=now + timedelta(seconds=lease_s),
                        attempts=Submission.attempts + 1, updated_at=now)
            ).rowcount
        if taken != 1:
            continue  # another worker took it between our SELECT and UPDATE
        task = _claimed_task(db, submission_id, worker_id)
        if task is not None:
            return task


def claim_submission(db: Database, submission_id: int, grading_round: int, worker_id: str, *,
                     lease_s: float = LEASE_S) -> Task | None:
    """Take submission ``submission_id`` for its round ``grading_round`` (a task message names both).

    It is taken when it is queued in that round, or running under a lease that has run out (its
    worker died). None when there is nothing to do: already graded, failed, a newer round, or
    another live worker holds it (see :func:`holder_lease`).
    """
    now = utcnow()
    with db.write() as session:
        taken = session.execute(
            update(Submission)
            .where(Submission.id == submission_id, Submission.grading_round == grading_round,
                   (Submission.status == "queued")
                   | ((Submission.status == "running") & (Submission.lease_until < now)))
            .values(status="running", worker_id=worker_id, lease_until=now + timedelta(seconds=lease_s),
                    attempts=Submission.attempts + 1, updated_at=now)).rowcount
    return _claimed_task(db, submission_id, worker_id) if taken == 1 else None


def holder_lease(db: Database, submission_id: int, grading_round: int) -> datetime | None:
    """When another worker's claim on this round runs out, if one holds it now; else None."""
    with db.read() as session:
        submission = session.get(Submission, submission_id)
        if submission is None or submission.grading_round != grading_round or submission.status != "running":
            return None
        return submission.lease_until


def _claimed_task(db: Database, submission_id: int, worker_id: str) -> Task | None:
    """The task of a submission this worker has just claimed, or None if it cannot be graded
    (then it is recorded as failed)."""
    with db.read() as session:
        submission = session.get(Submission, submission_id)
        version = submission.grading_version
        task = Task(submission.id, submission.grading_round, version.id, submission.attempts,
                    submission.answer_name, submission.text, version.reference(submission.answer_name),
                    submission.received_at, submission_values(session, submission))
    if task.reference is None:
        _fail(db, task, worker_id, f"version {version.number} has no answer {task.answer!r}")
    elif task.attempts > MAX_ATTEMPTS:
        _fail(db, task, worker_id, f"grading was interrupted {MAX_ATTEMPTS} times")
    else:
        return task
    return None


def queued_since(db: Database, before: datetime, limit: int = 1000) -> list[tuple[int, int]]:
    """(submission, round) of queued submissions not touched since ``before``: work whose message
    may have been lost (a broker that was down when it was submitted)."""
    with db.read() as session:
        rows = session.execute(select(Submission.id, Submission.grading_round)
                               .where(Submission.status == "queued", Submission.updated_at < before)
                               .order_by(Submission.id).limit(limit))
        return [(row[0], row[1]) for row in rows]


def _fail(db: Database, task: Task, worker_id: str, reason: str) -> None:
    """Record that ``task`` cannot be graded: status failed, with an ``error`` verdict in effect."""
    with db.write() as session:
        ours = session.execute(
            update(Submission)
            .where(Submission.id == task.submission_id, Submission.status == "running",
                   Submission.worker_id == worker_id, Submission.grading_round == task.grading_round)
            .values(status="failed", worker_id=None, lease_until=None, updated_at=utcnow())).rowcount
        if ours == 1:
            session.add(Verdict(submission_id=task.submission_id, grading_round=task.grading_round,
                                problem_version_id=task.version_id, verdict="error", score=0.0,
                                reason=f"could not be graded: {reason}", worker_id=worker_id))


def record(db: Database, task: Task, worker_id: str, result: dict[str, Any], *, score: float,
           grade_ms: float, started_at: datetime) -> bool:
    """Commit the verdict of ``task`` and mark it done, in one transaction.

    Returns False (and writes nothing) when the claim is no longer ours: a regrade started a new
    round, or the lease ran out and another worker took the submission.
    """
    try:
        with db.write() as session:
            ours = session.execute(
                update(Submission)
                .where(Submission.id == task.submission_id, Submission.status == "running",
                       Submission.worker_id == worker_id, Submission.grading_round == task.grading_round)
                .values(status="done", worker_id=None, lease_until=None, updated_at=utcnow())
            ).rowcount
            if ours != 1:
                return False
            session.add(Verdict(
                submission_id=task.submission_id, grading_round=task.grading_round, problem_version_id=task.version_id,
                verdict=result["verdict"], certainty=result.get("certainty"), score=score, reason=result.get("reason"),
                feedback=result.get("feedback"), counterexample=result.get("counterexample"), parsed=result.get("parsed"),
                check_ms=result.get("ms"), grade_ms=grade_ms, worker_id=worker_id,
                wait_ms=(started_at - task.received_at).total_seconds() * 1000,
            ))
            # A student who came through an LMS link gets the new score queued for the LMS in this same
            # transaction: no verdict is committed without it (grader/jobs/lti_passback.py).
            lti_passback.enqueue_for_verdict(session, task.submission_id)
    except IntegrityError:  # a verdict for this round exists already: it stays the one in effect
        return False
    return True


def release(db: Database, task: Task, worker_id: str) -> None:
    """Give a claimed task back to the queue (the worker could not grade it this time)."""
    with db.write() as session:
        session.execute(update(Submission)
                        .where(Submission.id == task.submission_id, Submission.worker_id == worker_id,
                               Submission.status == "running", Submission.grading_round == task.grading_round)
                        .values(status="queued", worker_id=None, lease_until=None, updated_at=utcnow()))
    announce([(task.submission_id, task.grading_round)])


def recover(db: Database) -> int:
    """At start-up: queue again the ``running`` submissions whose worker process has died on this host.

    Safe with many processes on one database: a claim held by a live process (here or on another
    host) is left alone; if that process dies, its lease runs out and :func:`requeue_expired` takes
    it back.
    """
    with db.write() as session:
        running = session.execute(select(Submission.id, Submission.worker_id, Submission.grading_round)
                                  .where(Submission.status == "running")).all()
        dead = [(row.id, row.worker_id, row.grading_round) for row in running if holder_is_dead(row.worker_id)]
        count = 0
        for submission_id, worker_id, grading_round in dead:
            count += session.execute(update(Submission).where(
                Submission.id == submission_id, Submission.status == "running", Submission.worker_id == worker_id)
                .values(status="queued", worker_id=None, lease_until=None)).rowcount
    if count:
        announce([(submission_id, grading_round) for submission_id, _, grading_round in dead])
    return count


def requeue_expired(db: Database, now: datetime | None = None) -> int:
    """Queue again the running submissions whose lease ran out (a stuck or vanished worker)."""
    now = now or utcnow()
    with db.write() as session:
        count = session.execute(update(Submission)
                                .where(Submission.status == "running", Submission.lease_until < now)
                                .values(status="queued", worker_id=None, lease_until=None)).rowcount
    if count:
        wake_workers()
    return count
