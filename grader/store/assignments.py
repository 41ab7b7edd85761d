"""Assignments: their rules (when they open, are due and close, what a late day costs, how many
attempts an answer gets) and making one.

Every rule is a function of the assignment and a moment ``now`` that the caller passes in (the web
layer's one injectable clock), so tests can stand on the boundary second. The rules, in one place:

- before ``opens_at`` nothing is accepted (``not_open``);
- up to and including ``due_at`` a submission is on time (``open``);
- after ``due_at`` and up to and including ``closes_at`` it is late (``late``): each *started* day
  after ``due_at`` costs ``late_penalty_per_day`` of its score (never below zero);
- after ``closes_at`` (after ``due_at`` when there is no ``closes_at``) it is refused (``closed``),
  and the worked solutions are shown; an instructor may release them earlier, which closes it
  then (a solution on the page and hand-ins still accepted would be full marks for copying it).
- each answer of each problem gets ``max_attempts`` submissions (None: unlimited).

Times are naive UTC (as every stored time); ``time_zone`` is how pages state them.
"""

from __future__ import annotations

import math
from datetime import datetime, timedelta, timezone
from zoneinfo import ZoneInfo, ZoneInfoNotFoundError

from sqlalchemy import func, select
from sqlalchemy.orm import Session

from grader.store.models import SCORE_POLICIES, Assignment, AssignmentProblem, Course, Enrolment, Problem, Submission
from grader.store.problems import latest_version, problem_by_slug

__all__ = ["AssignmentError", "MAX_ATTEMPTS", "MAX_PROBLEMS", "assignment_by_slug", "attempts_used", "create_assignment",
           "deadline_state", "late_days", "late_factor", "local_time", "pending_assignment", "solutions_open",
           "unopened_problems",
           "to_utc", "zone"]

DAY = timedelta(days=1)
MAX_PROBLEMS = 50
MAX_ATTEMPTS = 1000  # per answer; beyond it, "unlimited" (None) says it (and the column is 32-bit on PostgreSQL)


class AssignmentError(ValueError):
    """An assignment that cannot be made as asked (dates out of order, unknown problem); says why."""


def to_utc(moment: datetime) -> datetime:
    """``moment`` (aware, any offset) as the naive UTC the store keeps.

    Examples
    --------
    >>> to_utc(datetime.fromisoformat("2026-12-01T17:00:00+01:00"))
    datetime.datetime(2026, 12, 1, 16, 0)
    """
    if moment.tzinfo is None:
        raise AssignmentError("A time needs its offset from UTC (e.g. 2026-12-01T17:00:00+01:00).")
    return moment.astimezone(timezone.utc).replace(tzinfo=None)


def zone(name: str) -> ZoneInfo:
    """The IANA time zone ``name`` (AssignmentError if unknown)."""
    try:
        return ZoneInfo(name)
    except (ZoneInfoNotFoundError, ValueError):
        raise AssignmentError(f"{name[:64]!r} is not a time zone (use an IANA name such as Europe/Paris).") from None


def local_time(assignment: Assignment, moment: datetime | None) -> datetime | None:
    """A stored (naive UTC) ``moment`` in the assignment's time zone, aware."""
    if moment is None:
        return None
    return moment.replace(tzinfo=timezone.utc).astimezone(zone(assignment.time_zone))


def _naive(now: datetime) -> datetime:
    return to_utc(now) if now.tzinfo is not None else now


def closing(assignment: Assignment) -> datetime:
    """The last moment a submission is accepted (naive UTC)."""
    return assignment.closes_at or assignment.due_at


def deadline_state(assignment: Assignment, now: datetime) -> str:
    """``not_open``, ``open``, ``late`` or ``closed`` at ``now`` (aware, or naive UTC).

    Examples
    --------
    >>> a = Assignment(opens_at=datetime(2026, 12, 1), due_at=datetime(2026, 12, 8), closes_at=datetime(2026, 12, 10))
    >>> [deadline_state(a, datetime(2026, 12, d)) for d in (1, 8, 9, 10, 11)]
    ['open', 'open', 'late', 'late', 'closed']
    >>> a.solutions_released = True  # the solutions are shown: nothing more is handed in
    >>> deadline_state(a, datetime(2026, 12, 8))
    'closed'
    """
    now = _naive(now)
    if assignment.solutions_released:
        return "closed"
    if now < assignment.opens_at:
        return "not_open"
    if now <= assignment.due_at:
        return "open"
    if now <= closing(assignment):
        return "late"
    return "closed"


def late_days(assignment: Assignment, received_at: datetime) -> int:
    """Started days after the due time at ``received_at`` (0 when on time).

    Examples
    --------
    >>> a = Assignment(opens_at=datetime(2026, 12, 1), due_at=datetime(2026, 12, 8), closes_at=None)
    >>> [late_days(a, a.due_at + timedelta(seconds=s)) for s in (0, 1, 86400, 86401)]
    [0, 1, 1, 2]
    """
    late = _naive(received_at) - assignment.due_at
    if late <= timedelta(0):
        return 0
    return math.ceil(late / DAY)


def late_factor(assignment: Assignment, received_at: datetime) -> float:
    """What fraction of its score a submission received at ``received_at`` keeps (1.0 on time).

    Examples
    --------
    >>> a = Assignment(opens_at=datetime(2026, 12, 1), due_at=datetime(2026, 12, 8), late_penalty_per_day=0.25)
    >>> [late_factor(a, a.due_at + timedelta(hours=h)) for h in (0, 1, 25, 200)]
    [1.0, 0.75, 0.5, 0.0]
    """
    return max(0.0, 1.0 - (assignment.late_penalty_per_day or 0.0) * late_days(assignment, received_at))


