"""The background work of a web process: grading and derivation workers, started and stopped
together by ``grader serve`` and by the WSGI module under gunicorn.

Grading runs in this process's worker threads unless ``GRADER_BROKER_URL`` is set, in which case
Celery workers grade (:mod:`grader.jobs.celery_worker`) and this process only announces work.
Every process on one database may do this: claims are conditional, and start-up recovery only
takes back claims of processes that have died (:mod:`grader.jobs.processes`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from flask import Flask

__all__ = ["Background", "start_background"]


@dataclass
class Background:
    """What :func:`start_background` started; :meth:`stop` ends it."""

    description: str
    pools: list = field(default_factory=list)

    def stop(self) -> None:
        for pool in reversed(self.pools):
            pool.stop()
        self.pools.clear()


def start_background(app: Flask, *, grading_workers: int = 2) -> Background:
    """Start this process's grading (or its announcing to Celery) and derivation workers."""
    from grader.jobs import WorkerPool
    from grader.jobs.derivation_workers import DerivationWorkerPool
    from grader.web.policy import may_update

    database = app.extensions["lagrade.db"]
    background = Background("")
    if os.environ.get("GRADER_BROKER_URL"):
        from grader.jobs.celery_worker import install_publisher

        install_publisher()
        background.description = "grading by Celery workers on GRADER_BROKER_URL"
    else:
        background.pools.append(WorkerPool(database, workers=grading_workers,
                                           checker_factory=app.config["CHECKER_FACTORY"],
                                           budget_s=app.config["CHECK_BUDGET_S"]).start())
        background.description = f"{grading_workers} grading workers"
    background.pools.append(DerivationWorkerPool(database, may_update=may_update, workers=app.config["DERIVE_WORKERS"],
                                                 timeout_s=app.config["DERIVE_TIMEOUT_S"],
                                                 memory_mb=app.config["DERIVE_MEMORY_MB"]).start())
    # LTI scores waiting for their LMS (grader/jobs/lti_passback.py): each row is claimed by one sender.
    from grader.jobs.lti_passback import PassbackSender
    from grader.web.lti.ags import deliverer

    background.pools.append(PassbackSender(database, deliverer(database)).start())
    return background
