"""The derivation queue, kept in the ``derivation_jobs`` table: uploaded scenes waiting for the engine.

A job's life mirrors a submission's (:mod:`grader.jobs.queue`): ``enqueue`` commits the scene as
``queued`` in a short transaction (the upload request answers at once); a derivation worker
``claim``s it with a conditional UPDATE (``queued`` → ``running``, its worker id, a lease); derives it
in its own sandbox child with no session open; then ``finish`` stores the problem version and sets
``done`` in one transaction, or ``fail`` records the scene's error, in both cases only while the
claim is still the worker's. ``recover`` (at start: claims of dead processes on this host) and
``requeue_expired`` (claims whose lease ran out) put interrupted jobs back; a job claimed ``MAX_ATTEMPTS`` times without an outcome fails, so a scene that kills its
worker cannot loop.

Each requester may have at most ``max_active`` jobs queued or running: one instructor's batch of
slow scenes waits its turn instead of filling the queue in front of everyone else's.
"""

from __future__ import annotations

import hashlib
import threading
from dataclasses import dataclass
from datetime import datetime, timedelta
from typing import Callable

from sqlalchemy import func, select, update
from sqlalchemy.orm import Session, aliased

from grader.jobs.processes import holder_is_dead
from grader.store.db import Database
from grader.store.lengths import StoredValueError
from grader.store.models import DerivationJob, Problem, User, utcnow
from grader.store.problems import DerivedProblem, problem_by_slug, save_problem

__all__ = [
    "ACTIVE",
    "MAX_ACTIVE_PER_REQUESTER",
    "MAX_ATTEMPTS",
    "DerivationTask",
    "TooManyDerivations",
    "claim",
    "enqueue",
    "fail",
    "finish",
    "queued_ahead",
    "unfinished_business",
    "recover",
    "release",
    "requeue_expired",
    "wait_for_work",
    "wake_workers",
]

ACTIVE = ("queued", "running")
MAX_ACTIVE_PER_REQUESTER = 2
MAX_ATTEMPTS = 2

# Who may add a version to an existing problem: ``may_update(session, requester, problem)``. The
# rule lives in the web layer's access policy; the worker pool is handed it (data flows one way).
MayUpdate = Callable[[Session, User, Problem], bool]

_new_work = threading.Event()


def wake_workers() -> None:
    _new_work.set()


def wait_for_work(timeout: float) -> None:
    if _new_work.wait(timeout):
        _new_work.clear()


class TooManyDerivations(RuntimeError):
    """The requester has ``limit`` derivations queued or running already; try again later."""

    def __init__(self, limit: int, retry_after_s: int):
        super().__init__(f"You have {limit} scene{'s' if limit != 1 else ''} being derived already; "
                         f"wait until one is finished, then upload again.")
        self.limit, self.retry_after_s = limit, retry_after_s


def enqueue(db: Database, *, requester_id: int, source: str, filename: str = "upload.toml",
            course_id: int | None = None, publish: bool = False,
            max_active: int = MAX_ACTIVE_PER_REQUESTER, retry_after_s: int = 5) -> int:
    """Store the scene ``source`` as a ``queued`` job; returns its id.

    Raises :class:`TooManyDerivations` when the requester has ``max_active`` jobs queued or running.
    The count and the insert share one write transaction, serialized per requester (SQLite has one
    writer at a time; elsewhere the requester's row is locked), so concurrent uploads cannot both
    slip under the limit.
    """
    with db.write() as session:
        session.execute(select(User.id).where(User.id == requester_id).with_for_update())
        active = session.scalar(select(func.count()).select_from(DerivationJob)
                                .where(DerivationJob.requester_id == requester_id, DerivationJob.status.in_(ACTIVE)))
        if active >= max_active:
            raise TooManyDerivations(max_active, retry_after_s)
        job = DerivationJob(requester_id=requester_id, course_id=course_id, filename=filename[:100],
                            source=source, source_sha256=hashlib.sha256(source.encode()).hexdigest(),
                            publish=publish, status="queued")
        session.add(job)
        session.flush()
        job_id = job.id
    wake_workers()
    return job_id


@dataclass(frozen=True)
class DerivationTask:
    """What a worker needs to derive one job, read in a short session and detached from it."""

    job_id: int
    requester_id: int
    course_id: int | None
    filename: str
    source: str
    publish: bool
    attempts: int


def claim(db: Database, worker_id: str, *, lease_s: float) -> DerivationTask | None:
    """Take the next queued job for ``worker_id``, or None if there is none.

    Requesters take turns: the next job is the oldest of the requester served longest ago (or
    never), so many instructors' slow scenes delay a newcomer's upload by one derivation per
    worker, not by all of theirs.
    """
    earlier = aliased(DerivationJob)
    last_served = (select(func.max(earlier.started_at)).where(earlier.requester_id == DerivationJob.requester_id)
                   .scalar_subquery())
    while True:
        with db.write() as session:
            job_id = session.scalar(select(DerivationJob.id).where(DerivationJob.status == "queued")
                                    .order_by(last_served.is_not(None), last_served, DerivationJob.id).limit(1))
            if job_id is None:
                return None
            now = utcnow()
            taken = session.execute(
                update(DerivationJob)
                .where(DerivationJob.id == job_id, DerivationJob.status == "queued")
                .values(status="running", worker_id=worker_id, lease_until=now + timedelta(seconds=lease_s),
                        attempts=DerivationJob.attempts + 1, started_at=now, updated_at=now)).rowcount
            if taken != 1:
                continue
            job = session.get(DerivationJob, job_id)
            task = DerivationTask(job.id, job.requester_id, job.course_id, job.filename, job.source, job.publish,
                                  job.attempts)
        if task.attempts > MAX_ATTEMPTS:
            fail(db, task, worker_id, f"{task.filename}: the derivation was interrupted {MAX_ATTEMPTS} times "
                                      "(the server stopped while deriving it); upload it again to retry")
            continue
        return task


