"""What a student may see: published problems of their courses (or of no course), and their own work.

Everything here answers "not found" rather than "forbidden" for things a student may not see, so a
student cannot even learn that another student's submission or a draft problem exists.
"""

from __future__ import annotations

from flask import abort
from sqlalchemy import and_, func, select
from sqlalchemy.orm import Session, selectinload

from grader.store.models import Enrolment, Problem, ProblemVersion, Submission, User
from grader.store.problems import latest_version, problem_by_slug

__all__ = ["history", "own_submission", "visible_problems", "visible_version"]


def _courses(session: Session, user: User) -> set[int]:
    return set(session.scalars(select(Enrolment.course_id).where(Enrolment.user_id == user.id)))


def _may_see(problem: Problem, courses: set[int]) -> bool:
    # A problem in no course (e.g. loaded from problems/ at start) is open to every student.
    return problem.course_id is None or problem.course_id in courses


def visible_problems(session: Session, user: User) -> list[ProblemVersion]:
    """The newest published version of every problem the student may see, by title."""
    courses = _courses(session, user)
    newest = (select(ProblemVersion.problem_id, func.max(ProblemVersion.number).label("number"))
              .where(ProblemVersion.published.is_(True)).group_by(ProblemVersion.problem_id).subquery())
    rows = session.scalars(
        select(ProblemVersion).options(selectinload(ProblemVersion.problem))
        .join(newest, and_(ProblemVersion.problem_id == newest.c.problem_id, ProblemVersion.number == newest.c.number)))
    return sorted((v for v in rows if _may_see(v.problem, courses)), key=lambda v: (v.title.lower(), v.id))


def visible_version(session: Session, user: User, slug: str) -> ProblemVersion:
    """The newest published version of problem ``slug`` if the student may see it, else 404."""
    problem = problem_by_slug(session, slug)
    version = latest_version(session, problem, published_only=True) if problem else None
    if version is None or not _may_see(problem, _courses(session, user)):
        abort(404, "There is no such problem.")
    return version


def own_submission(session: Session, user: User, submission_id: int) -> Submission:
    """The student's own submission ``submission_id``, else 404 (also for other students' ones)."""
    submission = session.get(Submission, submission_id)
    if submission is None or submission.user_id != user.id:
        abort(404, "There is no such attempt.")
    return submission


def history(session: Session, user: User, problem: Problem) -> list[Submission]:
    """The student's attempts at any version of ``problem``, newest first."""
    versions = select(ProblemVersion.id).where(ProblemVersion.problem_id == problem.id)
    return list(session.scalars(
        select(Submission).options(selectinload(Submission.verdicts))
        .where(Submission.user_id == user.id, Submission.problem_version_id.in_(versions))
        .order_by(Submission.id.desc())))
