"""Handing in an answer for an assignment: the deadline and attempt rules, then the grading queue.

The rules (:mod:`grader.store.assignments`) are checked in the same write transaction that stores
the submission, with the student's row locked on PostgreSQL (SQLite has one writer at a time), so
two answers sent at once cannot both take a student's last attempt.
"""

from __future__ import annotations

from datetime import datetime

from sqlalchemy import select

from grader.answers.readable import read_error
from grader.jobs.queue import (MAX_ANSWER_CHARS, AnswerUnreadable, SubmissionRejected, _by_key, _fingerprint, _replay,
                               announce, same_attempt)
from grader.store.assignments import attempts_used, deadline_state, late_days, to_utc
from grader.store.db import Database
from grader.store.draws import draw_in
from grader.store.models import Assignment, AssignmentProblem, Submission, User

__all__ = ["HandInRefused", "hand_in"]


class HandInRefused(ValueError):
    """An answer the assignment's rules refuse now: ``reason`` is ``not_open``, ``closed`` or
    ``no_attempts_left``; the message says it in words."""

    def __init__(self, reason: str, message: str):
        super().__init__(message)
        self.reason = reason


def hand_in(database: Database, *, user: User, assignment_id: int, problem_id: int, answer: str, text: str,
            now: datetime, requester: User | None = None, secret: str = "",
            idempotency_key: str | None = None) -> tuple[int, int, bool]:
    """Store ``text`` as ``user``'s answer ``answer`` to problem ``problem_id`` of the assignment,
    received at ``now`` (the server's clock), queued for grading; returns (submission id, late days,
    created). With an ``idempotency_key`` (scoped to the requester), a retry of the same request returns
    the stored submission (``created`` False), even after the close; another request with the same key
    raises :class:`~grader.jobs.queue.IdempotencyConflict`.
    A randomised problem's parameter values for the student are drawn (from ``secret`` and the ids)
    if they were not yet, so the worker grades with the numbers the student was shown.

    Raises :class:`HandInRefused` outside the assignment's window or past the attempt limit, and
    :class:`~grader.jobs.queue.SubmissionRejected` for an unknown answer or an over-long text.
    """
    received = to_utc(now) if now.tzinfo is not None else now
    if len(text) > MAX_ANSWER_CHARS:
        raise SubmissionRejected(f"the answer is {len(text)} characters long; the limit is {MAX_ANSWER_CHARS}")
    with database.write() as session:
        if session.bind.dialect.name == "postgresql":
            session.execute(select(User.id).where(User.id == user.id).with_for_update())
        assignment = session.get(Assignment, assignment_id)
        item = session.scalar(select(AssignmentProblem).where(AssignmentProblem.assignment_id == assignment_id,
                                                              AssignmentProblem.problem_id == problem_id))
        if assignment is None or item is None:
            raise SubmissionRejected("this problem is not part of this assignment")
        version = item.problem_version
        if idempotency_key is not None:
            existing = _by_key(session, (requester or user).id, idempotency_key)
            if existing is not None:
                replayed = _replay(existing, _fingerprint(version, user.id, answer, text))
                return replayed, late_days(assignment, existing.received_at), False
        reference = version.reference(answer)
        if reference is None:
            names = ", ".join(r["name"] for r in version.references)
            raise SubmissionRejected(f"this problem has no answer {answer!r}; its answers: {names}")
        # As for practice (grader.jobs.queue.submit): an unreadable text is a typo to fix and the
        # same text again is the same attempt; neither uses up an attempt.
        unreadable = read_error(reference, text)
        if unreadable is not None:
            raise AnswerUnreadable(unreadable)
        earlier = same_attempt(session, user.id, version.id, answer, text, assignment_id=assignment_id)
        if earlier is not None:
            return earlier.id, late_days(assignment, earlier.received_at), False
        state = deadline_state(assignment, received)
        if state == "not_open":
            raise HandInRefused(state, "This assignment is not open yet.")
        if state == "closed":
            raise HandInRefused(state, "This assignment is closed: no more submissions are accepted.")
        if assignment.max_attempts is not None and attempts_used(
                session, assignment_id, user.id, problem_id, answer) >= assignment.max_attempts:
            raise HandInRefused("no_attempts_left", f"No attempts left for this answer (the limit is "
                                                    f"{assignment.max_attempts}).")
        draw_in(session, assignment_id, user.id, item, secret)
        submission = Submission(user_id=user.id, requester_id=(requester or user).id, problem_version_id=version.id,
                                grading_version_id=version.id, answer_name=answer, text=text, status="queued",
                                received_at=received, assignment_id=assignment_id,
                                idempotency_key=idempotency_key,
                                request_sha256=_fingerprint(version, user.id, answer, text))
        session.add(submission)
        session.flush()
        submission_id, late = submission.id, late_days(assignment, received)
    announce([(submission_id, 1)])
    return submission_id, late, True
