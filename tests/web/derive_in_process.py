"""Deriving queued scenes now, in this process, as a derivation worker would (the real engine, no child)."""

from __future__ import annotations

from grader.jobs import derivation_queue as queue
from grader.jobs.derivation import DerivationError, derive_request
from grader.store.problems import DerivedProblem
from grader.web.policy import may_update


def derive_in_process(source: str, filename: str) -> DerivedProblem:
    """The sandboxed derivation's result, computed here: a DerivedProblem or a DerivationError."""
    reply = derive_request({"source": source, "filename": filename})
    if reply["outcome"] != "ok":
        raise DerivationError(reply.get("message") or reply["trace"])
    return DerivedProblem(source=source, **reply["problem"])


def derive_one(app, task: queue.DerivationTask, worker_id: str = "test-deriver") -> None:
    """Finish a claimed ``task``: store its problem version, or fail it with the scene's error."""
    database = app.extensions["lagrade.db"]
    try:
        derived = derive_in_process(task.source, task.filename)
    except DerivationError as error:
        queue.fail(database, task, worker_id, str(error))
    else:
        queue.finish(database, task, worker_id, derived, may_update)


def derive_all(app) -> int:
    """Derive every queued scene now; returns how many."""
    database, count = app.extensions["lagrade.db"], 0
    while (task := queue.claim(database, "test-deriver", lease_s=60)) is not None:
        derive_one(app, task)
        count += 1
    return count
