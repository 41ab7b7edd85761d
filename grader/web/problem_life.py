"""A problem's life after its first upload, one rule for the REST API and the instructor pages alike.

A scene file becomes a problem version through one path, :func:`queue_scene`: the checks that need
no engine (empty, too large, not TOML, another problem's id, the same file again), then the
derivation queue (:mod:`grader.jobs.derivation_queue`), whose worker stores the version. Publishing,
unpublishing, archiving and restoring are :func:`grader.store.problems.set_published` and
:func:`~grader.store.problems.set_archived`. A regrade grades against :func:`regrade_version`. Who may do any of it is decided before, by
:mod:`grader.web.policy` (``manage``); each surface only puts the outcome into its own words (a
flash and a redirect, or a status and JSON), so the pages and the API cannot drift apart.
"""

from __future__ import annotations

from dataclasses import dataclass

from grader.jobs.derivation import DerivationError, read_scene_id
from grader.jobs.derivation_queue import TooManyDerivations, enqueue
from grader.store.db import Database
from grader.store.models import Problem, ProblemVersion
from grader.store.problems import latest_version
from grader.web.policy import Action, Principal, require, require_upload

__all__ = ["MAX_SCENE_BYTES", "Queued", "SceneRefused", "queue_scene", "regrade_version"]

MAX_SCENE_BYTES = 256 * 1024


class SceneRefused(Exception):
    """A scene file that was not queued, and why, in words for its author.

    Parameters
    ----------
    kind : ``empty``, ``too-large``, ``invalid-scene`` (not TOML), ``wrong-id`` (a new version must
        keep its problem's id) or ``too-many-derivations``.
    message : what to change.
    retry_after_s : for ``too-many-derivations``, when to try again.
    """

    def __init__(self, kind: str, message: str, retry_after_s: int | None = None):
        super().__init__(message)
        self.kind, self.message, self.retry_after_s = kind, message, retry_after_s


@dataclass(frozen=True)
class Queued:
    """What became of a scene file: the derivation job to follow, or (``job_id`` None) the number of
    the newest version whose source it repeats, so there was nothing to derive."""

    job_id: int | None
    same_as: int | None = None


def queue_scene(principal: Principal, source: str, *, filename: str, publish: bool, max_active: int,
                problem: Problem | None = None, course_id: int | None = None) -> Queued:
    """Queue the scene ``source`` for derivation into a problem version, after the checks that need no engine.

    Parameters
    ----------
    principal : who uploads it; the job is theirs.
    source : the scene file's text.
    filename : named in the scene's errors.
    publish : whether the version is published once derived.
    max_active : how many derivations one requester may have queued or running.
    problem : the problem this must be a new version of (an edit), found by the caller through the
        policy; the scene must keep its id, and a source equal to the newest version's is not
        derived again. None registers a problem: any id the policy lets ``principal`` upload under.
    course_id : for a new problem, the course it joins (a new version stays in its problem's course).

    Raises
    ------
    SceneRefused
        Empty, too large, not TOML, another id than ``problem``'s, or too many derivations waiting.
    """
    if not source.strip():
        raise SceneRefused("empty", "The scene file is empty.")
    if len(source.encode()) > MAX_SCENE_BYTES:
        raise SceneRefused("too-large", f"A scene file may be at most {MAX_SCENE_BYTES // 1024} KiB.")
    try:
        slug = read_scene_id(source, filename)
    except DerivationError as error:
        raise SceneRefused("invalid-scene", str(error)) from None
    database = Database.current()
    if problem is not None:
        require(principal, Action.MANAGE, problem)  # the caller found it so; this keeps the rule here too
        if slug != problem.slug:
            # Another id would register another problem (or change someone else's) behind the author's back.
            raise SceneRefused("wrong-id", f"This is a new version of the problem {problem.slug!r}: keep "
                                           f"`id = \"{problem.slug}\"` (to start another problem, register "
                                           "the scene as a new problem).")
        with database.read() as session:
            newest = latest_version(session, problem)
        if newest is not None and newest.source == source:
            return Queued(None, same_as=newest.number)
        course_id = problem.course_id
    elif slug is not None:
        with database.read() as session:  # another course's id: refused now (and again when the job saves it)
            require_upload(session, principal, slug)
    try:
        job_id = enqueue(database, requester_id=principal.user_id, source=source, filename=filename,
                         course_id=course_id, publish=publish, max_active=max_active)
    except TooManyDerivations as refused:
        raise SceneRefused("too-many-derivations", str(refused), retry_after_s=refused.retry_after_s) from None
    return Queued(job_id)


def regrade_version(session, problem: Problem) -> ProblemVersion | None:
    """The version a regrade of ``problem`` grades every submission against: the newest *published*
    one, the references students answer (None: publish one first). Never a draft: its references are
    unreviewed, and on a problem in no course any instructor may add one."""
    return latest_version(session, problem, published_only=True)
