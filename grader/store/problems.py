"""Problems and their versions.

A problem is identified by its scene ``id``. Storing a scene whose source differs from the latest
version's adds a version; storing the same source again changes nothing, so loading ``problems/``
at every start is idempotent.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from datetime import datetime
from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session

from grader.store.models import Problem, ProblemVersion, utcnow

__all__ = ["DerivedProblem", "latest_version", "problem_by_slug", "save_problem", "set_archived", "set_published"]


@dataclass(frozen=True)
class DerivedProblem:
    """What the engine made of one scene file: everything a version stores."""

    slug: str
    title: str
    statement: str
    source: str
    derivation: dict[str, Any]
    references: list[dict[str, Any]]
    engine_version: str

    @property
    def source_sha256(self) -> str:
        return hashlib.sha256(self.source.encode()).hexdigest()


def problem_by_slug(session: Session, slug: str) -> Problem | None:
    return session.scalar(select(Problem).where(Problem.slug == slug))


def latest_version(session: Session, problem: Problem, *, published_only: bool = False) -> ProblemVersion | None:
    """The newest version of ``problem`` (the newest published one if ``published_only``)."""
    query = select(ProblemVersion).where(ProblemVersion.problem_id == problem.id)
    if published_only:
        query = query.where(ProblemVersion.published.is_(True))
    return session.scalar(query.order_by(ProblemVersion.number.desc()).limit(1))


def save_problem(session: Session, derived: DerivedProblem, *, published: bool = True) -> tuple[ProblemVersion, bool]:
    """Store ``derived`` as a new version unless its source equals the latest; returns (version, created)."""
    problem = problem_by_slug(session, derived.slug)
    if problem is None:
        problem = Problem(slug=derived.slug)
        session.add(problem)
        session.flush()
    latest = latest_version(session, problem)
    if latest is not None and latest.source_sha256 == derived.source_sha256 and latest.published == published:
        return latest, False
    version = ProblemVersion(
        problem=problem,
        number=(latest.number + 1) if latest else 1,
        title=derived.title,
        statement=derived.statement,
        source=derived.source,
        source_sha256=derived.source_sha256,
        derivation=derived.derivation,
        references=derived.references,
        engine_version=derived.engine_version,
        published=published,
    )
    session.add(version)
    session.flush()
    return version, True


def set_published(version: ProblemVersion, published: bool) -> bool:
    """Publish ``version`` (students who may see the problem see it) or make it a draft again.

    Returns False, changing nothing, when it already is: a repeated click or a retried request is a
    no-op, not an error. Students see the newest *published* version (:func:`latest_version`), so
    unpublishing the newest one shows them the one before it, or nothing. The caller commits.

    Examples
    --------
    >>> version = ProblemVersion(published=True)
    >>> set_published(version, False), set_published(version, False), version.published
    (True, False, False)
    """
    if bool(version.published) == published:
        return False
    version.published = published
    return True


def set_archived(problem: Problem, archived: bool, *, now: datetime | None = None) -> bool:
    """Archive ``problem`` (kept for the record; only its managers see it and nobody answers it,
    as ``grader.web.policy`` says) or bring it back; its versions and submissions are untouched.

    Returns False, changing nothing, when it already is (archiving twice keeps the first date).
    The caller commits.

    Examples
    --------
    >>> problem = Problem(slug="yoyo")
    >>> set_archived(problem, True, now=datetime(2026, 1, 2)), set_archived(problem, True), problem.archived_at
    (True, False, datetime.datetime(2026, 1, 2, 0, 0))
    >>> set_archived(problem, False), problem.archived_at is None
    (True, True)
    """
    if (problem.archived_at is not None) == archived:
        return False
    problem.archived_at = (now or utcnow()) if archived else None
    return True
