"""Courses and who is in them: creating a course, enrolling people one by one or from a CSV roster.

A member is found by e-mail or by external id (an LMS's or the registrar's), and created as a
sign-in-less account when unknown (they sign in once an administrator sets a password, or come
through the LMS). Enrolling someone again changes their role in the course; nobody is enrolled
twice.
"""

from __future__ import annotations

import csv
import io
import re
from dataclasses import dataclass

from sqlalchemy import func, select
from sqlalchemy.orm import Session, joinedload

from grader.store.models import ENROLMENT_ROLES, Course, Enrolment, User
from grader.store.users import LTI_PREFIX, reserved_external_id

__all__ = ["COURSE_CODE_CHARS", "COURSE_CODE_PATTERN", "CourseError", "Member", "ROSTER_COLUMNS", "MAX_ROSTER_ROWS",
           "add_member", "check_course_code", "course_by_code", "create_course", "parse_roster", "roster"]

ROSTER_COLUMNS = ("email", "name", "external_id", "role")  # a roster's header names these (role optional)
MAX_ROSTER_ROWS = 2000
_EMAIL_CHARS = User.__table__.c.email.type.length
_NAME_CHARS = User.__table__.c.name.type.length
_EXTERNAL_CHARS = User.__table__.c.external_id.type.length
# A course code goes into URLs and CSV file names: ASCII letters and digits, with - _ . inside.
# The API's schema shows the same pattern; check_course_code is the rule every way in applies.
COURSE_CODE_PATTERN = "^[A-Za-z0-9][A-Za-z0-9_.-]*$"
COURSE_CODE_CHARS = Course.__table__.c.code.type.length


class CourseError(ValueError):
    """A request about a course that cannot be done (taken code, bad roster line); says why."""


@dataclass(frozen=True)
class Member:
    """One line of a roster, or one person added by hand."""

    name: str
    email: str | None = None
    external_id: str | None = None
    role: str = "student"


def course_by_code(session: Session, code: str) -> Course | None:
    return session.scalar(select(Course).where(Course.code == code))


def check_course_code(code: str) -> str:
    """``code`` if it is a course code, else CourseError saying what one is.

    Examples
    --------
    >>> check_course_code("MECH-2026")
    'MECH-2026'
    >>> check_course_code("-x")
    Traceback (most recent call last):
    ...
    grader.store.courses.CourseError: '-x' is not a course code: a code is 1 to 64 ASCII letters, digits, ...
    """
    # fullmatch: a "$" alone would let a code end in a newline
    if not isinstance(code, str) or len(code) > COURSE_CODE_CHARS or not re.fullmatch(COURSE_CODE_PATTERN, code):
        raise CourseError(f"{code!r} is not a course code: a code is 1 to {COURSE_CODE_CHARS} ASCII letters, digits, "
                          f"- _ or ., starting with a letter or a digit.")
    return code


def create_course(session: Session, *, code: str, title: str, instructor: User | None = None) -> Course:
    """A new course; ``instructor`` (its creator) teaches it.

    Raises CourseError if ``code`` is no course code (:func:`check_course_code`) or is taken, in any
    case: ``other`` beside ``OTHER`` would be two courses a person tells apart by case alone.
    """
    check_course_code(code)
    taken = session.scalar(select(Course.code).where(func.lower(Course.code) == code.lower()).limit(1))
    if taken is not None:
        raise CourseError(f"There is already a course {taken!r}; codes that differ only in case are one code, "
                          f"choose another.")
    course = Course(code=code, title=title)
    session.add(course)
    session.flush()
    if instructor is not None:
        session.add(Enrolment(user_id=instructor.id, course_id=course.id, role="instructor"))
        session.flush()
    return course