def solutions_open(assignment: Assignment, now: datetime) -> bool:
    """Whether students see the worked solutions: once it closes, or when the instructor released them."""
    return bool(assignment.solutions_released) or deadline_state(assignment, now) == "closed"


def attempts_used(session: Session, assignment_id: int, user_id: int, problem_id: int, answer: str) -> int:
    """How many submissions ``user_id`` has handed in for this answer in this assignment."""
    return session.scalar(
        select(func.count()).select_from(Submission).join(AssignmentProblem, (
            AssignmentProblem.assignment_id == Submission.assignment_id)
            & (AssignmentProblem.problem_version_id == Submission.problem_version_id))
        .where(Submission.assignment_id == assignment_id, Submission.user_id == user_id,
               AssignmentProblem.problem_id == problem_id, Submission.answer_name == answer)) or 0


def pending_assignment(session: Session, user_id: int, problem_id: int, now: datetime) -> Assignment | None:
    """An assignment set to ``user_id`` (a student of its course) that holds ``problem_id`` and has not
    closed yet, if any. Until it closes, the problem is answered there, not as practice: practice
    verdicts would get round its attempt limit (and answer before it opens).
    """
    candidates = session.scalars(
        select(Assignment).join(AssignmentProblem, AssignmentProblem.assignment_id == Assignment.id)
        .join(Enrolment, (Enrolment.course_id == Assignment.course_id) & (Enrolment.user_id == user_id))
        .where(AssignmentProblem.problem_id == problem_id, Enrolment.role == "student"))
    return next((a for a in candidates if deadline_state(a, now) != "closed"), None)


def unopened_problems(session: Session, user_id: int, now: datetime) -> set[int]:
    """The problems held by an assignment set to ``user_id`` (a student of its course) that has not
    opened at ``now``: its students see them once it opens, as its page shows them (access policy)."""
    rows = session.execute(
        select(AssignmentProblem.problem_id, Assignment)
        .join(Assignment, AssignmentProblem.assignment_id == Assignment.id)
        .join(Enrolment, (Enrolment.course_id == Assignment.course_id) & (Enrolment.user_id == user_id))
        .where(Enrolment.role == "student", Assignment.opens_at > _naive(now)))
    return {problem_id for problem_id, assignment in rows if deadline_state(assignment, now) == "not_open"}


def assignment_by_slug(session: Session, course: Course, slug: str) -> Assignment | None:
    return session.scalar(select(Assignment).where(Assignment.course_id == course.id, Assignment.slug == slug))


def create_assignment(session: Session, course: Course, *, slug: str, title: str, problems: list[str],
                      opens_at: datetime, due_at: datetime, closes_at: datetime | None = None,
                      time_zone: str = "UTC", max_attempts: int | None = None,
                      late_penalty_per_day: float = 0.0, score_policy: str = "best") -> Assignment:
    """A new assignment of ``course`` over the problems named by ``problems`` (ids, in order), each
    pinned to its newest published version. Times are aware datetimes (stored as UTC)."""
    zone(time_zone)
    opens, due = to_utc(opens_at), to_utc(due_at)
    closes = to_utc(closes_at) if closes_at is not None else None
    if not opens < due:
        raise AssignmentError("An assignment opens before it is due.")
    if closes is not None and closes < due:
        raise AssignmentError("An assignment closes at or after its due time.")
    if late_penalty_per_day and closes is None:
        raise AssignmentError("A late penalty needs a closing time (closes_at) after the due time.")
    if not 0.0 <= late_penalty_per_day <= 1.0:
        raise AssignmentError("The late penalty per day is a fraction of the score, from 0 to 1.")
    if max_attempts is not None and not 1 <= max_attempts <= MAX_ATTEMPTS:
        raise AssignmentError(f"An answer gets at least one attempt and at most {MAX_ATTEMPTS} (or no limit).")
    if score_policy not in SCORE_POLICIES:
        raise AssignmentError(f"The score policy is one of {', '.join(SCORE_POLICIES)}.")
    if not problems or len(problems) > MAX_PROBLEMS or len(set(problems)) != len(problems):
        raise AssignmentError(f"An assignment has 1 to {MAX_PROBLEMS} different problems.")
    if assignment_by_slug(session, course, slug) is not None:
        raise AssignmentError(f"The course already has an assignment {slug!r}.")
    assignment = Assignment(course_id=course.id, slug=slug, title=title, opens_at=opens, due_at=due,
                            closes_at=closes, time_zone=time_zone, max_attempts=max_attempts,
                            late_penalty_per_day=late_penalty_per_day, score_policy=score_policy)
    for position, name in enumerate(problems, start=1):
        problem = _problem_for(session, course, name)
        version = latest_version(session, problem, published_only=True)
        assignment.problems.append(AssignmentProblem(position=position, problem_id=problem.id,
                                                     problem_version_id=version.id))
    session.add(assignment)
    session.flush()
    return assignment


def _problem_for(session: Session, course: Course, slug: str) -> Problem:
    problem = problem_by_slug(session, slug)
    if problem is None or problem.course_id not in (None, course.id):
        raise AssignmentError(f"There is no problem {slug!r} in this course (or in no course).")
    if latest_version(session, problem, published_only=True) is None:
        raise AssignmentError(f"Problem {slug!r} has no published version yet; publish it first.")
    return problem
