"""Shared fixtures: a migrated temporary SQLite database, the app on it, clients and tokens.

``yoyo_version`` stores a problem version whose references are written out by hand in the shape
``grader.mechanics`` produces (the yo-yo of problems/yoyo.toml: a = 2g/3, T = mg/3), so the store,
queue and API can be tested without running the engine; tests that need the engine derive for real.
"""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import time
import uuid
from pathlib import Path

import pytest
from sqlalchemy import create_engine
from sqlalchemy.engine import make_url

from grader.store.db import Database
from grader.store.migrate import upgrade
from grader.store.problems import DerivedProblem, save_problem
from grader.store.users import create_token, create_user

_VARIABLES = {
    "g": {"dimension": "m*s^-2", "domain": "positive", "kind": "parameter"},
    "m": {"dimension": "kg", "domain": "positive", "kind": "parameter"},
}
YOYO = DerivedProblem(
    slug="yoyo",
    title="Yo-yo",
    statement="A light string is wound around a solid cylinder of mass $m$ that falls, unwinding it.",
    source='id = "yoyo"\n# hand-written test data\n',
    derivation={"id": "yoyo", "answers": {"acceleration": "2*g/3", "tension": "g*m/3"}},
    references=[
        {"name": "acceleration", "prompt": "Acceleration of the axis", "kind": "expression", "reference": "2*g/3",
         "variables": {"g": _VARIABLES["g"]}, "dimension": "m*s^-2", "latex": r"\frac{2 g}{3}", "feedback": []},
        {"name": "tension", "prompt": "Tension in the string", "kind": "expression", "reference": "g*m/3",
         "variables": _VARIABLES, "dimension": "kg*m*s^-2", "latex": r"\frac{g m}{3}",
         "feedback": [{"expr": "m*g", "message": "The tension must be less than the weight."}]},
    ],
    engine_version="test",
)


# The store, the queues and the API run on both databases the service supports; the rest on SQLite.
BOTH_DATABASES_DIRS = ("store", "jobs")
BOTH_DATABASES_PREFIX = "test_api_"
POSTGRES_SCRIPT = Path(__file__).resolve().parents[1] / ".ci" / "postgres"


def pytest_configure(config):
    config.addinivalue_line("markers", "sqlite_only: a fact about the SQLite set-up (not run on PostgreSQL)")
    config.addinivalue_line("markers", "postgresql_only: a fact about the PostgreSQL set-up (not run on SQLite)")


def pytest_generate_tests(metafunc):
    if "database_kind" not in metafunc.fixturenames or metafunc.definition.get_closest_marker("sqlite_only"):
        return
    if metafunc.definition.get_closest_marker("postgresql_only"):
        metafunc.parametrize("database_kind", ["postgresql"])
        return
    path = Path(str(metafunc.definition.path))
    if path.parent.name in BOTH_DATABASES_DIRS or path.name.startswith(BOTH_DATABASES_PREFIX):
        metafunc.parametrize("database_kind", ["sqlite", "postgresql"])


@pytest.fixture
def database_kind() -> str:
    return "sqlite"


@pytest.fixture(scope="session")
def postgres_server():
    """A PostgreSQL server: ``LAGRADE_TEST_POSTGRES_URL`` (``.ci/run`` starts one), else a throwaway
    cluster started here by ``.ci/postgres``. Skipped without the server package, except under CI."""
    url = os.environ.get("LAGRADE_TEST_POSTGRES_URL")
    if url:
        yield url
        return
    started = subprocess.run([str(POSTGRES_SCRIPT)], capture_output=True, text=True)
    if started.returncode != 0:
        reason = f"no PostgreSQL server for the tests: {started.stderr.strip()[-300:]}"
        if os.environ.get("CI") == "true":
            pytest.fail(reason)
        pytest.skip(reason)
    url, folder = started.stdout.split()
    yield url
    subprocess.run([str(POSTGRES_SCRIPT), "stop", folder], check=False)


@pytest.fixture(scope="session")
def postgres_template(postgres_server):
    """An admin engine and a migrated template database; each test gets a copy of it."""
    admin = create_engine(postgres_server, isolation_level="AUTOCOMMIT")
    name = f"lagrade_template_{os.getpid()}"
    with admin.connect() as connection:
        connection.exec_driver_sql(f"DROP DATABASE IF EXISTS {name}")
        connection.exec_driver_sql(f"CREATE DATABASE {name}")
    upgrade(_with_database(postgres_server, name))
    yield admin, name
    with admin.connect() as connection:
        connection.exec_driver_sql(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)")
    admin.dispose()


def _with_database(url: str, name: str) -> str:
    return make_url(url).set(database=name).render_as_string(hide_password=False)


