"""Derivation workers: every queued scene ends done (a problem version) or failed (with the reason)."""

import re
import socket
import time

import pytest

from grader.bench.isolation import pathological_scene
from grader.jobs import derivation_queue as queue
from grader.jobs.derivation import DerivationError
from grader.jobs.derivation_workers import DerivationWorkerPool
from grader.store.models import DerivationJob
from grader.store.users import create_user

BROKEN = 'id = "x"\n[energy\n'


def anyone_may_update(session, requester, problem):
    return True


@pytest.fixture
def instructor(database):
    with database.write() as session:
        return create_user(session, role="instructor", name="Ine").id


@pytest.fixture
def fake_deriver(yoyo):
    """The hand-written yo-yo for any scene but BROKEN, which fails as the engine would say."""
    def factory():
        def derive(source, filename):
            if source == BROKEN:
                raise DerivationError(f"{filename}: line 2: expected ']'")
            return yoyo
        return derive
    return factory


def _wait(database, job_id, timeout=60.0) -> DerivationJob:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with database.read() as session:
            job = session.get(DerivationJob, job_id)
        if job.status in ("done", "failed"):
            return job
        time.sleep(0.05)
    raise AssertionError(f"job {job_id} still {job.status} after {timeout} s")


@pytest.mark.parametrize("source, status, error", [
    ('id = "yoyo"\n', "done", None),
    (BROKEN, "failed", "upload.toml: line 2: expected ']'"),
])
def test_a_queued_scene_is_derived_by_a_worker(database, instructor, fake_deriver, source, status, error):
    job_id = queue.enqueue(database, requester_id=instructor, source=source)
    pool = DerivationWorkerPool(database, may_update=anyone_may_update, deriver_factory=fake_deriver,
                                poll_s=0.05).start()
    try:
        job = _wait(database, job_id)
    finally:
        pool.stop()
    assert (job.status, job.error) == (status, error)
    assert (job.problem_version_id is not None) == (status == "done")


def test_jobs_left_running_by_a_stopped_server_are_derived_after_the_restart(database, instructor, fake_deriver):
    job_id = queue.enqueue(database, requester_id=instructor, source='id = "yoyo"\n')
    queue.claim(database, f"{socket.gethostname()}:{2 ** 22 + 7}:old/d0", lease_s=600)  # its process is gone
    pool = DerivationWorkerPool(database, may_update=anyone_may_update, deriver_factory=fake_deriver,
                                poll_s=0.05).start()
    try:
        job = _wait(database, job_id)
    finally:
        pool.stop()
    assert (job.status, job.attempts) == ("done", 2)


def test_a_broken_sandbox_gives_the_job_back_rather_than_failing_the_scene(database, instructor, yoyo):
    calls = []

    def factory():
        def derive(source, filename):
            calls.append(filename)
            if len(calls) == 1:
                raise RuntimeError("the sandboxed child did not start")
            return yoyo
        return derive

    job_id = queue.enqueue(database, requester_id=instructor, source='id = "yoyo"\n')
    pool = DerivationWorkerPool(database, may_update=anyone_may_update, deriver_factory=factory, poll_s=0.05).start()
    try:
        job = _wait(database, job_id)
    finally:
        pool.stop()
    assert (job.status, job.attempts, len(calls)) == ("done", 2, 2)


@pytest.mark.slow
def test_a_pathological_scene_fails_at_its_time_limit_and_the_next_scene_is_derived(database, instructor):
    """Real sandbox children: a four-link chain cannot be derived in a second; a two-link one can."""
    slow = queue.enqueue(database, requester_id=instructor, source=pathological_scene(4), filename="chain4.toml")
    pool = DerivationWorkerPool(database, may_update=anyone_may_update, timeout_s=1.0, poll_s=0.05).start()
    try:
        stopped = _wait(database, slow)
    finally:
        pool.stop()
    assert stopped.status == "failed"
    # The engine's budget (0.9 s) names the step; the child's kill at 1 s is the backstop.
    assert re.fullmatch(r"chain4\.toml: the derivation (ran out of its 0\.9 s budget while .+"
                        r"|took longer than 1 s and was stopped)", stopped.error), stopped.error
    fast = queue.enqueue(database, requester_id=instructor, source=pathological_scene(2), filename="chain2.toml")
    pool = DerivationWorkerPool(database, may_update=anyone_may_update, poll_s=0.05).start()
    try:
        done = _wait(database, fast)
    finally:
        pool.stop()
    assert done.status == "done", done.error