def _ours(task: DerivationTask, worker_id: str):
    return (DerivationJob.id == task.job_id, DerivationJob.status == "running", DerivationJob.worker_id == worker_id)


def finish(db: Database, task: DerivationTask, worker_id: str, derived: DerivedProblem,
           may_update: MayUpdate) -> bool:
    """Store ``derived`` as a version and mark the job done, in one transaction.

    A scene whose id names a problem the requester may not change fails instead (its id is taken),
    and so does one with a value no column takes (a NUL character, a title too long): deriving it
    again would not help, so the job fails at once with that reason rather than going back to the
    queue until it reads as interrupted. Returns False (and writes nothing) when the claim is no
    longer ours.
    """
    try:
        return _store(db, task, worker_id, derived, may_update)
    except StoredValueError as error:  # the transaction was rolled back: nothing of it was stored
        return fail(db, task, worker_id, f"{task.filename}: the derived problem cannot be stored: {error}")


def _store(db: Database, task: DerivationTask, worker_id: str, derived: DerivedProblem,
           may_update: MayUpdate) -> bool:
    with db.write() as session:
        job = session.get(DerivationJob, task.job_id)
        if job is None or job.status != "running" or job.worker_id != worker_id:
            return False
        existing = problem_by_slug(session, derived.slug)
        if existing is not None and not may_update(session, job.requester, existing):
            _set_failed(session, task, worker_id, f"The problem id {derived.slug!r} is taken by another course; "
                                                  "give the scene another id.")
            return True
        version, created = save_problem(session, derived, published=task.publish)
        if created and version.number == 1 and task.course_id is not None:
            version.problem.course_id = task.course_id
        now = utcnow()
        session.execute(update(DerivationJob).where(*_ours(task, worker_id)).values(
            status="done", problem_version_id=version.id, new_version=created, worker_id=None, lease_until=None,
            finished_at=now, updated_at=now))
    return True


def fail(db: Database, task: DerivationTask, worker_id: str, message: str) -> bool:
    """Mark the job failed with ``message`` (the scene's error, for the instructor)."""
    with db.write() as session:
        return _set_failed(session, task, worker_id, message)


def _set_failed(session: Session, task: DerivationTask, worker_id: str, message: str) -> bool:
    now = utcnow()
    return session.execute(update(DerivationJob).where(*_ours(task, worker_id)).values(
        status="failed", error=message, worker_id=None, lease_until=None, finished_at=now,
        updated_at=now)).rowcount == 1


def queued_ahead(session: Session, job: DerivationJob) -> int | None:
    """How many queued jobs will be claimed before ``job`` (None unless it is queued)."""
    if job.status != "queued":
        return None
    return session.scalar(select(func.count()).select_from(DerivationJob)
                          .where(DerivationJob.status == "queued", DerivationJob.id < job.id))


def unfinished_business(session: Session, requester_id: int, *, limit: int = 5) -> list[DerivationJob]:
    """The requester's newest uploads still waiting, deriving, or failed (what needs their attention)."""
    return list(session.scalars(select(DerivationJob)
                                .where(DerivationJob.requester_id == requester_id,
                                       DerivationJob.status.in_(ACTIVE + ("failed",)))
                                .order_by(DerivationJob.id.desc()).limit(limit)))


def release(db: Database, task: DerivationTask, worker_id: str) -> None:
    """Give a claimed job back to the queue (the worker's sandbox broke, not the scene)."""
    with db.write() as session:
        session.execute(update(DerivationJob).where(*_ours(task, worker_id)).values(
            status="queued", worker_id=None, lease_until=None, updated_at=utcnow()))
    wake_workers()


def recover(db: Database) -> int:
    """At start-up: queue again the ``running`` jobs whose worker process has died on this host.

    Safe with many processes on one database (:mod:`grader.jobs.processes`): a claim held by a live
    process, here or on another host, is left alone; should that process die, its lease runs out.
    """
    with db.write() as session:
        running = session.execute(select(DerivationJob.id, DerivationJob.worker_id)
                                  .where(DerivationJob.status == "running")).all()
        count = 0
        for job_id, worker_id in running:
            if holder_is_dead(worker_id):
                count += session.execute(update(DerivationJob).where(
                    DerivationJob.id == job_id, DerivationJob.status == "running", DerivationJob.worker_id == worker_id)
                    .values(status="queued", worker_id=None, lease_until=None)).rowcount
    if count:
        wake_workers()
    return count


def requeue_expired(db: Database, now: datetime | None = None) -> int:
    """Queue again the running jobs whose lease ran out (a stuck or vanished worker)."""
    with db.write() as session:
        count = session.execute(update(DerivationJob)
                                .where(DerivationJob.status == "running", DerivationJob.lease_until < (now or utcnow()))
                                .values(status="queued", worker_id=None, lease_until=None)).rowcount
    if count:
        wake_workers()
    return count
