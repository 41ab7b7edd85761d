"""Courses: enrolment, assignments with deadlines, hand-ins and the gradebook.

Instructors of a course manage it (members, assignments, releasing solutions); its teaching
assistants read its gradebook; its students see their own assignments and scores. Who may do what
is the access policy's (:mod:`grader.web.policy`); the deadline and attempt rules are the store's
(:mod:`grader.store.assignments`), read against the server's one clock (:mod:`grader.web.clock`);
every score comes from :mod:`grader.store.scores`.
"""

from __future__ import annotations

from datetime import datetime
from typing import Any

from flask import current_app, g, request, url_for
from sqlalchemy.exc import IntegrityError

from grader.jobs.assignment_submissions import HandInRefused, hand_in
from grader.jobs.queue import MAX_ANSWER_CHARS, AnswerUnreadable, IdempotencyConflict, SubmissionRejected
from grader.store.assignments import MAX_ATTEMPTS, MAX_PROBLEMS, AssignmentError, create_assignment
from grader.store.courses import (COURSE_CODE_CHARS, COURSE_CODE_PATTERN, CourseError, Member, add_member,
                                   check_course_code, create_course, parse_roster, roster)
from grader.store.db import db
from grader.store.models import (ENROLMENT_ROLES, SCORE_POLICIES, Assignment, Course, Problem, Submission, User)
from grader.web import clock
from grader.web.api import spec
from grader.web.api.schemas import NAME_PATTERN
from grader.web.api.submissions import _LOCATION, MAX_KEY_CHARS, SUBMISSION, submission_json
from grader.web.coursework import GRADEBOOK_COLUMNS, assignment_view, gradebook_rows, stamp
from grader.web.csv_export import csv_response
from grader.web.errors import ApiProblem
from grader.web.policy import (API_ROLES, INSTRUCTOR_ROLES, Action, allowed, current_principal, find_assignment,
                               find_course, my_courses, require)

__all__ = ["course_json"]

PEOPLE = API_ROLES - {"lms"}  # TAs may hold student accounts; the policy decides per course
MAX_ROSTER_BYTES = 512 * 1024
_CODE = {"type": "string", "minLength": 1, "maxLength": COURSE_CODE_CHARS, "pattern": COURSE_CODE_PATTERN}
_SLUG = {"type": "string", "minLength": 1, "maxLength": Assignment.__table__.c.slug.type.length,
         "pattern": "^[A-Za-z0-9][A-Za-z0-9_.-]*$"}
_TITLE = {"type": "string", "minLength": 1, "maxLength": Course.__table__.c.title.type.length}
_TIME = {"type": "string", "format": "date-time", "maxLength": 40,
         "pattern": r"^\d{4}-\d\d-\d\dT\d\d:\d\d(:\d\d(\.\d{1,6})?)?(Z|[+-]\d\d:\d\d)$",
         "description": "ISO 8601 with an offset, e.g. 2026-12-01T17:00:00+01:00."}

COURSE_REQUEST = {"type": "object", "required": ["code", "title"], "additionalProperties": False,
                  "properties": {"code": _CODE, "title": _TITLE}}
MEMBER_REQUEST = {"type": "object", "required": ["name"], "additionalProperties": False,
                  "anyOf": [{"required": ["email"]}, {"required": ["external_id"]}],
                  "properties": {
                      "email": {"type": "string", "format": "email", "maxLength": User.__table__.c.email.type.length,
                                "pattern": "^[^@\\s]+@[^@\\s]+$"},
                      "external_id": {"type": "string", "minLength": 1,
                                      "maxLength": User.__table__.c.external_id.type.length},
                      "name": {"type": "string", "maxLength": User.__table__.c.name.type.length},
                      "role": {"type": "string", "enum": list(ENROLMENT_ROLES), "default": "student"}}}