@pytest.fixture
def database_url(request, database_kind, tmp_path):
    if database_kind == "sqlite":
        url = f"sqlite:///{tmp_path / 'lagrade.sqlite'}"
        upgrade(url)
        yield url
        return
    admin, template = request.getfixturevalue("postgres_template")
    name = f"t_{uuid.uuid4().hex[:16]}"
    with admin.connect() as connection:
        connection.exec_driver_sql(f"CREATE DATABASE {name} TEMPLATE {template}")
    yield _with_database(str(admin.url.render_as_string(hide_password=False)), name)
    with admin.connect() as connection:
        connection.exec_driver_sql(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)")


@pytest.fixture
def database(database_url):
    database = Database(database_url)
    yield database
    database.dispose()


@pytest.fixture
def app(database_url, tmp_path, monkeypatch):
    from grader.web import create_app

    monkeypatch.chdir(tmp_path)  # the instance folder goes here
    app = create_app({"TESTING": True, "DATABASE_URL": database_url, "SECRET_KEY": "test-secret"})
    yield app
    app.extensions["lagrade.checkers"].close()
    app.extensions["lagrade.db"].dispose()


@pytest.fixture
def client(app):
    return app.test_client()


@pytest.fixture
def runner(app):
    return app.test_cli_runner()


@pytest.fixture
def make_token(app):
    """``make_token(role, external_id=None) -> (user_id, headers)`` with an Authorization header."""

    def make(role: str, external_id: str | None = None, name: str | None = None):
        with app.extensions["lagrade.db"].write() as session:
            user = create_user(session, role=role, name=name or f"{role} {external_id or ''}".strip(),
                               external_id=external_id)
            secret = create_token(session, user)
            return user.id, {"Authorization": f"Bearer {secret}"}

    return make


@pytest.fixture
def enrol(app):
    """``enrol(user_id, code, role)``: the user enrolled in course ``code`` (made on first use) as ``role``
    (``"lms"`` links an LMS account to the course)."""
    from sqlalchemy import select

    from grader.store.models import Course, Enrolment

    def add(user_id: int, code: str, role: str = "student") -> int:
        with app.extensions["lagrade.db"].write() as session:
            course = session.scalar(select(Course).where(Course.code == code))
            if course is None:
                course = Course(code=code, title=code)
                session.add(course)
                session.flush()
            session.add(Enrolment(user_id=user_id, course_id=course.id, role=role))
            return course.id

    return add


@pytest.fixture
def yoyo() -> DerivedProblem:
    """The hand-written yo-yo problem (not stored)."""
    return YOYO


@pytest.fixture
def yoyo_version(app):
    """The hand-written yo-yo problem, stored as version 1 (published)."""
    with app.extensions["lagrade.db"].write() as session:
        version, _ = save_problem(session, YOYO)
        return version.id



@pytest.fixture
def workers(app):
    """Grading workers (real sandbox children) on the app's database, stopped after the test."""
    from grader.jobs import WorkerPool

    pool = WorkerPool(app.extensions["lagrade.db"], workers=2, poll_s=0.1).start()
    yield pool
    pool.stop()


@pytest.fixture
def derivers(app):
    """Derivation workers on the app's database, running the real engine in this process (no child)."""
    from grader.jobs.derivation_workers import DerivationWorkerPool
    from grader.web.policy import may_update
    from tests.web.derive_in_process import derive_in_process

    pool = DerivationWorkerPool(app.extensions["lagrade.db"], may_update=may_update,
                                deriver_factory=lambda: derive_in_process, poll_s=0.05).start()
    yield pool
    pool.stop()


@pytest.fixture
def poll(client):
    """``poll(url, headers)``: GET until the submission is graded; returns its JSON."""
    import time

    def wait(url: str, headers: dict, timeout: float = 60.0) -> dict:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            body = client.get(url, headers=headers).get_json()
            if body["status"] in ("done", "failed"):
                return body
            time.sleep(0.05)
        raise AssertionError(f"{url} not graded within {timeout} s: {body}")

    return wait


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="session")
def redis_server(tmp_path_factory):
    """A Redis server for the session (Debian's redis-server on a free loopback port), or
    ``LAGRADE_TEST_REDIS_URL``. Skipped without the package, except under CI."""
    url = os.environ.get("LAGRADE_TEST_REDIS_URL")
    if url:
        yield url
        return
    binary = shutil.which("redis-server")
    if binary is None:
        if os.environ.get("CI") == "true":
            pytest.fail("redis-server is not installed (apt-get install redis-server)")
        pytest.skip("redis-server is not installed (apt-get install redis-server)")
    port = free_port()
    server = subprocess.Popen([binary, "--port", str(port), "--bind", "127.0.0.1", "--save", "", "--appendonly", "no",
                               "--dir", str(tmp_path_factory.mktemp("redis"))],
                              stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
            break
        except OSError:
            time.sleep(0.05)
    yield f"redis://127.0.0.1:{port}/0"
    server.kill()
    server.wait()


@pytest.fixture
def redis_url(redis_server):
    """The session's Redis, emptied: no message of an earlier test is left to deliver."""
    import redis

    client = redis.Redis.from_url(redis_server)
    client.flushall()
    client.close()
    return redis_server
