"""Engines and short sessions.

SQLite is the default (``instance/lagrade.sqlite`` relative to the working directory); any
SQLAlchemy URL works through ``DATABASE_URL``. On SQLite every connection runs in WAL mode with a
busy timeout and foreign keys on, and write transactions start with ``BEGIN IMMEDIATE`` (the pysqlite
event recipe), so two writers queue on the busy timeout instead of failing on a lock upgrade.

In a request, use the extension created once here::

    from grader.store.db import db
    user = db.session.get(User, 1)           # one session per request, closed at teardown
    db.session.commit()

Outside a request (the grading workers, the CLI), open a short session and close it before any
slow work::

    with db.write() as session:              # BEGIN IMMEDIATE ... COMMIT (or ROLLBACK on error)
        session.add(thing)
"""

from __future__ import annotations

import os
import threading
from contextlib import contextmanager, nullcontext
from pathlib import Path
from typing import Iterator

from sqlalchemy import Engine, create_engine, event
from sqlalchemy.orm import Session, sessionmaker

__all__ = ["Database", "db", "default_url", "make_engine"]

DEFAULT_SQLITE = "instance/lagrade.sqlite"
BUSY_TIMEOUT_MS = 30_000


def default_url() -> str:
    """``DATABASE_URL`` if set, else the SQLite file ``instance/lagrade.sqlite`` under the cwd."""
    url = os.environ.get("DATABASE_URL")
    if url:
        return url
    path = Path.cwd() / DEFAULT_SQLITE
    path.parent.mkdir(parents=True, exist_ok=True)
    return f"sqlite:///{path}"


def make_engine(url: str, **kwargs) -> Engine:
    """An engine for ``url``; on SQLite configured for many threads writing through one file."""
    if not url.startswith("sqlite"):
        return create_engine(url, pool_pre_ping=True, **kwargs)
    kwargs.setdefault("pool_size", 20)
    kwargs.setdefault("max_overflow", 20)
    engine = create_engine(url, connect_args={"timeout": BUSY_TIMEOUT_MS / 1000}, **kwargs)

    @event.listens_for(engine, "connect")
    def _on_connect(dbapi_connection, _record):
        # Let SQLAlchemy emit BEGIN itself (below), instead of pysqlite's implicit one.
        dbapi_connection.isolation_level = None
        cursor = dbapi_connection.cursor()
        cursor.execute("PRAGMA journal_mode=WAL")
        cursor.execute(f"PRAGMA busy_timeout={BUSY_TIMEOUT_MS}")
        cursor.execute("PRAGMA foreign_keys=ON")
        cursor.execute("PRAGMA synchronous=NORMAL")
        cursor.close()

    @event.listens_for(engine, "begin")
    def _on_begin(connection):
        immediate = connection.get_execution_options().get("sqlite_immediate", False)
        connection.exec_driver_sql("BEGIN IMMEDIATE" if immediate else "BEGIN")

    return engine


class Database:
    """The engine and session factories of one app (a Flask extension, created once below).

    ``reader`` sessions begin a deferred transaction; ``writer`` sessions begin ``BEGIN IMMEDIATE``
    on SQLite (elsewhere both are the same).
    """

    def __init__(self, url: str | None = None):
        self.engine: Engine | None = None
        self.reader: sessionmaker[Session] | None = None
        self.writer: sessionmaker[Session] | None = None
        self.write_lock: threading.Lock | None = None
        if url:
            self.configure(url)

    def configure(self, url: str, **engine_kwargs) -> Database:
        if self.engine is not None:
            self.engine.dispose()
        self.engine = make_engine(url, **engine_kwargs)
        immediate = self.engine.execution_options(sqlite_immediate=True)
        self.reader = sessionmaker(self.engine, expire_on_commit=False)
        self.writer = sessionmaker(immediate, expire_on_commit=False)
        # SQLite has one writer at a time; threads of this process queue for it here, in order,
        # instead of in SQLite's busy handler, which sleeps in growing steps (up to 100 ms).
        self.write_lock = threading.Lock() if url.startswith("sqlite") else None
        return self

    def init_app(self, app) -> None:
        """Bind to a Flask app: its own engine from ``DATABASE_URL``, a session per request."""
        from flask import g

        app.extensions["lagrade.db"] = Database(app.config["DATABASE_URL"])

        @app.teardown_appcontext
        def _close_session(_exc):
            session = g.pop("db_session", None)
            if session is not None:
                session.close()

    @staticmethod
    def current() -> Database:
        """The Database bound to the current Flask app."""
        from flask import current_app

        return current_app.extensions["lagrade.db"]

    @property
    def session(self) -> Session:
        """The session of the current request: a writer for unsafe methods, a reader for GET/HEAD."""
        from flask import g, request

        session = g.get("db_session")
        if session is None:
            bound = self if self.engine is not None else self.current()
            unsafe = request.method not in ("GET", "HEAD", "OPTIONS")
            session = g.db_session = (bound.writer if unsafe else bound.reader)()
        return session

    @contextmanager
    def read(self) -> Iterator[Session]:
        """A short read-only session."""
        bound = self if self.engine is not None else self.current()
        with bound.reader() as session:
            yield session

    @contextmanager
    def write(self) -> Iterator[Session]:
        """A short write transaction: committed on success, rolled back on error, always closed."""
        bound = self if self.engine is not None else self.current()
        with bound.write_lock or nullcontext(), bound.writer() as session, session.begin():
            yield session

    def dispose(self) -> None:
        if self.engine is not None:
            self.engine.dispose()


# The extension: bound to each app by ``db.init_app(app)``; ``db.session`` in requests.
db = Database()