ASSIGNMENT_REQUEST = {
    "type": "object", "additionalProperties": False,
    "required": ["id", "title", "problems", "opens_at", "due_at"],
    "properties": {
        "id": _SLUG, "title": _TITLE,
        "problems": {"type": "array", "minItems": 1, "maxItems": MAX_PROBLEMS, "uniqueItems": True,
                     "items": {"type": "string", "minLength": 1, "maxLength": Problem.__table__.c.slug.type.length},
                     "description": "Problem ids, in order; each is pinned to its newest published version."},
        "opens_at": _TIME, "due_at": _TIME, "closes_at": {**_TIME, "nullable": True},
        "time_zone": {"type": "string", "maxLength": 64, "default": "UTC",
                      "description": "IANA name the pages show times in, e.g. Europe/Paris."},
        "max_attempts": {"type": "integer", "nullable": True, "minimum": 1, "maximum": MAX_ATTEMPTS,
                         "description": "Per answer; null: unlimited."},
        "late_penalty_per_day": {"type": "number", "minimum": 0, "maximum": 1, "default": 0,
                                 "description": "Fraction of the score each started day late costs (needs closes_at)."},
        "score_policy": {"type": "string", "enum": list(SCORE_POLICIES), "default": "best"}}}
HAND_IN_REQUEST = {"type": "object", "required": ["problem", "answer", "text"], "additionalProperties": False,
                   "properties": {"problem": {"type": "string", "minLength": 1,
                                              "maxLength": Problem.__table__.c.slug.type.length},
                                  "answer": {"type": "string", "pattern": NAME_PATTERN,
                                             "maxLength": Submission.__table__.c.answer_name.type.length},
                                  "text": {"type": "string", "maxLength": MAX_ANSWER_CHARS}}}

COURSE = spec.schema("Course", {"type": "object", "properties": {
    "code": {"type": "string"}, "title": {"type": "string"}, "role": {"type": "string", "nullable": True},
    "assignments": {"type": "array", "items": {"type": "object"}},
    "members": {"type": "array", "items": {"type": "object"}, "description": "Instructors and TAs only."},
    "links": {"type": "object"}}})
ASSIGNMENT = spec.schema("Assignment", {"type": "object", "properties": {
    "id": {"type": "string"}, "title": {"type": "string"}, "course": {"type": "string"},
    "time_zone": {"type": "string"}, "opens_at": {"type": "string", "format": "date-time"},
    "due_at": {"type": "string", "format": "date-time"},
    "closes_at": {"type": "string", "format": "date-time", "nullable": True},
    "state": {"type": "string", "enum": ["not_open", "open", "late", "closed"]},
    "max_attempts": {"type": "integer", "nullable": True}, "late_penalty_per_day": {"type": "number"},
    "score_policy": {"type": "string"}, "solutions_available": {"type": "boolean"},
    "rules": {"type": "array", "items": {"type": "string"}},
    "score": {"type": "number", "description": "Students: their total (each problem is out of 1)."},
    "problems": {"type": "array", "items": {"type": "object", "description":
                 "id, title, statement, answers (students: attempts_used, attempts_left, score), "
                 "students: parameters (their own values) and score; solution once available."}}}})
GRADEBOOK = spec.schema("Gradebook", {"type": "object", "properties": {
    "course": {"type": "string"},
    "rows": {"type": "array", "items": {"type": "object", "properties": {
        name: {"type": kind, "nullable": True} for name, kind in zip(GRADEBOOK_COLUMNS, [
            "string", "string", "integer", "string", "string", "string", "string", "number", "integer",
            "integer", "integer"])}}}}})
_REFUSED = {"not_open": 409, "closed": 409, "no_attempts_left": 409}


def _time(text: str | None) -> datetime | None:
    if text is None:
        return None
    try:
        return datetime.fromisoformat(text.replace("Z", "+00:00"))
    except ValueError:
        raise ApiProblem(422, f"{text!r} is not an ISO 8601 time.", kind="invalid-request") from None


def _role_in(course: Course) -> str | None:
    principal = current_principal()
    for enrolment in course.enrolments:
        if enrolment.user_id == principal.user_id:
            return enrolment.role
    return None


