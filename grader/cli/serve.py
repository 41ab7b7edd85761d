"""``grader serve``: migrations, problems, demo accounts, grading workers and the waitress server."""

from __future__ import annotations

import logging
import os
import secrets
import signal
import sys
from pathlib import Path

import click

PASSWORDS_FILE = "first-start-passwords.txt"


@click.command()
@click.option("--host", default="127.0.0.1", show_default=True, help="Address to listen on.")
@click.option("--port", default=8000, show_default=True, type=int, help="Port (0: any free one).")
@click.option("--workers", default=2, show_default=True, type=click.IntRange(1, 64), help="Grading workers.")
@click.option("--threads", default=16, show_default=True, type=click.IntRange(1, 256), help="HTTP threads.")
@click.option("--problems", "problems_dir", default="problems", show_default=True,
              type=click.Path(file_okay=False, path_type=Path), help="Scene files to load at start.")
@click.option("--demo/--no-demo", default=True, show_default=True,
              help="Create a demo instructor and student on first start.")
def serve(host: str, port: int, workers: int, threads: int, problems_dir: Path, demo: bool) -> None:
    """Serve the web pages and the API, and grade submissions in the background."""
    from grader.jobs.derivation import close_shared_sandboxes, load_problem_files
    from grader.store.db import Database, default_url
    from grader.store.migrate import upgrade
    from grader.web import create_app
    from grader.web.background import start_background
    from grader.web.server_refusals import create_server

    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    url = default_url()
    click.echo(f"database: revision {upgrade(url)}")
    app = create_app({"DATABASE_URL": url})
    database: Database = app.extensions["lagrade.db"]

    limits = {"timeout_s": app.config["DERIVE_TIMEOUT_S"], "memory_mb": app.config["DERIVE_MEMORY_MB"]}
    # Before the server listens, so no request waits on it; unchanged files cost a hash each.
    for name, outcome in load_problem_files(database, sorted(problems_dir.glob("*.toml")), **limits):
        click.echo(f"problem {name}: {outcome}")
    close_shared_sandboxes()  # uploads are derived by the derivation workers' own children
    if demo:
        for line in _show_once(_demo_accounts(database), Path(app.instance_path), sys.stdout.isatty()):
            click.echo(line)

    background = start_background(app, grading_workers=workers)
    # A body over the app's cap is refused by waitress from its Content-Length, before it is read:
    # a flood of oversized requests then costs the server a header each, not megabytes each. The
    # app writes that refusal (and waitress's others): a problem document under /api/, a page elsewhere.
    server = create_server(app, host=host, port=port, threads=threads, ident="lagrade",
                           max_request_body_size=app.config["MAX_CONTENT_LENGTH"] + 1)
    base = f"http://{host}:{server.effective_port}"
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    click.echo(f"sign in at {base}{_sign_in_path(app)}; API at {base}/api/v1 (see /api/v1/openapi.json)\n"
               f"lagrade is serving on {base}/ with {background.description}")
    try:
        server.run()
    except (KeyboardInterrupt, SystemExit):
        pass
    finally:
        server.close()
        background.stop()
        app.extensions["lagrade.checkers"].close()
        database.dispose()


def _demo_accounts(database) -> list[str]:
    """On a database with no web accounts, one instructor and one student, with printed passwords."""
    from sqlalchemy import select

    from grader.store.models import User
    from grader.store.users import create_user

    with database.write() as session:
        if session.scalar(select(User.id).where(User.password_hash.is_not(None)).limit(1)) is not None:
            return []
        lines = ["first start: created demo accounts (change their passwords on /account, or make your own accounts "
                 "with `grader db create-user`):"]
        for role in ("instructor", "student"):
            password = secrets.token_urlsafe(9)
            create_user(session, role=role, name=f"Demo {role}", email=f"{role}@example.org", password=password)
            lines.append(f"  {role}: {role}@example.org  password: {password}")
    return lines


def _show_once(lines: list[str], instance: Path, terminal: bool) -> list[str]:
    """What to print of the first start's demo passwords: all of it on a terminal; otherwise (stdout
    is a log file or a pipe, which outlive the passwords' usefulness) only where they were written, a
    file readable by its owner alone (mode 0600) in the instance folder."""
    if not lines or terminal:
        return lines
    instance.mkdir(parents=True, exist_ok=True)
    path = instance / PASSWORDS_FILE
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    with os.fdopen(fd, "w", encoding="utf-8") as out:
        os.fchmod(fd, 0o600)  # also when the file was there before, with wider modes
        out.write("\n".join(lines) + "\n")
    return [f"first start: created demo accounts; their passwords are in {path} (readable by you only; "
            "delete it once read, and change them with `grader db reset-password`)"]


def _sign_in_path(app) -> str:
    if "auth.login" not in app.view_functions:
        return "/"
    with app.test_request_context():
        from flask import url_for

        return url_for("auth.login")
