"""Passwords from the command line: ``grader db reset-password``, and where ``grader serve`` puts the
first start's demo passwords (a terminal sees them once; a log file never holds them)."""

import os
import stat

import pytest
from click.testing import CliRunner

from grader.cli.db import db as db_command
from grader.cli.serve import PASSWORDS_FILE, _demo_accounts, _show_once
from grader.store.db import Database
from grader.store.migrate import upgrade
from grader.store.users import authenticate, create_user

OLD = "the old password"


@pytest.fixture
def url(tmp_path, monkeypatch):
    url = f"sqlite:///{tmp_path / 'accounts.sqlite'}"
    monkeypatch.setenv("DATABASE_URL", url)
    upgrade(url)
    database = Database(url)
    with database.write() as session:
        create_user(session, role="instructor", name="Ine", email="ine@example.org", password=OLD)
    database.dispose()
    return url


def _signs_in(url, email, password) -> bool:
    database = Database(url)
    try:
        with database.read() as session:
            return authenticate(session, email, password) is not None
    finally:
        database.dispose()


def test_reset_password_prints_a_new_random_one_that_signs_in(url):
    result = CliRunner().invoke(db_command, ["reset-password", "--email", "ine@example.org"])
    assert result.exit_code == 0, result.output
    password = result.output.strip().rsplit(": ", 1)[1]
    assert len(password) >= 16 and _signs_in(url, "ine@example.org", password)
    assert not _signs_in(url, "ine@example.org", OLD)


def test_reset_password_takes_a_chosen_one_without_echoing_it(url):
    result = CliRunner().invoke(db_command, ["reset-password", "--email", "ine@example.org",
                                            "--password", "chosen with care"])
    assert result.exit_code == 0 and "chosen with care" not in result.output
    assert _signs_in(url, "ine@example.org", "chosen with care")


@pytest.mark.parametrize("args, message", [
    (["--email", "nobody@example.org"], "no account with the email 'nobody@example.org'"),
    (["--email", "ine@example.org", "--password", "short"], "at least 10 characters"),
])
def test_reset_password_refuses_with_one_line_and_changes_nothing(url, args, message):
    result = CliRunner().invoke(db_command, ["reset-password", *args])
    assert result.exit_code == 1 and message in result.output and "Traceback" not in result.output
    assert _signs_in(url, "ine@example.org", OLD)


@pytest.fixture
def fresh(tmp_path):
    url = f"sqlite:///{tmp_path / 'fresh.sqlite'}"
    upgrade(url)
    database = Database(url)
    yield database
    database.dispose()


def test_first_start_on_a_terminal_prints_the_passwords_once(fresh, tmp_path):
    lines = _show_once(_demo_accounts(fresh), tmp_path / "instance", terminal=True)
    assert any("instructor@example.org  password: " in line for line in lines)
    assert not (tmp_path / "instance" / PASSWORDS_FILE).exists()
    assert _demo_accounts(fresh) == []  # the second start makes none


def test_first_start_into_a_log_writes_the_passwords_to_a_private_file(fresh, tmp_path):
    instance = tmp_path / "instance"
    made = _demo_accounts(fresh)
    lines = _show_once(made, instance, terminal=False)
    path = instance / PASSWORDS_FILE
    assert len(lines) == 1 and str(path) in lines[0] and "password:" not in lines[0]
    assert stat.S_IMODE(os.stat(path).st_mode) == 0o600
    written = path.read_text()
    assert written.splitlines() == made
    email, password = next((line.split()[1], line.split()[-1]) for line in made if "student@" in line)
    with fresh.read() as session:
        assert authenticate(session, email, password) is not None


def test_a_passwords_file_left_with_wide_modes_is_made_private(fresh, tmp_path):
    instance = tmp_path / "instance"
    instance.mkdir()
    (instance / PASSWORDS_FILE).write_text("old\n")
    os.chmod(instance / PASSWORDS_FILE, 0o644)
    _show_once(_demo_accounts(fresh), instance, terminal=False)
    assert stat.S_IMODE(os.stat(instance / PASSWORDS_FILE).st_mode) == 0o600
    assert "old" not in (instance / PASSWORDS_FILE).read_text()
