"""Derivation workers: threads in the ``grader serve`` process, each driving its own sandbox child.

They are a pool apart from the grading workers and from the ``POST /check`` sandboxes, so slow
scenes never hold a request thread or a checker: at most ``workers`` scenes are derived at once,
each in a child under the derivation budget, at a lowered CPU priority.
"""

from __future__ import annotations

import logging
import os
import signal
import threading
import time
import uuid
from typing import Callable

from grader.jobs import derivation_queue as queue
from grader.jobs.derivation import DERIVE_MEMORY_MB, DERIVE_TIMEOUT_S, DerivationError, derivation_sandbox, derive_source
from grader.jobs.processes import process_tag
from grader.jobs.threads import start_threads
from grader.sandbox import Sandbox
from grader.store.db import Database
from grader.store.problems import DerivedProblem

__all__ = ["DerivationWorkerPool", "Deriver"]

log = logging.getLogger(__name__)

# A lease outlives the budget by the time a fresh child needs to start (importing sympy).
LEASE_MARGIN_S = 60.0

# ``deriver(source, filename) -> DerivedProblem``, raising DerivationError for a scene that fails.
Deriver = Callable[[str, str], DerivedProblem]


class DerivationWorkerPool:
    """``workers`` threads deriving queued scenes.

    Parameters
    ----------
    db : the Database to claim from and store into.
    may_update : ``may_update(session, requester, problem)``: whether the requester may add a version
        to an existing problem (the access policy's rule).
    workers : number of threads, each with its own sandbox child.
    timeout_s, memory_mb : the limits of one derivation.
    deriver_factory : makes one worker's deriver; by default a sandboxed one (tests pass an in-process one).
    poll_s : how long an idle worker sleeps when not woken by an upload.
    """

    def __init__(self, db: Database, *, may_update: queue.MayUpdate, workers: int = 1,
                 timeout_s: float = DERIVE_TIMEOUT_S, memory_mb: int = DERIVE_MEMORY_MB,
                 deriver_factory: Callable[[], Deriver] | None = None, poll_s: float = 1.0):
        self.db, self.may_update, self.workers, self.poll_s = db, may_update, workers, poll_s
        self.timeout_s, self.memory_mb = timeout_s, memory_mb
        self.lease_s = timeout_s + LEASE_MARGIN_S
        self.deriver_factory = deriver_factory
        self.boot_id = f"{process_tag()}:{uuid.uuid4().hex[:8]}"  # recover() reads host and pid from it
        self._stop = threading.Event()
        self._threads: list[threading.Thread] = []
        self._sandboxes: list[Sandbox] = []
        self.derived = 0

    def start(self, *, recover: bool = True) -> DerivationWorkerPool:
        """Start the threads; with ``recover``, first queue again what dead processes left ``running``."""
        if recover:
            count = queue.recover(self.db)
            if count:
                log.warning("queued %d scene derivations again that were running when the server stopped", count)
        self._threads += start_threads(self._run, self.workers, self.boot_id, "derivation-worker", "d")
        return self

    def stop(self, timeout: float = 10.0) -> None:
        self._stop.set()
        queue.wake_workers()
        for sandbox in self._sandboxes:
            _kill_now(sandbox)  # a derivation in progress ends now; its job is recovered at the next start
        for thread in self._threads:
            thread.join(timeout)
        self._threads.clear()
        for sandbox in self._sandboxes:
            sandbox.close()
        self._sandboxes.clear()

    def _sandboxed(self) -> Deriver:
        sandbox = derivation_sandbox(self.timeout_s, self.memory_mb)
        self._sandboxes.append(sandbox)

        def derive(source: str, filename: str) -> DerivedProblem:
            return derive_source(source, filename=filename, timeout_s=self.timeout_s, memory_mb=self.memory_mb,
                                 sandbox=sandbox)

        return derive

    def _run(self, worker_id: str) -> None:
        deriver: Deriver | None = None
        last_sweep = 0.0
        while not self._stop.is_set():
            try:
                if time.monotonic() - last_sweep > self.lease_s / 4:
                    queue.requeue_expired(self.db)
                    last_sweep = time.monotonic()
                task = queue.claim(self.db, worker_id, lease_s=self.lease_s)
                if task is None:
                    queue.wait_for_work(self.poll_s)
                    continue
                deriver = deriver or (self.deriver_factory() if self.deriver_factory else self._sandboxed())
                self._derive(deriver, task, worker_id)
            except Exception:
                # E.g. the database was unreachable: a claimed job stays leased and is queued again
                # when its lease runs out; this worker carries on after a pause.
                log.exception("derivation worker %s: unexpected error; going on in 1 s", worker_id)
                self._stop.wait(1.0)

    def _derive(self, deriver: Deriver, task: queue.DerivationTask, worker_id: str) -> None:
        try:
            derived = deriver(task.source, task.filename)
        except DerivationError as error:
            if not self._stop.is_set():  # else stopped mid-derivation: recovered at the next start
                queue.fail(self.db, task, worker_id, str(error))
            return
        except Exception:
            if self._stop.is_set():
                return
            # The sandbox itself broke (could not start): not the scene's fault; try again later.
            log.exception("deriving job %d failed; it goes back to the queue", task.job_id)
            queue.release(self.db, task, worker_id)
            self._stop.wait(0.5)
            return
        if queue.finish(self.db, task, worker_id, derived, self.may_update):
            self.derived += 1


def _kill_now(sandbox: Sandbox) -> None:
    """SIGKILL a sandbox's child without waiting for the request it is serving (close() would)."""
    pid = sandbox.pid
    if pid is not None:
        try:
            os.killpg(pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
