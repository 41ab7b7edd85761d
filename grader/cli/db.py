"""``grader db``: migrate the database and manage sign-in accounts, courses and enrolments."""

from __future__ import annotations

import secrets

import click

from grader.store.db import Database, default_url


@click.group()
def db() -> None:
    """The service's database (DATABASE_URL, default instance/lagrade.sqlite)."""


@db.command()
@click.option("--revision", default="head", show_default=True, help="Alembic revision to go to.")
def upgrade(revision: str) -> None:
    """Create or migrate the database to the newest schema."""
    from grader.store.migrate import upgrade as run_upgrade

    url = default_url()
    click.echo(f"database {_safe(url)} is at revision {run_upgrade(url, revision)}")


@db.command()
def current() -> None:
    """Show the database's schema revision and the newest one."""
    from grader.store.migrate import current_revision, head_revision

    url = default_url()
    click.echo(f"database {_safe(url)}: revision {current_revision(url)} (newest: {head_revision()})")


@db.command("create-user")
@click.option("--role", type=click.Choice(["student", "instructor", "admin"]), required=True)
@click.option("--email", required=True, help="What the user signs in with.")
@click.option("--name", help="Display name (default: the email).")
@click.option("--password", help="Default: a random one, printed.")
def create_user(role: str, email: str, name: str | None, password: str | None) -> None:
    """Create an account that signs in on the web pages with email and password."""
    from grader.store.migrate import upgrade as run_upgrade
    from grader.store.users import create_user as add_user

    url = default_url()
    run_upgrade(url)
    password = password or secrets.token_urlsafe(9)
    database = Database(url)
    try:
        with database.write() as session:
            user = add_user(session, role=role, name=name or email, email=email, password=password)
            user_id = user.id
    finally:
        database.dispose()
    click.echo(f"created {role} {email} (user {user_id}) with password: {password}")


@db.command("create-course")
@click.argument("code")
@click.option("--title", help="Default: the code.")
def create_course(code: str, title: str | None) -> None:
    """Create the course CODE (its students see its published problems; see `grader db enrol`)."""
    from grader.store.courses import CourseError
    from grader.store.courses import create_course as create
    from grader.store.migrate import upgrade as run_upgrade

    url = default_url()
    run_upgrade(url)
    database = Database(url)
    try:
        with database.write() as session:
            course_id = create(session, code=code, title=title or code).id
    except CourseError as error:
        raise click.ClickException(str(error)) from None
    finally:
        database.dispose()
    click.echo(f"created course {code} (course {course_id})")


@db.command()
@click.argument("code")
@click.option("--user", "user_id", type=int, required=True,
              help="The user's id, as create-user or token create printed it.")
@click.option("--as", "role", type=click.Choice(["student", "ta", "instructor", "lms"]), default="student",
              show_default=True, help="instructor: manages the course's problems; ta: reads its roster and "
                   "gradebook, never publishes; lms: links an LMS account, which may then submit "
                   "for students and read grades of the course's problems.")
def enrol(code: str, user_id: int, role: str) -> None:
    """Enrol a user in the course CODE (again: change their role in it). Access rules: grader.web.policy."""
    from sqlalchemy import select

    from grader.store.migrate import upgrade as run_upgrade
    from grader.store.models import Course, Enrolment, User

    url = default_url()
    run_upgrade(url)
    database = Database(url)
    try:
        with database.write() as session:
            course = session.scalar(select(Course).where(Course.code == code))
            user = session.get(User, user_id)
            if course is None:
                raise click.ClickException(f"there is no course {code!r}")
            if user is None:
                raise click.ClickException(f"there is no user {user_id}")
            # An LMS account is only ever linked (role lms), and only instructors can teach.
            if (role == "lms") != (user.role == "lms") or (role == "instructor" and user.role != "instructor"):
                raise click.ClickException(f"user {user_id} is a {user.role} account; it cannot be enrolled as {role}")
            enrolment = session.scalar(select(Enrolment).where(Enrolment.user_id == user_id,
                                                               Enrolment.course_id == course.id))
            if enrolment is None:
                session.add(Enrolment(user_id=user_id, course_id=course.id, role=role))
            else:
                enrolment.role = role
    finally:
        database.dispose()
    click.echo(f"enrolled user {user_id} in {code} as {role}")


def _safe(url: str) -> str:
    """The URL without its password."""
    from sqlalchemy.engine import make_url

    return make_url(url).render_as_string(hide_password=True)


@db.command("load-problems")
@click.argument("directory", default="problems", type=click.Path(file_okay=False, exists=True))
def load_problems(directory: str) -> None:
    """Derive and store the scene files in DIRECTORY (unchanged ones are skipped by their hash)."""
    from pathlib import Path

    from grader.jobs.derivation import close_shared_sandboxes, load_problem_files
    from grader.store.migrate import upgrade as run_upgrade

    url = default_url()
    run_upgrade(url)
    database = Database(url)
    try:
        for name, outcome in load_problem_files(database, sorted(Path(directory).glob("*.toml"))):
            click.echo(f"problem {name}: {outcome}")
    finally:
        close_shared_sandboxes()
        database.dispose()


@db.command("reset-password")
@click.option("--email", required=True, help="The account's sign-in email.")
@click.option("--password", help="The new password (default: a random one, printed once).")
def reset_password(email: str, password: str | None) -> None:
    """Give the account with EMAIL a new password (it is signed out of every browser)."""
    from sqlalchemy import select

    from grader.store.migrate import upgrade as run_upgrade
    from grader.store.models import User
    from grader.store.users import new_password_problem, set_password

    if password is not None and (problem := new_password_problem(password)) is not None:
        raise click.ClickException(problem)
    chosen = password or secrets.token_urlsafe(12)
    url = default_url()
    run_upgrade(url)
    database = Database(url)
    try:
        with database.write() as session:
            user = session.scalar(select(User).where(User.email == email))
            if user is None:
                raise click.ClickException(f"there is no account with the email {email!r}")
            set_password(user, chosen)
    finally:
        database.dispose()
    # A password typed on the command line is the caller's already: it is not echoed back.
    click.echo(f"new password of {email}: {chosen}" if password is None else f"changed the password of {email}")