def course_json(course: Course, *, members: bool) -> dict[str, Any]:
    body: dict[str, Any] = {
        "code": course.code, "title": course.title, "role": _role_in(course),
        "assignments": [{"id": a.slug, "title": a.title, "opens_at": stamp(a, a.opens_at), "due_at": stamp(a, a.due_at),
                         "links": {"self": url_for("api.get_assignment", code=course.code, assignment=a.slug)}}
                        for a in course.assignments],
        "links": {"self": url_for("api.get_course", code=course.code),
                  "gradebook": url_for("api.get_gradebook", code=course.code)},
    }
    if members:
        body["members"] = [_member_json(e) for e in roster(db.session, course)]
    return body


def _member_json(enrolment) -> dict[str, Any]:
    user = enrolment.user
    return {"user_id": user.id, "name": user.name, "email": user.email, "external_id": user.external_id,
            "role": enrolment.role}


@spec.route("/courses", "POST", roles=INSTRUCTOR_ROLES, errors=(400, 409, 413, 415, 422),
            request={"application/json": spec.schema("CourseRequest", COURSE_REQUEST)},
            responses={201: ("The course; its creator teaches it.", {"application/json": COURSE})})
def create_course_route():
    """Create a course (instructors); the caller becomes its instructor."""
    require(current_principal(), Action.CREATE_COURSE, None)
    body = g.api_body
    try:
        check_course_code(body["code"])  # what the schema's pattern lets by ("MECH\n")
    except CourseError as error:
        raise ApiProblem(422, str(error), kind="invalid-request") from None
    try:
        with db.write() as session:
            course = create_course(session, code=body["code"], title=body["title"],
                                   instructor=session.get(User, g.api_user.id))
            code = course.code
    except (CourseError, IntegrityError) as error:
        raise ApiProblem(409, str(error) if isinstance(error, CourseError) else
                         f"There is already a course {body['code']!r}.", kind="conflict") from None
    g.pop("_principal", None)  # the caller teaches a course now: their principal is read again
    found = find_course(db.session, current_principal(), code)
    return course_json(found, members=True), 201, {"Location": url_for("api.get_course", code=code)}


@spec.route("/courses", "GET", roles=API_ROLES,
            responses={200: ("The courses the caller is in.", {"application/json": {
                "type": "object", "properties": {"courses": {"type": "array", "items": COURSE}}}})})
def list_courses():
    """The courses the caller is enrolled in (any role)."""
    return {"courses": [course_json(c, members=False) for c in my_courses(db.session, current_principal())]}


@spec.route("/courses/<code>", "GET", roles=API_ROLES, errors=(404,),
            responses={200: ("The course, its assignments, and (instructors, TAs) its members.",
                             {"application/json": COURSE})})
def get_course(code: str):
    """A course: its assignments; its roster for its instructors and TAs."""
    principal = current_principal()
    course = find_course(db.session, principal, code)
    return course_json(course, members=allowed(principal, Action.GRADE_COURSE, course))


@spec.route("/courses/<code>/members", "POST", roles=INSTRUCTOR_ROLES, errors=(400, 404, 413, 415, 422),
            request={"application/json": spec.schema("MemberRequest", MEMBER_REQUEST),
                     "text/csv": {"type": "string", "description": "A roster: a header line naming email, name, "
                                                                   "external_id (role optional), one person a line."}},
            responses={201: ("The members added (accounts are created for unknown people).", {"application/json": {
                "type": "object", "properties": {"members": {"type": "array", "items": {"type": "object"}},
                                                 "created_accounts": {"type": "integer"}}}})})
def add_members(code: str):
    """Enrol one person (JSON) or a CSV roster (instructors of the course).

    Enrolling someone already in the course changes their role. A roster with any bad line adds
    nobody, and the problem lists every bad line.
    """
    principal = current_principal()
    with db.read() as session:
        course_id = find_course(session, principal, code, Action.MANAGE_COURSE).id
    if request.mimetype == "text/csv":
        if (request.content_length or 0) > MAX_ROSTER_BYTES:
            raise ApiProblem(413, f"A roster may be at most {MAX_ROSTER_BYTES // 1024} KiB.", kind="too-large")
        try:
            members = parse_roster(request.get_data(as_text=True))
        except CourseError as error:
            raise ApiProblem(422, str(error), kind="invalid-roster") from None
    else:
        body = g.api_body
        members = [Member(name=body.get("name") or "", email=body.get("email"), external_id=body.get("external_id"),
                          role=body.get("role", "student"))]
    added, created = [], 0
    try:
        with db.write() as session:
            course = session.get(Course, course_id)
            for member in members:
                enrolment, new = add_member(session, course, member)
                created += new
                added.append(_member_json(enrolment))
    except CourseError as error:
        raise ApiProblem(422, str(error), kind="invalid-member") from None
    return {"members": added, "created_accounts": created}, 201


