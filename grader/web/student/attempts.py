"""A student's own attempts at a problem (who may see what is decided by :mod:`grader.web.policy`)."""

from __future__ import annotations

from sqlalchemy import select
from sqlalchemy.orm import Session, selectinload

from grader.store.models import Problem, ProblemVersion, Submission, User

__all__ = ["history"]


def history(session: Session, user: User, problem: Problem) -> list[Submission]:
    """The student's attempts at any version of ``problem``, newest first."""
    versions = select(ProblemVersion.id).where(ProblemVersion.problem_id == problem.id)
    return list(session.scalars(
        select(Submission).options(selectinload(Submission.verdicts))
        .where(Submission.user_id == user.id, Submission.problem_version_id.in_(versions))
        .order_by(Submission.id.desc())))
