"""The real server: `grader serve` as a process on 127.0.0.1, killed with SIGKILL mid-grading and
restarted, and 16 concurrent clients submitting; every accepted submission ends with exactly one verdict."""

import os
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
import requests
from sqlalchemy import create_engine, text

from grader.bench.http import Server, accounted, make_tokens, run_load, submission_bodies

pytestmark = [pytest.mark.server, pytest.mark.slow]

YOYO = Path(__file__).resolve().parents[2] / "problems" / "yoyo.toml"
SUBMIT = "/api/v1/problems/yoyo/submissions"
BODIES = submission_bodies()  # each one a new attempt: the same text again would be the same submission


@pytest.fixture
def site(tmp_path, database_url):
    """A working directory with the yo-yo problem and a database URL (SQLite or PostgreSQL, migrated);
    servers started in it are killed after."""
    (tmp_path / "problems").mkdir()
    shutil.copy(YOYO, tmp_path / "problems" / "yoyo.toml")
    url = database_url
    servers = []

    def server(**kwargs) -> Server:
        instance = Server(tmp_path, database_url=url, problems=tmp_path / "problems",
                          env={"LAGRADE_RATE_LIMITS_ENABLED": "false"}, log_name=f"server-{len(servers)}.log", **kwargs)
        servers.append(instance)
        return instance

    yield tmp_path, url, server
    for instance in servers:
        instance.kill()


def _count(url: str, sql: str) -> int:
    engine = create_engine(url)
    try:
        with engine.connect() as connection:
            return connection.execute(text(sql)).scalar()
    finally:
        engine.dispose()


def test_token_create_prints_a_token_that_works_as_its_last_word(site):
    workdir, url, server = site
    done = subprocess.run([sys.executable, "-c", "from grader.cli import main; main()", "token", "create",
                           "--role", "instructor", "--name", "Prof"], cwd=workdir, capture_output=True, text=True,
                          env={**os.environ, "DATABASE_URL": url}, timeout=120, check=True)
    token = done.stdout.split()[-1]
    assert token.startswith("lg_")
    with server() as running:
        response = requests.get(f"{running.base_url}/api/v1/problems/yoyo", headers={"Authorization": f"Bearer {token}"},
                                timeout=30)
        assert response.status_code == 200
        assert {a["name"] for a in response.json()["answers"]} == {"acceleration", "angular_acceleration", "tension"}


def test_a_server_killed_mid_grading_loses_no_accepted_submission(site):
    workdir, url, server = site
    tokens = make_tokens(url, "student", 8)
    first = server(workers=1).start()
    stop = threading.Event()
    outcome = {}
    load = threading.Thread(target=lambda: outcome.setdefault("load", run_load(
        "submit", first.base_url, tokens, path=SUBMIT, bodies=BODIES, ok={202}, duration_s=120,
        max_requests=100_000, stop=stop)))
    load.start()
    deadline = time.monotonic() + 120
    # Killed with work in flight: 30 verdicts in, and a backlog the worker has not graded yet (a
    # worker that keeps up with eight clients would otherwise be killed idle, testing nothing).
    while (_count(url, "SELECT count(*) FROM verdicts") < 30
           or _count(url, "SELECT count(*) FROM submissions WHERE status IN ('queued', 'running')") < 3):
        assert time.monotonic() < deadline, first.log()
        time.sleep(0.005)
    first.kill()  # SIGKILL to the server's process group, while clients submit and the worker grades
    stop.set()
    load.join()
    accepted = outcome["load"].accepted
    pending = _count(url, "SELECT count(*) FROM submissions WHERE status IN ('queued', 'running')")
    assert len(accepted) >= 30 and pending > 0, "the kill came after all grading was done: nothing was tested"

    second = server(workers=2).start()
    result = accounted(url, accepted, timeout_s=180)
    assert result["missing"] == [] and result["not_graded"] == [], second.log()
    assert set(result["verdicts_in_effect"].values()) == {1}
    # And no stray verdict of any round: one row per submission in all.
    assert _count(url, "SELECT count(*) FROM verdicts") == _count(url, "SELECT count(*) FROM submissions")


def test_sixteen_concurrent_clients_get_no_errors_and_lose_nothing(site):
    """The acceptance load: 16 clients submitting for 30 s against SQLite, then every accepted
    submission is accounted for with exactly one verdict."""
    workdir, url, server = site
    tokens = make_tokens(url, "student", 16)
    with server() as running:
        load = run_load("submit", running.base_url, tokens, path=SUBMIT, bodies=BODIES, ok={202},
                        duration_s=30, max_requests=20000)
        result = accounted(url, load.accepted, timeout_s=300)
    assert load.errors == [] and load.requests == len(load.accepted) > 16
    assert result["missing"] == [] and result["not_graded"] == []
    assert set(result["verdicts_in_effect"].values()) == {1}


def test_serve_loads_problems_once_and_says_where_to_sign_in(site):
    workdir, url, server = site
    with server() as running:
        pass
    with server() as again:
        pass
    first_log, second_log = running.log_path.read_text(), again.log_path.read_text()
    assert "problem yoyo.toml: version 1 of 'yoyo'" in first_log
    assert "problem yoyo.toml: unchanged" in second_log
    assert "sign in at http://127.0.0.1:" in first_log
    assert _count(url, "SELECT count(*) FROM problem_versions") == 1

