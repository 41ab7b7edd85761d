"""Each student's own numbers for a randomised problem of an assignment.

A student's parameter values are drawn once, the first time they are asked for, and kept in
``parameter_draws`` (one row per assignment, student and problem), so every page, every check and
the worked solution use the same numbers. The drawing itself is the engine's
(``draw_parameters``, helper H11's part of issue 9); a problem that declares no random parameters
has no draw and gets ``{}``.
"""

from __future__ import annotations

import hashlib
from typing import Any

from sqlalchemy import select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from grader.store.models import Assignment, AssignmentProblem, ParameterDraw, User

__all__ = ["parameters_for", "seed_for"]


def seed_for(assignment_id: int, user_id: int, problem_id: int) -> int:
    """A seed fixed by (assignment, student, problem): the same student gets the same numbers again,
    two students (almost surely) different ones.

    Examples
    --------
    >>> seed_for(1, 2, 3) == seed_for(1, 2, 3), seed_for(1, 2, 3) == seed_for(1, 4, 3)
    (True, False)
    """
    digest = hashlib.sha256(f"{assignment_id}:{user_id}:{problem_id}".encode()).digest()
    return int.from_bytes(digest[:4], "big") & 0x7FFFFFFF  # fits the database's 32-bit integer


def _drawer():
    """The engine's ``draw_parameters(source_or_derivation, seed)``, if this build has it."""
    try:
        from grader.mechanics.randomise import draw_parameters  # H11 (issue 9)
    except ImportError:
        return None
    return draw_parameters


def parameters_for(session: Session, assignment: Assignment, student: User, item: AssignmentProblem) -> dict[str, Any]:
    """``student``'s parameter values for ``item`` (drawn and stored on first use; ``{}`` if fixed)."""
    stored = session.scalar(select(ParameterDraw).where(ParameterDraw.assignment_id == assignment.id,
                                                        ParameterDraw.user_id == student.id,
                                                        ParameterDraw.problem_id == item.problem_id))
    if stored is not None:
        return dict(stored.values)
    draw = _drawer()
    version = item.problem_version
    if draw is None or not version.derivation.get("random_parameters"):
        return {}
    seed = seed_for(assignment.id, student.id, item.problem_id)
    values = draw(version.derivation, seed)
    try:
        with session.begin_nested():
            session.add(ParameterDraw(assignment_id=assignment.id, user_id=student.id, problem_id=item.problem_id,
                                      seed=seed, values=values))
    except IntegrityError:  # drawn at the same moment by another request: the same seed, the same values
        pass
    return values