@spec.route("/courses/<code>/assignments", "POST", roles=INSTRUCTOR_ROLES, errors=(400, 404, 409, 413, 415, 422),
            request={"application/json": spec.schema("AssignmentRequest", ASSIGNMENT_REQUEST)},
            responses={201: ("The assignment.", {"application/json": ASSIGNMENT})})
def create_assignment_route(code: str):
    """Build an assignment of published problems (instructors of the course)."""
    principal = current_principal()
    body = g.api_body
    with db.read() as session:
        course_id = find_course(session, principal, code, Action.MANAGE_COURSE).id
    try:
        with db.write() as session:
            create_assignment(session, session.get(Course, course_id), slug=body["id"], title=body["title"],
                              problems=body["problems"], opens_at=_time(body["opens_at"]), due_at=_time(body["due_at"]),
                              closes_at=_time(body.get("closes_at")), time_zone=body.get("time_zone", "UTC"),
                              max_attempts=body.get("max_attempts"),
                              late_penalty_per_day=float(body.get("late_penalty_per_day", 0.0)),
                              score_policy=body.get("score_policy", "best"))
    except AssignmentError as error:
        raise ApiProblem(422, str(error), kind="invalid-assignment") from None
    except IntegrityError:
        raise ApiProblem(409, f"The course already has an assignment {body['id']!r}.", kind="conflict") from None
    assignment = find_assignment(db.session, principal, code, body["id"])
    location = url_for("api.get_assignment", code=code, assignment=body["id"])
    return assignment_view(db.session, assignment, clock.now(), student=None), 201, {"Location": location}


def _student_or_none(assignment: Assignment) -> User | None:
    """The caller as a student of the assignment's course, or None for its graders (and admins)."""
    principal = current_principal()
    if allowed(principal, Action.GRADE_COURSE, assignment):
        return None
    return db.session.get(User, principal.user_id)


@spec.route("/courses/<code>/assignments/<assignment>", "GET", roles=API_ROLES, errors=(404,),
            responses={200: ("The assignment as the caller sees it.", {"application/json": ASSIGNMENT})})
def get_assignment(code: str, assignment: str):
    """An assignment: its times, rules and problems; a student also gets their own parameter values,
    attempts left and scores, and the worked solutions once it closes or they are released."""
    found = find_assignment(db.session, current_principal(), code, assignment)
    return assignment_view(db.session, found, clock.now(), student=_student_or_none(found))


@spec.route("/courses/<code>/assignments/<assignment>/release", "POST", roles=INSTRUCTOR_ROLES, errors=(404,),
            responses={200: ("Solutions are released.", {"application/json": ASSIGNMENT})})
def release_solutions(code: str, assignment: str):
    """Show the assignment's worked solutions to its students now, before it closes (instructors)."""
    found = find_assignment(db.session, current_principal(), code, assignment, Action.MANAGE_COURSE)
    found.solutions_released = True
    db.session.commit()
    return assignment_view(db.session, found, clock.now(), student=None)


@spec.route("/courses/<code>/assignments/<assignment>/submissions", "POST", roles=API_ROLES,
            errors=(400, 404, 409, 413, 415, 422, 429), rate_limit="submit",
            request={"application/json": spec.schema("HandInRequest", HAND_IN_REQUEST)},
            parameters=[{"name": "Idempotency-Key", "in": "header", "required": False, "schema": {
                "type": "string", "minLength": 1, "maxLength": MAX_KEY_CHARS},
                "description": "Makes retries safe: the same key and body return the same submission (even "
                               "after the close, and without using an attempt); another body is refused (422)."}],
            responses={202: ("Accepted: stored and queued for grading; poll the Location.",
                             {"application/json": SUBMISSION}),
                       200: ("A retry of a request already handed in: the stored submission.",
                             {"application/json": SUBMISSION})},
            headers={202: _LOCATION, 200: _LOCATION})