def add_member(session: Session, course: Course, member: Member) -> tuple[Enrolment, bool]:
    """Enrol ``member`` in ``course`` (creating their account if unknown); returns (enrolment, new account).

    Examples
    --------
    >>> Member(name="Ada", email="ada@example.org").role
    'student'
    """
    if member.role not in ENROLMENT_ROLES:
        raise CourseError(f"A member's role is one of {', '.join(ENROLMENT_ROLES)}, not {member.role!r}.")
    if not (member.email or member.external_id):
        raise CourseError("Give each member an e-mail address or an external id.")
    if reserved_external_id(member.external_id):
        raise CourseError(f"External ids starting with {LTI_PREFIX!r} are made by LTI launches; give the member "
                          "their id in your LMS or an e-mail address.")
    user = None
    if member.email:
        user = session.scalar(select(User).where(User.email == member.email))
    if user is None and member.external_id:
        user = session.scalar(select(User).where(User.external_id == member.external_id))
    created = user is None
    if user is None:
        user = User(role="student" if member.role == "student" else "instructor", name=member.name or
                    member.email or member.external_id, email=member.email, external_id=member.external_id)
        session.add(user)
        session.flush()
    elif user.role == "lms":
        raise CourseError(f"{member.email or member.external_id!r} is an LMS account, not a person.")
    enrolment = session.scalar(select(Enrolment).where(Enrolment.user_id == user.id,
                                                       Enrolment.course_id == course.id))
    if enrolment is None:
        enrolment = Enrolment(user_id=user.id, course_id=course.id, role=member.role)
        session.add(enrolment)
    else:
        enrolment.role = member.role
    session.flush()
    return enrolment, created


def parse_roster(text: str) -> list[Member]:
    """The members listed by a CSV roster: a header naming ``email``, ``name``, ``external_id`` (any
    order; ``role`` optional, default student), then one person a line. Every bad line is reported
    at once, by its line number, and nothing is returned for a roster with any.

    Examples
    --------
    >>> parse_roster("email,name,external_id\\nada@example.org,Ada Lovelace,s1\\n")
    [Member(name='Ada Lovelace', email='ada@example.org', external_id='s1', role='student')]
    """
    reader = csv.DictReader(io.StringIO(text.lstrip("\ufeff")))
    header = [h.strip().lower() for h in (reader.fieldnames or [])]
    if "name" not in header or not ({"email", "external_id"} & set(header)):
        raise CourseError("The roster's first line names its columns: email, name, external_id (role optional).")
    reader.fieldnames = header
    members, problems = [], []
    for row in reader:
        line = reader.line_num
        if len(members) >= MAX_ROSTER_ROWS:
            raise CourseError(f"A roster has at most {MAX_ROSTER_ROWS} people; split it.")
        if None in row:
            problems.append(f"line {line}: more fields than the header names")
            continue
        values = {k: (row.get(k) or "").strip() for k in ROSTER_COLUMNS}
        if not any(values.values()):
            continue  # a blank line
        email, external_id = values["email"] or None, values["external_id"] or None
        problem = _roster_problem(values, email, external_id)
        if problem:
            problems.append(f"line {line}: {problem}")
            continue
        members.append(Member(name=values["name"], email=email, external_id=external_id,
                              role=values["role"].lower() or "student"))
    if problems:
        raise CourseError("The roster was not imported: " + "; ".join(problems[:10]) +
                          (f" (and {len(problems) - 10} more)" if len(problems) > 10 else ""))
    return members


def _roster_problem(values: dict[str, str], email: str | None, external_id: str | None) -> str | None:
    if not (email or external_id):
        return "no email and no external_id"
    if email and ("@" not in email or len(email) > _EMAIL_CHARS):
        return f"{email[:40]!r} is not an e-mail address"
    if external_id and len(external_id) > _EXTERNAL_CHARS:
        return f"the external_id is longer than {_EXTERNAL_CHARS} characters"
    if len(values["name"]) > _NAME_CHARS:
        return f"the name is longer than {_NAME_CHARS} characters"
    if values["role"] and values["role"].lower() not in ENROLMENT_ROLES:
        return f"the role is one of {', '.join(ENROLMENT_ROLES)}"
    return None


def roster(session: Session, course: Course) -> list[Enrolment]:
    """Everyone in ``course`` (instructors, TAs, then students; LMS links left out), by name."""
    order = {"instructor": 0, "ta": 1, "student": 2}
    enrolments = session.scalars(select(Enrolment).options(joinedload(Enrolment.user))
                                 .where(Enrolment.course_id == course.id, Enrolment.role.in_(ENROLMENT_ROLES)))
    return sorted(enrolments, key=lambda e: (order[e.role], e.user.name.lower(), e.user_id))
