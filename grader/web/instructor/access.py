"""Which problems an instructor manages: those of the courses they teach, and those in no course.

An admin manages everything. A problem another instructor's course owns is "not found", as for students.
"""

from __future__ import annotations

from flask import abort
from sqlalchemy import select
from sqlalchemy.orm import Session

from grader.store.models import Course, Enrolment, Problem, ProblemVersion, User

__all__ = ["managed_courses", "managed_problem", "managed_problems", "may_manage", "version_of"]


def managed_courses(session: Session, user: User) -> list[Course]:
    """The courses ``user`` teaches (every course for an admin), by code."""
    query = select(Course).order_by(Course.code)
    if user.role != "admin":
        query = query.join(Enrolment, Enrolment.course_id == Course.id).where(
            Enrolment.user_id == user.id, Enrolment.role == "instructor")
    return list(session.scalars(query))


def may_manage(session: Session, user: User, problem: Problem) -> bool:
    if user.role == "admin" or problem.course_id is None:
        return True
    return problem.course_id in {c.id for c in managed_courses(session, user)}


def managed_problems(session: Session, user: User) -> list[Problem]:
    problems = session.scalars(select(Problem).order_by(Problem.slug))
    courses = None if user.role == "admin" else {c.id for c in managed_courses(session, user)}
    return [p for p in problems if courses is None or p.course_id is None or p.course_id in courses]


def managed_problem(session: Session, user: User, slug: str) -> Problem:
    problem = session.scalar(select(Problem).where(Problem.slug == slug))
    if problem is None or not problem.versions or not may_manage(session, user, problem):
        abort(404, "There is no such problem.")
    return problem


def version_of(problem: Problem, number: int | None) -> ProblemVersion:
    """Version ``number`` of ``problem`` (the newest when None), else 404."""
    if number is None:
        return problem.versions[-1]
    version = next((v for v in problem.versions if v.number == number), None)
    if version is None:
        abort(404, "There is no such version.")
    return version
