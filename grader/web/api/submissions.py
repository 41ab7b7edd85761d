"""Submissions: accepted at once (202, committed as queued), graded by the workers, polled by URL."""

from __future__ import annotations

from typing import Any

from flask import g, request, url_for
from sqlalchemy import select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from grader import jobs
from grader.store.assignments import pending_assignment
from grader.store.db import db
from grader.store.models import Course, ProblemVersion, Submission, User, Verdict
from grader.store.courses import CourseError, Member, add_member
from grader.store.users import reserved_external_id
from grader.web import clock
from grader.web.api import spec
from grader.web.api.problems import EVERYONE, visible_version
from grader.web.api.schemas import PARSED, SUBMISSION_REQUEST, read_json
from grader.web.errors import ApiProblem
from grader.web.policy import Action, Principal, current_principal, find_submission, may_act_for, require
from grader.web.student.verdicts import student_summary

__all__ = ["submission_json"]

MAX_KEY_CHARS = 200

VERDICT = spec.schema("Verdict", {"type": "object", "nullable": True, "properties": {
    "verdict": {"type": "string"}, "certainty": {"type": "string", "nullable": True},
    "score": {"type": "number"},
    "reason": {"type": "string", "nullable": True, "description": "The checker's technical account."},
    "summary": {"type": "string", "nullable": True,
                "description": "One sentence a student can act on when the feedback says nothing (else null)."},
    "feedback": {"nullable": True}, "counterexample": {"type": "object", "nullable": True},
    "parsed": {**PARSED, "nullable": True}, "ms": {"type": "number", "nullable": True},
    "graded_at": {"type": "string", "format": "date-time"},
    "version": {"type": "integer", "description": "The problem version whose references graded it."}}})
SUBMISSION = spec.schema("Submission", {"type": "object", "properties": {
    "id": {"type": "integer"}, "problem": {"type": "string"}, "version": {"type": "integer"},
    "answer": {"type": "string"}, "text": {"type": "string"},
    "status": {"type": "string", "enum": ["queued", "running", "done", "failed"]},
    "received_at": {"type": "string", "format": "date-time"}, "grading_round": {"type": "integer"},
    "user": {"type": "object", "properties": {"id": {"type": "integer"},
                                              "external_id": {"type": "string", "nullable": True}}},
    "verdict": VERDICT, "links": {"type": "object"}}})
_LOCATION = {"Location": {"schema": {"type": "string"}, "description": "Where to poll the submission."}}


def _time(value) -> str:
    return value.isoformat() + "Z"


# What a student may see of a counterexample: where their answer fails and what it gives there
# (for equations, at a second state too). An allow-list: anything else the checker records (the
# reference's values, their ratio or difference) is part of the reference.
STUDENT_COUNTEREXAMPLE_KEYS = ("values", "answer", "note", "other_state", "answer_there")


def _student_counterexample(example: dict | None) -> dict | None:
    if not example:
        return example
    return {k: v for k, v in example.items() if k in STUDENT_COUNTEREXAMPLE_KEYS}


def verdict_json(verdict: Verdict | None) -> dict[str, Any] | None:
    if verdict is None:
        return None
    example = verdict.counterexample or {}
    summary = None if verdict.feedback else student_summary(verdict.verdict, verdict.reason,
                                                            point=bool(example.get("values")))
    return {"verdict": verdict.verdict, "certainty": verdict.certainty, "score": verdict.score,
            "reason": verdict.reason, "summary": summary, "feedback": verdict.feedback,
            "counterexample": _student_counterexample(verdict.counterexample),
            "parsed": verdict.parsed, "ms": verdict.check_ms, "graded_at": _time(verdict.graded_at),
            "version": verdict.problem_version.number}


def submission_json(submission: Submission) -> dict[str, Any]:
    slug = submission.problem_version.problem.slug
    return {
        "id": submission.id, "problem": slug, "version": submission.problem_version.number,
        "answer": submission.answer_name, "text": submission.text, "status": submission.status,
        "received_at": _time(submission.received_at), "grading_round": submission.grading_round,
        "user": {"id": submission.user_id, "external_id": submission.user.external_id},
        "verdict": verdict_json(submission.verdict),
        "links": {"self": url_for("api.get_submission", submission_id=submission.id),
                  "problem": url_for("api.get_problem", slug=slug)},
    }


def _whose(session: Session, requester: User, version: ProblemVersion, external_id: str | None) -> User:
    """The student a submission is for: the caller, or the one named by ``user`` if the access policy
    lets the caller submit for that student (`grader.web.policy.may_act_for`)."""
    principal = current_principal()
    if external_id is None:
        if principal.role == "lms":
            raise ApiProblem(422, "An LMS token must say which student this is for in 'user'.", kind="invalid-request")
        return requester
    if principal.role == "student" and external_id == requester.external_id:
        return requester
    require(principal, Action.SUBMIT_FOR_OTHERS, version)  # a student naming someone else: 403
    # One answer for "unknown", "not yours" and "not a student": it tells nobody who exists here.
    not_yours = ApiProblem(422, f"{external_id!r} is not a student of your courses who may answer this problem "
                                "(enrol them in your course first).", kind="invalid-request")
    student = session.scalar(select(User).where(User.external_id == external_id))
    if student is None:
        student_id = _first_sight(principal, external_id)
        if student_id is None:
            raise not_yours
        session.commit()  # ends this read's snapshot (nothing to write), which began before the student was made
        student = session.get(User, student_id)
    if not may_act_for(principal, Principal.of(session, student), version):
        raise not_yours
    return student