def hand_in_route(code: str, assignment: str):
    """Hand in an answer for an assignment (its students).

    Refused with 409 before the assignment opens, after it closes, or when the answer has no
    attempts left; between the due time and the close it is accepted as late (the penalty applies
    to its score). The submission's ``late_days`` says how late it was.
    """
    principal = current_principal()
    body = g.api_body
    with db.read() as session:
        found = find_assignment(session, principal, code, assignment)
        item = next((p for p in found.problems if p.problem.slug == body["problem"]), None)
        if item is None:
            raise ApiProblem(404, f"Assignment {assignment!r} has no problem {body['problem']!r}.", kind="not-found")
        require(principal, Action.SUBMIT, item.problem_version)
        assignment_id, problem_id = found.id, item.problem_id
    if principal.role == "lms" or allowed(principal, Action.GRADE_COURSE, found):
        raise ApiProblem(403, "Only the course's students hand in answers for its assignments.", kind="forbidden")
    try:
        submission_id, late, created = hand_in(
            db, user=g.api_user, assignment_id=assignment_id, problem_id=problem_id, answer=body["answer"],
            text=body["text"], now=clock.now(), secret=current_app.config["SECRET_KEY"],
            idempotency_key=request.headers.get("Idempotency-Key"))
    except HandInRefused as refused:
        raise ApiProblem(_REFUSED[refused.reason], str(refused), kind=refused.reason.replace("_", "-")) from None
    except AnswerUnreadable as error:  # a typo to fix, not an attempt: nothing was stored
        raise ApiProblem(422, str(error), kind="unreadable-answer", error=error.error) from None
    except SubmissionRejected as error:
        raise ApiProblem(422, str(error), kind="invalid-submission") from None
    except IdempotencyConflict as error:
        raise ApiProblem(422, str(error), kind="idempotency-key-reused") from None
    with db.read() as session:
        submission = submission_json(session.get(Submission, submission_id))
    submission.update(assignment=assignment, late_days=late)
    pending = submission["status"] in ("queued", "running")
    return submission, (202 if created or pending else 200), {
        "Location": url_for("api.get_submission", submission_id=submission_id)}


@spec.route("/courses/<code>/gradebook", "GET", roles=API_ROLES, errors=(404,),
            parameters=[{"name": "format", "in": "query", "schema": {"type": "string", "enum": ["json", "csv"]},
                         "description": "csv for a spreadsheet."},
                        {"name": "assignment", "in": "query", "schema": _SLUG,
                         "description": "Only this assignment."}],
            responses={200: ("One row per assignment, student and problem (students: their own rows).", {
                "application/json": GRADEBOOK,
                "text/csv": {"type": "string", "description": f"Columns: {', '.join(GRADEBOOK_COLUMNS)}."}})})
def get_gradebook(code: str):
    """The gradebook of a course: every student × every problem of its assignments, with the score
    (under each assignment's policy and late penalty), attempts and late days.

    Instructors and TAs get every student; a student gets their own rows. The CSV has the same
    rows and numbers as the JSON.
    """
    principal = current_principal()
    course = find_course(db.session, principal, code)
    grader_view = allowed(principal, Action.GRADE_COURSE, course)
    if principal.role == "lms" and not grader_view:
        raise ApiProblem(403, "An LMS reads grades per problem (/problems/{id}/grades).", kind="forbidden")
    assignments = list(course.assignments)
    only = request.args.get("assignment")
    if only is not None:
        assignments = [a for a in assignments if a.slug == only]
        if not assignments:
            raise ApiProblem(404, f"There is no assignment {only!r} in course {code!r}.", kind="not-found")
    rows = gradebook_rows(db.session, assignments, user_id=None if grader_view else principal.user_id)
    if request.args.get("format") == "csv":
        return csv_response(rows, f"{code}-gradebook.csv", header=GRADEBOOK_COLUMNS)
    return {"course": code, "rows": rows}
