"""Migrations run by `grader db upgrade`: from nothing to the newest schema, and back down."""

import pytest
from click.testing import CliRunner
from sqlalchemy import create_engine, inspect

from grader.cli.db import db as db_command
from grader.store.migrate import current_revision, head_revision, upgrade
from grader.store.models import Base


@pytest.fixture
def url(tmp_path, monkeypatch):
    url = f"sqlite:///{tmp_path / 'fresh.sqlite'}"
    monkeypatch.setenv("DATABASE_URL", url)
    return url


def _tables(url: str) -> set[str]:
    engine = create_engine(url)
    try:
        return set(inspect(engine).get_table_names())
    finally:
        engine.dispose()


def test_grader_db_upgrade_creates_the_schema(url):
    result = CliRunner().invoke(db_command, ["upgrade"])
    assert result.exit_code == 0, result.output
    assert f"is at revision {head_revision()}" in result.output
    assert set(Base.metadata.tables) <= _tables(url)


def test_upgrade_is_idempotent_and_downgrade_undoes_it(url):
    assert upgrade(url) == upgrade(url) == head_revision()
    from alembic import command

    from grader.store.migrate import alembic_config

    command.downgrade(alembic_config(url), "base")
    assert current_revision(url) is None and _tables(url) <= {"alembic_version"}
    assert upgrade(url) == head_revision()


def test_grader_db_create_user_makes_a_sign_in_account(url):
    result = CliRunner().invoke(db_command, ["create-user", "--role", "instructor", "--email", "prof@example.org"])
    assert result.exit_code == 0, result.output
    password = result.output.split()[-1]
    from grader.store.db import Database
    from grader.store.users import authenticate

    database = Database(url)
    with database.read() as session:
        assert authenticate(session, "prof@example.org", password).role == "instructor"
    database.dispose()


def test_upgrading_a_database_in_use_keeps_its_rows_and_adds_the_derivation_jobs(url):
    """A database made by revision 0001, with a user in it, gains the job table and loses nothing."""
    upgrade(url, "0001")
    engine = create_engine(url)
    try:
        with engine.begin() as connection:
            connection.exec_driver_sql("INSERT INTO users (role, name, created_at) VALUES ('instructor', 'Ine', "
                                       "'2026-11-21 00:00:00')")
        assert "derivation_jobs" not in set(inspect(engine).get_table_names())
        assert upgrade(url) == head_revision()
        assert "derivation_jobs" in set(inspect(engine).get_table_names())
        with engine.connect() as connection:
            assert connection.exec_driver_sql("SELECT name FROM users").scalars().all() == ["Ine"]
    finally:
        engine.dispose()


@pytest.fixture
def empty_url(request, database_kind, tmp_path):
    """An empty database (no tables) of the kind under test: SQLite, or a new PostgreSQL database."""
    if database_kind == "sqlite":
        yield f"sqlite:///{tmp_path / 'old.sqlite'}"
        return
    import uuid

    from sqlalchemy.engine import make_url

    server = request.getfixturevalue("postgres_server")
    admin = create_engine(server, isolation_level="AUTOCOMMIT")
    name = f"m_{uuid.uuid4().hex[:16]}"
    with admin.connect() as connection:
        connection.exec_driver_sql(f"CREATE DATABASE {name}")
    yield make_url(server).set(database=name).render_as_string(hide_password=False)
    with admin.connect() as connection:
        connection.exec_driver_sql(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)")
    admin.dispose()


def test_upgrading_a_database_with_submissions_keeps_every_one_and_adds_assignments(empty_url, database_kind):
    """A database made by revision 0002, with a graded submission in it, gains the assignment tables;
    the submission, its verdict and its text are all still there, in no assignment."""
    url = empty_url
    upgrade(url, "0002")
    engine = create_engine(url)
    true = "true" if database_kind == "postgresql" else "1"
    try:
        with engine.begin() as connection:
            run = connection.exec_driver_sql
            run("INSERT INTO users (id, role, name, created_at) VALUES (1, 'student', 'Ada', '2026-11-21 00:00:00')")
            run("INSERT INTO problems (id, slug, created_at) VALUES (1, 'yoyo', '2026-11-21 00:00:00')")
            run("INSERT INTO problem_versions (id, problem_id, number, title, statement, source, source_sha256, "
                "derivation, \"references\", engine_version, published, created_at) VALUES (1, 1, 1, 'Yo-yo', 's', "
                f"'src', 'x', '{{}}', '[]', 'test', {true}, '2026-11-21 00:00:00')")
            run("INSERT INTO submissions (id, user_id, requester_id, problem_version_id, grading_version_id, "
                "answer_name, text, received_at, status, grading_round, attempts, updated_at) VALUES "
                "(1, 1, 1, 1, 1, 'tension', 'm*g/3', '2026-11-21 00:00:00', 'done', 1, 1, '2026-11-21 00:00:00')")
            run("INSERT INTO verdicts (submission_id, grading_round, problem_version_id, verdict, score, graded_at) "
                "VALUES (1, 1, 1, 'equivalent', 1.0, '2026-11-21 00:00:00')")
        assert upgrade(url) == head_revision()
        assert {"assignments", "assignment_problems", "parameter_draws"} <= set(inspect(engine).get_table_names())
        with engine.connect() as connection:
            rows = connection.exec_driver_sql(
                "SELECT s.text, s.assignment_id, v.score FROM submissions s JOIN verdicts v ON v.submission_id = s.id"
            ).all()
        assert [tuple(r) for r in rows] == [("m*g/3", None, 1.0)]
    finally:
        engine.dispose()
