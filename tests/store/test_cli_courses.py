"""`grader db create-course` and `grader db enrol`: the courses and links the access policy reads."""

import pytest
from click.testing import CliRunner

from grader.cli.db import db as db_command
from grader.store.db import Database
from grader.store.migrate import upgrade
from grader.store.models import User
from grader.store.users import create_user
from grader.web.policy import Principal


@pytest.fixture
def url(tmp_path, monkeypatch):
    url = f"sqlite:///{tmp_path / 'courses.sqlite'}"
    monkeypatch.setenv("DATABASE_URL", url)
    upgrade(url)
    return url


@pytest.fixture
def users(url) -> dict[str, int]:
    database = Database(url)
    with database.write() as session:
        made = {role: create_user(session, role=role, name=role).id for role in ("student", "instructor", "lms")}
    database.dispose()
    return made


def _run(*args: str):
    return CliRunner().invoke(db_command, list(args))


def _principal(url: str, user_id: int) -> Principal:
    database = Database(url)
    try:
        with database.read() as session:
            return Principal.of(session, session.get(User, user_id))
    finally:
        database.dispose()


def test_an_enrolment_gives_the_policy_its_courses(url, users):
    assert _run("create-course", "MECH", "--title", "Mechanics").exit_code == 0
    for role in ("student", "instructor", "lms"):
        result = _run("enrol", "MECH", "--user", str(users[role]), "--as", role)
        assert result.exit_code == 0 and f"as {role}" in result.output
    instructor, lms = _principal(url, users["instructor"]), _principal(url, users["lms"])
    assert instructor.manages_course(1) and instructor.taught == {1}
    assert lms.in_scope(1) and not lms.manages_course(1)  # a linked LMS: its course's problems, not to manage
    assert _principal(url, users["student"]).enrolled == {1}


def test_enrolling_again_changes_the_role(url, users):
    _run("create-course", "MECH")
    _run("enrol", "MECH", "--user", str(users["instructor"]), "--as", "student")
    assert _principal(url, users["instructor"]).taught == frozenset()
    _run("enrol", "MECH", "--user", str(users["instructor"]), "--as", "instructor")
    assert _principal(url, users["instructor"]).taught == {1}


@pytest.mark.parametrize("args, message", [
    (("enrol", "NOPE", "--user", "1"), "no course 'NOPE'"),
    (("enrol", "MECH", "--user", "99"), "no user 99"),
    (("enrol", "MECH", "--user", "1", "--as", "lms"), "student account; it cannot be enrolled as lms"),
    (("enrol", "MECH", "--user", "3", "--as", "student"), "lms account; it cannot be enrolled as student"),
    (("enrol", "MECH", "--user", "1", "--as", "instructor"), "cannot be enrolled as instructor"),
    (("create-course", "MECH"), "already a course 'MECH'"),
    (("create-course", "mech"), "already a course 'MECH'"),  # codes differ by more than case
    (("create-course", "--", "-x"), "'-x' is not a course code"),
    (("create-course", "Ω²ǅ"), "'Ω²ǅ' is not a course code"),
])
def test_mistakes_are_refused_in_one_line(url, users, args, message):
    _run("create-course", "MECH")
    result = _run(*args)
    assert result.exit_code == 1 and message in result.output and "Traceback" not in result.output


def test_a_teaching_assistant_grades_but_does_not_manage(url, users):
    _run("create-course", "MECH")
    result = _run("enrol", "MECH", "--user", str(users["student"]), "--as", "ta")
    assert result.exit_code == 0 and "as ta" in result.output
    ta = _principal(url, users["student"])
    assert ta.assisted == {1} and ta.taught == frozenset() and not ta.manages_course(1)
