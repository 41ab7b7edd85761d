"""``grader token create``: an API user and its bearer token (printed once, stored hashed)."""

from __future__ import annotations

import click

from grader.store.db import Database, default_url


@click.group()
def token() -> None:
    """API bearer tokens."""


@token.command()
@click.option("--role", type=click.Choice(["student", "instructor", "admin", "lms"]), required=True)
@click.option("--name", help="Who the token is for (default: '<role> <n>').")
@click.option("--external-id", help="Students: the id an LMS knows them by.")
def create(role: str, name: str | None, external_id: str | None) -> None:
    """Create a user with ROLE and print its token as the last word of the output."""
    from sqlalchemy import func, select

    from grader.store.migrate import upgrade
    from grader.store.models import User
    from grader.store.users import create_token, create_user

    url = default_url()
    upgrade(url)
    database = Database(url)
    try:
        with database.write() as session:
            if name is None:
                count = session.scalar(select(func.count()).select_from(User).where(User.role == role))
                name = f"{role} {count + 1}"
            try:
                user = create_user(session, role=role, name=name, external_id=external_id)
            except ValueError as error:
                raise click.BadParameter(str(error), param_hint="--external-id") from None
            secret = create_token(session, user, name=name)
            user_id = user.id
    finally:
        database.dispose()
    click.echo(f"created {role} {name!r} (user {user_id}); token: {secret}")
