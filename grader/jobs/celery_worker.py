"""Grading on Celery workers over a Redis broker, when ``GRADER_BROKER_URL`` is set.

Without a broker, ``grader serve`` grades in its own worker threads (:mod:`grader.jobs.worker`). With
one, every submission committed as ``queued`` is also announced as a task message
``lagrade.grade(submission_id, grading_round)``, and separate worker processes grade it::

    GRADER_BROKER_URL=redis://localhost:6379/0 DATABASE_URL=postgresql+psycopg://... \\
        celery -A grader.jobs.celery_worker worker --pool solo --loglevel INFO

Delivery is at least once and grading exactly once. A message is acknowledged only after its
verdict is committed (``acks_late``, one message at a time); a worker killed mid-job leaves the
message unacknowledged, and the broker delivers it again after the visibility timeout. The task is
idempotent by (submission, round): it claims the row only if the row is still queued in that round,
or running under a lease that has run out, and the verdict table's UNIQUE(submission, round) keeps a
second verdict out whatever happens. A message that never reached the broker is not lost either:
the submission stays ``queued`` in the database, and each worker's sweep announces such rows again.

Settings (environment): ``GRADER_BROKER_URL``; ``DATABASE_URL``; ``GRADER_TASK_TIME_LIMIT_S`` (hard
limit of one job, default 120); ``GRADER_LEASE_S`` (a claim's lease, default the limit + 30 s, so a
live worker's claim never runs out); ``GRADER_BROKER_VISIBILITY_S`` (default the lease + 30 s);
``GRADER_SWEEP_S`` (default 300); ``GRADER_CHECKER_FACTORY`` (``module:function``, default the
sandboxed checker); ``GRADER_CHECK_BUDGET_S``.
"""

from __future__ import annotations

import importlib
import logging
import os
import threading
import time
from dataclasses import dataclass
from datetime import timedelta

from celery import Celery, signals

from grader.jobs import queue
from grader.jobs.processes import process_tag
from grader.jobs.grading import CHECK_BUDGET_S, Checker, check_task, score
from grader.store.db import Database, default_url
from grader.store.models import utcnow

__all__ = ["app", "grade", "install_publisher", "publish", "settings"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Settings:
    broker_url: str | None
    time_limit_s: float
    lease_s: float
    visibility_s: float
    sweep_s: float
    checker_factory: str
    budget_s: float

    @classmethod
    def from_environment(cls) -> Settings:
        limit = float(os.environ.get("GRADER_TASK_TIME_LIMIT_S", "120"))
        lease = float(os.environ.get("GRADER_LEASE_S", str(limit + 30)))
        return cls(broker_url=os.environ.get("GRADER_BROKER_URL") or None, time_limit_s=limit, lease_s=lease,
                   visibility_s=float(os.environ.get("GRADER_BROKER_VISIBILITY_S", str(lease + 30))),
                   sweep_s=float(os.environ.get("GRADER_SWEEP_S", "300")),
                   checker_factory=os.environ.get("GRADER_CHECKER_FACTORY", "grader.jobs.grading:sandbox_checker"),
                   budget_s=float(os.environ.get("GRADER_CHECK_BUDGET_S", str(CHECK_BUDGET_S))))


settings = Settings.from_environment()

app = Celery("lagrade", set_as_current=False)
app.conf.update(
    broker_url=settings.broker_url,
    broker_connection_retry_on_startup=True,
    broker_transport_options={"visibility_timeout": settings.visibility_s},
    task_acks_late=True,  # acknowledged after the verdict is committed, not on receipt
    task_reject_on_worker_lost=True,  # a worker that dies mid-job gives the message back
    worker_prefetch_multiplier=1,  # a worker reserves one message at a time
    task_time_limit=settings.time_limit_s,  # hard: the worker child is killed past it
    task_serializer="json",
    accept_content=["json"],
    task_ignore_result=True,  # the verdict lives in the database, not in a result backend
    task_default_queue="lagrade-grading",
    worker_hijack_root_logger=False,
)

_state = threading.local()
_database: Database | None = None


def _db() -> Database:
    global _database
    if _database is None:
        _database = Database(default_url())
    return _database


def _checker() -> Checker:
    checker = getattr(_state, "checker", None)
    if checker is None:
        module, _, name = settings.checker_factory.partition(":")
        checker = _state.checker = getattr(importlib.import_module(module), name)()
    return checker


def _drop_checker() -> None:
    checker = getattr(_state, "checker", None)
    _state.checker = None
    if checker is not None:
        checker.close()


def _worker_id() -> str:
    return f"{process_tag()}:celery-{threading.get_ident() % 100000}"


@app.task(name="lagrade.grade", bind=True, max_retries=None)
def grade(self, submission_id: int, grading_round: int) -> str:
    """Grade one submission's round, once; returns what happened (for the worker's log)."""
    db = _db()
    worker_id = _worker_id()
    task = queue.claim_submission(db, submission_id, grading_round, worker_id, lease_s=settings.lease_s)
    if task is None:
        held_until = queue.holder_lease(db, submission_id, grading_round)
        if held_until is not None:
            # Another worker holds it. If that worker died, its lease runs out: look again then.
            raise self.retry(countdown=max(1.0, (held_until - utcnow()).total_seconds() + 1.0))
        return "nothing to do (graded, failed or superseded)"
    started_at, start = utcnow(), time.perf_counter()
    try:
        result = check_task(_checker(), task, budget_s=settings.budget_s)
    except Exception:
        # The checker broke, not the answer: a fresh checker, and the task back to the queue
        # (after MAX_ATTEMPTS claims it is recorded as failed).
        log.exception("checking submission %d failed; it goes back to the queue", submission_id)
        _drop_checker()
        queue.release(db, task, worker_id)
        return "checker failed; released"
    recorded = queue.record(db, task, worker_id, result, score=score(result),
                            grade_ms=(time.perf_counter() - start) * 1000, started_at=started_at)
    return "graded" if recorded else "taken over; result dropped"


def publish(work: list[tuple[int, int]]) -> None:
    """Send a ``lagrade.grade`` message for each (submission, round)."""
    for submission_id, grading_round in work:
        grade.apply_async((submission_id, grading_round))


def install_publisher() -> None:
    """Announce queued work to the broker from this process (the web processes call this)."""
    if settings.broker_url is None:
        raise RuntimeError("GRADER_BROKER_URL is not set")
    queue.add_publisher(publish)


def sweep_once(db: Database | None = None, older_than_s: float | None = None) -> int:
    """Queue again what ran out of its lease, and announce work queued long ago (its message may
    have been lost). Returns how many messages were sent."""
    db = db or _db()
    queue.requeue_expired(db)
    before = utcnow() - timedelta(seconds=settings.sweep_s if older_than_s is None else older_than_s)
    work = queue.queued_since(db, before)
    publish(work)
    return len(work)


def _sweep_forever(stop: threading.Event) -> None:
    while not stop.wait(settings.sweep_s):
        try:
            sent = sweep_once()
            if sent:
                log.warning("announced %d queued submissions again (their messages may have been lost)", sent)
        except Exception:
            log.exception("sweep failed; trying again in %.0f s", settings.sweep_s)


_sweeper_stop = threading.Event()


@signals.worker_ready.connect
def _on_worker_ready(**_kwargs) -> None:
    queue.add_publisher(publish)  # work released by this worker is announced again
    threading.Thread(target=_sweep_forever, args=(_sweeper_stop,), name="lagrade-sweep", daemon=True).start()


@signals.worker_shutdown.connect
def _on_worker_shutdown(**_kwargs) -> None:
    _sweeper_stop.set()
    _drop_checker()
