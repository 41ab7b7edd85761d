"""Two gunicorn web processes on one PostgreSQL database and one Redis: rate limits are shared and
start-up recovery takes back only what a dead process left, never what a live one holds.

The processes run the production entry point (``gunicorn grader.web.wsgi:app``), as docker-compose's
``web`` service does, started here as plain processes (no Docker engine on these machines).
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from datetime import timedelta
from pathlib import Path

import pytest
import requests
from sqlalchemy import select

from grader.jobs import queue
from grader.store.models import ProblemVersion, Submission, User, Verdict, utcnow
from grader.store.problems import save_problem
from grader.store.users import create_token, create_user

pytestmark = [pytest.mark.server, pytest.mark.slow, pytest.mark.postgresql_only]

ROOT = Path(__file__).resolve().parents[2]


class Web:
    """One ``gunicorn`` master with one worker, in its own process group."""

    def __init__(self, tmp_path: Path, name: str, env: dict[str, str]):
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            self.port = probe.getsockname()[1]
        self.log = tmp_path / f"{name}.log"
        self.process = subprocess.Popen(
            [sys.executable, "-m", "gunicorn", "-w", "1", "-b", f"127.0.0.1:{self.port}", "--timeout", "60",
             "grader.web.wsgi:app"], cwd=tmp_path, env=env, stdout=self.log.open("wb"), stderr=subprocess.STDOUT,
            start_new_session=True)
        self.base = f"http://127.0.0.1:{self.port}"
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            try:
                if requests.get(f"{self.base}/api/v1/health", timeout=1).status_code == 200:
                    return
            except requests.RequestException:
                time.sleep(0.2)
        self.stop()
        pytest.fail(f"gunicorn did not start:\n{self.log.read_text(errors='replace')[-3000:]}")

    def stop(self) -> None:
        try:
            os.killpg(self.process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        self.process.wait()


@pytest.fixture
def web(tmp_path, database_url, redis_url):
    env = {**os.environ, "DATABASE_URL": database_url, "PYTHONPATH": str(ROOT / "tests"),
           "LAGRADE_SECRET_KEY": "scale-out-test", "LAGRADE_RATELIMIT_STORAGE_URI": redis_url,
           "LAGRADE_RATE_LIMITS_ENABLED": "true", "LAGRADE_RATE_LIMITS": '{"check": [6, 3]}'}
    env.pop("GRADER_BROKER_URL", None)
    started: list[Web] = []

    def start(name: str) -> Web:
        started.append(Web(tmp_path, name, env))
        return started[-1]

    yield start
    for process in started:
        process.stop()


@pytest.fixture
def student_token(database):
    with database.write() as session:
        return create_token(session, create_user(session, role="student", name="Ada"))


def test_two_processes_share_one_rate_limit(web, student_token):
    a, b = web("a"), web("b")
    headers = {"Authorization": f"Bearer {student_token}"}
    body = {"reference": "m*g", "answer": "g*m", "variables": {"m": {"dimension": "mass"},
                                                               "g": {"dimension": "acceleration"}}}
    codes = [requests.post(f"{server.base}/api/v1/check", json=body, headers=headers, timeout=30).status_code
             for server in (a, b, a, b)]
    assert codes == [200, 200, 200, 429]  # a burst of 3, counted across both processes
    assert requests.post(f"{a.base}/api/v1/check", json=body, headers=headers, timeout=30).headers["Retry-After"]


def test_a_starting_process_takes_back_only_what_a_dead_process_left(web, database, yoyo):
    a = web("a")
    with database.write() as session:
        version, _ = save_problem(session, yoyo)
        student = create_user(session, role="student", name="Ada")
        version_id, student_id = version.id, student.id
    with database.read() as session:
        version, student = session.get(ProblemVersion, version_id), session.get(User, student_id)
    left_by_dead = queue.submit(database, user=student, version=version, answer="tension", text="g*m/3")[0]
    held_by_a = queue.submit(database, user=student, version=version, answer="tension", text="m*g")[0]
    live_holder = f"{socket.gethostname()}:{a.process.pid}:pool/0"
    dead_holder = f"{socket.gethostname()}:{2 ** 22 + 7}:pool/0"  # no process has that pid
    # Claimed as if by those workers, with leases that would not run out during the test. Process a
    # is already up, so only the second process's start-up recovery can give either back.
    for submission_id, holder in ((left_by_dead, dead_holder), (held_by_a, live_holder)):
        with database.write() as session:
            row = session.get(Submission, submission_id)
            row.status, row.worker_id, row.lease_until = "running", holder, utcnow() + timedelta(hours=1)
    web("b")
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        with database.read() as session:
            if session.get(Submission, left_by_dead).status == "done":
                break
        time.sleep(0.2)
    with database.read() as session:
        assert session.get(Submission, left_by_dead).status == "done"
        assert [v.verdict for v in session.scalars(select(Verdict).where(Verdict.submission_id == left_by_dead))] \
            == ["equivalent"]
        held = session.get(Submission, held_by_a)
        assert (held.status, held.worker_id) == ("running", live_holder)  # a's claim is a's
