"""``grader db``: migrate the database and manage sign-in accounts."""

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


def _safe(url: str) -> str:
    """The URL without its password."""
    from sqlalchemy.engine import make_url

    return make_url(url).render_as_string(hide_password=True)
