"""Grading workers: threads in the ``grader serve`` process, each driving its own sandbox child.

A worker loops: claim a task in a short transaction, close the session, run the sandboxed check,
record the verdict in a new short transaction. It never holds a session while grading.
"""

from __future__ import annotations

import logging
import threading
import time
import uuid
from typing import Callable

from grader.jobs import queue
from grader.jobs.processes import process_tag
from grader.jobs.threads import start_threads
from grader.jobs.grading import CHECK_BUDGET_S, Checker, check_task, sandbox_checker, score
from grader.store.db import Database
from grader.store.models import utcnow

__all__ = ["WorkerPool"]

log = logging.getLogger(__name__)


class WorkerPool:
    """``workers`` grading threads over one database.

    Parameters
    ----------
    db : the Database to claim from and record into.
    workers : number of threads (each with its own checker).
    checker_factory : makes a checker; defaults to a sandbox child per worker.
    poll_s : how long an idle worker sleeps when not woken by a new submission.
    """

    def __init__(self, db: Database, *, workers: int = 2, checker_factory: Callable[[], Checker] | None = None,
                 poll_s: float = 1.0, budget_s: float = CHECK_BUDGET_S, lease_s: float = queue.LEASE_S):
        self.db, self.workers, self.poll_s, self.budget_s, self.lease_s = db, workers, poll_s, budget_s, lease_s
        self.checker_factory = checker_factory or sandbox_checker
        self.boot_id = f"{process_tag()}:{uuid.uuid4().hex[:8]}"  # recover() reads host and pid from it
        self._stop = threading.Event()
        self._threads: list[threading.Thread] = []
        self.graded = 0

    def start(self, *, recover: bool = True) -> WorkerPool:
        """Start the threads; with ``recover``, first queue again whatever a crash left ``running``."""
        if recover:
            count = queue.recover(self.db)
            if count:
                log.warning("queued %d submissions again that were being graded when the server stopped", count)
        self._threads += start_threads(self._run, self.workers, self.boot_id, "grader-worker")
        return self

    def stop(self, timeout: float = 10.0) -> None:
        self._stop.set()
        queue.wake_workers()
        for thread in self._threads:
            thread.join(timeout)
        self._threads.clear()

    def _run(self, worker_id: str) -> None:
        checker = None
        last_sweep = 0.0
        try:
            while not self._stop.is_set():
                try:
                    if time.monotonic() - last_sweep > self.lease_s / 4:
                        queue.requeue_expired(self.db)
                        last_sweep = time.monotonic()
                    task = queue.claim(self.db, worker_id, lease_s=self.lease_s)
                    if task is None:
                        queue.wait_for_work(self.poll_s)
                        continue
                    checker = checker or self.checker_factory()
                    checker = self._grade(checker, task, worker_id)
                except Exception:
                    # E.g. the database was unreachable: a claimed task stays leased and is queued
                    # again when its lease runs out; this worker carries on after a pause.
                    log.exception("grading worker %s: unexpected error; going on in 1 s", worker_id)
                    self._stop.wait(1.0)
        finally:
            if checker is not None:
                checker.close()

    def _grade(self, checker: Checker, task: queue.Task, worker_id: str) -> Checker | None:
        started_at, start = utcnow(), time.perf_counter()
        try:
            result = check_task(checker, task, budget_s=self.budget_s)
        except Exception:
            # The checker itself broke (not the student's answer, which yields a verdict): start a
            # fresh one and give the task back; after MAX_ATTEMPTS claims it is recorded as failed.
            log.exception("checking submission %d failed; it goes back to the queue", task.submission_id)
            checker.close()
            queue.release(self.db, task, worker_id)
            self._stop.wait(0.5)
            return None
        grade_ms = (time.perf_counter() - start) * 1000
        if queue.record(self.db, task, worker_id, result, score=score(result), grade_ms=grade_ms,
                        started_at=started_at):
            self.graded += 1
        else:
            log.info("submission %d round %d was taken over; its result was dropped",
                     task.submission_id, task.grading_round)
        return checker