def _first_sight(principal: Principal, external_id: str) -> int | None:
    """The id of the student an LMS linked to exactly one course names for the first time, made and
    enrolled there (as its roster would); None where that course is not known (an instructor, an LMS
    of several courses or none) or the id is one only an LTI launch may give."""
    if principal.role != "lms" or len(principal.enrolled) != 1 or reserved_external_id(external_id):
        return None
    (course_id,) = principal.enrolled
    member = Member(name=external_id, external_id=external_id, role="student")
    for _ in range(2):  # a concurrent request may make the same student first: then it exists
        try:
            with db.write() as writer:
                enrolment, _ = add_member(writer, writer.get(Course, course_id), member)
                return enrolment.user_id
        except IntegrityError:
            continue
        except CourseError:
            return None
    return None


def _not_in_an_open_assignment(session: Session, user: User, version: ProblemVersion) -> None:
    """Refuse (409) practice on a problem the student has in an assignment that is not closed yet."""
    assignment = pending_assignment(session, user.id, version.problem_id, clock.now())
    if assignment is not None:
        raise ApiProblem(409, f"This problem is part of assignment {assignment.slug!r} of course "
                              f"{assignment.course.code!r}: hand it in there "
                              f"(/api/v1/courses/{assignment.course.code}/assignments/{assignment.slug}/submissions) "
                              "until the assignment closes.", kind="in-assignment")


@spec.route("/problems/<slug>/submissions", "POST", roles=EVERYONE, errors=(400, 404, 409, 413, 415, 422, 429),
            rate_limit="submit",
            request={"application/json": spec.schema("SubmissionRequest", SUBMISSION_REQUEST)},
            parameters=[{"name": "Idempotency-Key", "in": "header", "required": False, "schema": {
                "type": "string", "minLength": 1, "maxLength": MAX_KEY_CHARS},
                "description": "Makes retries safe: the same key and body return the same submission; "
                               "the same key with another body is refused (422)."}],
            responses={202: ("Accepted: stored and queued for grading; poll the Location.",
                             {"application/json": SUBMISSION}),
                       200: ("A retry, or the same text sent again, already graded: the stored submission.",
                             {"application/json": SUBMISSION})},
            headers={202: _LOCATION, 200: _LOCATION})
def create_submission(slug: str):
    """Submit an answer for grading.

    The submission is committed before this returns; a worker grades it in the background. A text
    the grader cannot read is refused (422, ``unreadable-answer``, with the reader's ``error``:
    message, 0-based ``position``, 1-based ``column``) and is not an attempt; the same text the
    student already sent for this answer returns that submission (200 once graded) instead of a new one.
    """
    requester = g.api_user
    body = read_json(SUBMISSION_REQUEST)
    key = request.headers.get("Idempotency-Key")
    if key is not None and not (0 < len(key) <= MAX_KEY_CHARS):
        raise ApiProblem(422, f"An Idempotency-Key has 1 to {MAX_KEY_CHARS} characters.", kind="invalid-request")
    # Reads in a deferred transaction, the insert in a short write transaction of its own: on
    # SQLite the write lock is held only for the INSERT, not for this whole request.
    with db.read() as session:
        version = visible_version(slug, session, Action.SUBMIT)
        user = _whose(session, requester, version, body.get("user"))
        _not_in_an_open_assignment(session, user, version)
    try:
        submission_id, created = jobs.submit(db, user=user, requester=requester, version=version,
                                             answer=body["answer"], text=body["text"], idempotency_key=key)
    except jobs.AnswerUnreadable as error:  # a typo to fix, not an attempt: nothing was stored
        raise ApiProblem(422, str(error), kind="unreadable-answer", error=error.error) from None
    except jobs.SubmissionRejected as error:
        raise ApiProblem(422, str(error), kind="invalid-submission") from None
    except jobs.IdempotencyConflict as error:
        raise ApiProblem(422, str(error), kind="idempotency-key-reused") from None
    with db.read() as session:
        submission = submission_json(session.get(Submission, submission_id))
    pending = submission["status"] in ("queued", "running")
    location = url_for("api.get_submission", submission_id=submission_id)
    return submission, (202 if created or pending else 200), {"Location": location}


@spec.route("/submissions/<int:submission_id>", "GET", roles=EVERYONE, errors=(404,),
            responses={200: ("The submission, its status and its verdict once graded.",
                             {"application/json": SUBMISSION})})
def get_submission(submission_id: int):
    """Poll a submission (students: only their own; an LMS: those it sent; instructors: those of
    problems they manage)."""
    return submission_json(find_submission(db.session, current_principal(), submission_id))
