"""Each student's own numbers for a randomised problem of an assignment.

A student's parameter values are drawn once, the first time they are needed (their assignment page,
or their first hand-in), and kept in ``parameter_draws`` (one row per assignment, student and
problem), so every page, every check and the worked solution use the same numbers. The drawing is
:func:`grader.answers.randomised.draw_parameters`; a problem without random parameters has no draw
and gets ``{}`` (its fixed values stay in its statement).
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from grader.answers.randomised import draw_parameters, is_randomised, seed_for
from grader.store.db import Database
from grader.store.models import AssignmentProblem, ParameterDraw, Submission

__all__ = ["draw_in", "parameters_for", "stored_values", "submission_values"]


def stored_values(session: Session, assignment_id: int, user_id: int, problem_id: int) -> dict[str, Any] | None:
    """The values drawn for this student, assignment and problem, if drawn."""
    return session.scalar(select(ParameterDraw.values).where(ParameterDraw.assignment_id == assignment_id,
                                                             ParameterDraw.user_id == user_id,
                                                             ParameterDraw.problem_id == problem_id))


def draw_in(session: Session, assignment_id: int, user_id: int, item: AssignmentProblem,
            secret: str = "") -> dict[str, Any]:
    """The student's values for ``item``, drawn and added to ``session`` (a write transaction) if new."""
    values = stored_values(session, assignment_id, user_id, item.problem_id)
    if values is not None:
        return dict(values)
    spec = item.problem_version.derivation.get("parameters") or {}
    if not is_randomised(spec):
        return {}
    seed = seed_for(secret, assignment_id, user_id, item.problem_id)
    values = draw_parameters(spec, seed)
    session.add(ParameterDraw(assignment_id=assignment_id, user_id=user_id, problem_id=item.problem_id, seed=seed,
                              values=values))
    session.flush()
    return values


def parameters_for(database: Database, assignment_id: int, user_id: int, item: AssignmentProblem,
                   secret: str = "") -> dict[str, Any]:
    """The student's values for ``item`` (``{}`` for a fixed problem), drawn and stored in a short write
    transaction of their own the first time."""
    with database.read() as session:
        values = stored_values(session, assignment_id, user_id, item.problem_id)
    if values is not None:
        return dict(values)
    if not is_randomised(item.problem_version.derivation.get("parameters") or {}):
        return {}
    try:
        with database.write() as session:
            return draw_in(session, assignment_id, user_id, session.get(AssignmentProblem, item.id), secret)
    except IntegrityError:  # drawn at the same moment by another request: read theirs
        with database.read() as session:
            return dict(stored_values(session, assignment_id, user_id, item.problem_id) or {})


def submission_values(session: Session, submission: Submission) -> dict[str, Any] | None:
    """The parameter values a submission is graded with: its student's draw for its assignment's
    problem (None outside an assignment or for a fixed problem: the preview values apply)."""
    if submission.assignment_id is None:
        return None
    return stored_values(session, submission.assignment_id, submission.user_id,
                         submission.problem_version.problem_id)
