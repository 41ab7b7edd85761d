"""Grading on real Celery worker processes over a real Redis server: nothing lost, graded once.

Each test starts ``redis-server`` (Debian's package) on a free loopback port and ``celery worker``
processes on the test's database (SQLite and PostgreSQL, like every test in tests/jobs). Under
``CI=true`` a missing redis-server fails the test rather than skipping it.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from sqlalchemy import func, select

from grader.jobs import queue
from grader.store.models import ProblemVersion, Submission, User, Verdict
from grader.store.problems import save_problem
from grader.store.users import create_user

pytestmark = [pytest.mark.server, pytest.mark.slow]

TESTS = Path(__file__).resolve().parents[1]
ROOT = TESTS.parent


class Workers:
    """``celery worker`` processes (each in its own process group, so kill -9 takes all of it)."""

    def __init__(self, tmp_path: Path, redis_url: str, database_url: str):
        self.tmp_path, self.processes = tmp_path, []
        self.env = {**os.environ, "GRADER_BROKER_URL": redis_url, "DATABASE_URL": database_url,
                    "PYTHONPATH": os.pathsep.join([str(TESTS), str(ROOT)]),
                    "GRADER_CHECKER_FACTORY": "celery_checkers:slow_sandbox_checker",
                    "GRADER_TASK_TIME_LIMIT_S": "20", "GRADER_LEASE_S": "6", "GRADER_BROKER_VISIBILITY_S": "4",
                    "GRADER_SWEEP_S": "2"}

    def start(self, name: str, delay_s: float = 0.0) -> subprocess.Popen:
        log = open(self.tmp_path / f"{name}.log", "wb")
        process = subprocess.Popen(
            [sys.executable, "-m", "celery", "-A", "grader.jobs.celery_worker", "worker", "--pool", "solo",
             "--loglevel", "INFO", "-n", f"{name}@%h", "--without-gossip", "--without-mingle", "--without-heartbeat"],
            cwd=self.tmp_path, env={**self.env, "LAGRADE_TEST_CHECK_DELAY_S": str(delay_s)},
            stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        self.processes.append(process)
        return process

    def kill(self, process: subprocess.Popen) -> None:
        try:
            os.killpg(process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        process.wait()

    def stop_all(self) -> None:
        for process in self.processes:
            self.kill(process)

    def logs(self) -> str:
        return "\n".join(p.read_text(errors="replace")[-3000:] for p in sorted(self.tmp_path.glob("*.log")))


@pytest.fixture
def workers(tmp_path, redis_url, database_url):
    pool = Workers(tmp_path, redis_url, database_url)
    yield pool
    pool.stop_all()


@pytest.fixture
def broker(redis_url, monkeypatch):
    """This process announces queued work to the broker, as a web process does."""
    from grader.jobs import celery_worker

    monkeypatch.setattr(celery_worker.app.conf, "broker_url", redis_url)
    queue.add_publisher(celery_worker.publish)
    yield celery_worker
    queue._publishers.remove(celery_worker.publish)


@pytest.fixture
def setup(database, yoyo):
    with database.write() as session:
        version, _ = save_problem(session, yoyo)
        student = create_user(session, role="student", name="Ada")
        return {"version": version.id, "student": student.id}


def _submit(database, setup, text):
    with database.read() as session:
        version, student = session.get(ProblemVersion, setup["version"]), session.get(User, setup["student"])
    return queue.submit(database, user=student, version=version, answer="tension", text=text)[0]


def _wait(database, ids, status="done", timeout=90.0, workers=None):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with database.read() as session:
            rows = dict(session.execute(select(Submission.id, Submission.status).where(Submission.id.in_(ids))).all())
        if all(rows.get(i) == status for i in ids):
            return
        time.sleep(0.1)
    pytest.fail(f"not all {status} after {timeout} s: {rows}\n{workers.logs() if workers else ''}")


def _verdicts(database, ids):
    with database.read() as session:
        return {i: session.scalars(select(Verdict).where(Verdict.submission_id == i)).all() for i in ids}


def test_a_worker_grades_what_the_web_process_announces(database, setup, workers, broker):
    workers.start("w1")
    right = [_submit(database, setup, text) for text in ("g*m/3", "m g / 3", "(1/3) m g")]
    wrong = [_submit(database, setup, text) for text in ("m*g", "g*m/2")]
    _wait(database, right + wrong, workers=workers)
    verdicts = _verdicts(database, right + wrong)
    assert [verdicts[i][0].verdict for i in right] == ["equivalent"] * 3
    assert [verdicts[i][0].verdict for i in wrong] == ["not_equivalent"] * 2
    assert all(len(v) == 1 for v in verdicts.values())


def test_a_worker_killed_mid_job_gets_the_job_back_and_it_is_graded_exactly_once(database, setup, workers, broker):
    first = workers.start("doomed", delay_s=3.0)
    ids = [_submit(database, setup, text) for text in ("g*m/3", "m*g", "g*m/3 + 0")]
    _wait(database, ids[:1], status="running", timeout=60, workers=workers)
    workers.kill(first)  # kill -9 in the middle of grading ids[0]: its message was never acknowledged
    workers.start("rescuer")
    _wait(database, ids, workers=workers)
    verdicts = _verdicts(database, ids)
    assert all(len(v) == 1 and v[0].grading_round == 1 for v in verdicts.values())  # nothing lost, none twice
    with database.read() as session:
        attempts = session.get(Submission, ids[0]).attempts
    assert attempts == 2  # claimed by the killed worker, then again after redelivery


def test_a_duplicate_message_does_not_grade_twice(database, setup, workers, broker):
    submission = _submit(database, setup, "g*m/3")
    broker.publish([(submission, 1), (submission, 1)])  # the announce above plus two more
    workers.start("w1")
    _wait(database, [submission], workers=workers)
    time.sleep(1.0)  # give the duplicates time to be consumed
    assert len(_verdicts(database, [submission])[submission]) == 1


def test_work_whose_message_never_reached_the_broker_is_found_by_the_sweep(database, setup, workers):
    # No publisher in this process: the submission is committed as queued but never announced.
    submission = _submit(database, setup, "g*m/3")
    workers.start("w1")  # its sweep (every 2 s here) announces queued rows older than 2 s
    _wait(database, [submission], timeout=60, workers=workers)
    with database.read() as session:
        assert session.scalar(select(func.count()).select_from(Verdict)) == 1
