"""``grader lti``: register an LMS (LTI 1.3 platform), map its courses, list what is registered."""

from __future__ import annotations

import click

from grader.store.db import Database, default_url


def _database() -> Database:
    from grader.store.migrate import upgrade

    url = default_url()
    upgrade(url)
    return Database(url)


@click.group()
def lti() -> None:
    """LTI 1.3: the LMSs that may launch lagrade (see /lti/config for the URLs to give them)."""


@lti.command("add-platform")
@click.option("--name", default="", help="A name to show (default: the issuer).")
@click.option("--issuer", required=True, help="The platform's issuer (iss), e.g. https://canvas.instructure.com.")
@click.option("--client-id", required=True, help="The client id the platform gave this tool.")
@click.option("--deployment", "deployments", multiple=True, required=True,
              help="A deployment id the platform may launch with (repeat for several).")
@click.option("--auth-url", required=True, help="The platform's OIDC authorisation URL.")
@click.option("--token-url", required=True, help="The platform's OAuth 2 token URL (grade and roster services).")
@click.option("--jwks-url", required=True, help="The platform's public keys (JWKS) URL.")
def add_platform(name: str, issuer: str, client_id: str, deployments: tuple[str, ...], auth_url: str,
                 token_url: str, jwks_url: str) -> None:
    """Register an LMS, or update its URLs and add deployments if it is registered already."""
    from grader.web.lti.platforms import PlatformError, register_platform

    database = _database()
    try:
        with database.write() as session:
            platform = register_platform(session, name=name, issuer=issuer, client_id=client_id, auth_url=auth_url,
                                         token_url=token_url, jwks_url=jwks_url, deployment_ids=list(deployments))
            line = (f"platform {platform.id} {platform.name!r}: issuer {platform.issuer}, client id "
                    f"{platform.client_id}, deployments {', '.join(d.deployment_id for d in platform.deployments)}")
    except PlatformError as error:
        raise click.UsageError(str(error)) from None
    finally:
        database.dispose()
    click.echo(line)


@lti.command("map-context")
@click.option("--platform", "platform_id", type=int, required=True, help="The platform's number (grader lti list).")
@click.option("--context", "context_id", required=True, help="The LMS course's context id.")
@click.option("--course", "course_code", required=True, help="The lagrade course code it is.")
def map_context(platform_id: int, context_id: str, course_code: str) -> None:
    """Make an LMS course launch into an existing lagrade course (instead of a new one of its own)."""
    from sqlalchemy import select

    from grader.store.lti_models import LtiContext, LtiPlatform
    from grader.store.models import Course

    database = _database()
    try:
        with database.write() as session:
            course = session.scalar(select(Course).where(Course.code == course_code))
            if session.get(LtiPlatform, platform_id) is None or course is None:
                raise click.UsageError("unknown platform number or course code")
            context = session.scalar(select(LtiContext).where(LtiContext.platform_id == platform_id,
                                                              LtiContext.context_id == context_id[:255]))
            if context is None:
                session.add(LtiContext(platform_id=platform_id, context_id=context_id[:255], title=course.title,
                                       course_id=course.id))
            else:
                context.course_id = course.id
    finally:
        database.dispose()
    click.echo(f"LMS course {context_id!r} of platform {platform_id} launches into {course_code}")


@lti.command("list")
def list_platforms() -> None:
    """The registered platforms and their deployments."""
    from sqlalchemy import select

    from grader.store.lti_models import LtiPlatform

    database = _database()
    try:
        with database.read() as session:
            for platform in session.scalars(select(LtiPlatform).order_by(LtiPlatform.id)):
                deployments = ", ".join(d.deployment_id for d in platform.deployments)
                click.echo(f"{platform.id}\t{platform.name}\t{platform.issuer}\t{platform.client_id}\t{deployments}")
    finally:
        database.dispose()
