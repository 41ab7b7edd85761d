"""The Flask app factory: configuration, database, security, the API and the HTML blueprints."""

from __future__ import annotations

import importlib
import importlib.util
import logging
import os
import secrets
from pathlib import Path

from flask import Flask

from grader.jobs.derivation import DERIVE_MEMORY_MB, DERIVE_TIMEOUT_S
from grader.jobs.derivation_queue import MAX_ACTIVE_PER_REQUESTER
from grader.jobs.grading import CHECK_BUDGET_S, CheckerPool, sandbox_checker
from grader.store.db import db, default_url
from grader.web import errors, headers, security
from grader.web.converters import IdConverter
from grader.web import text_input

__all__ = ["create_app"]

# The page blueprints, each a package exposing ``bp``; registered when present.
PAGE_BLUEPRINTS = ("auth", "student", "instructor", "lti")


def create_app(test_config: dict | None = None) -> Flask:
    """Make the app. Settings: ``test_config``, else ``LAGRADE_*`` environment variables
    (``LAGRADE_HTTPS=true``...), else the defaults below; ``DATABASE_URL`` as usual."""
    app = Flask(__name__, instance_path=str(Path.cwd() / "instance"))
    app.url_map.converters["int"] = IdConverter  # ids in URLs stay within the database's integers
    app.config.from_mapping(
        DATABASE_URL=None,
        SESSION_COOKIE_HTTPONLY=True,
        SESSION_COOKIE_SAMESITE="Lax",
        SESSION_COOKIE_SECURE=False,  # made true by HTTPS
        HTTPS=False,  # served over HTTPS (LAGRADE_HTTPS=true): HSTS and Secure cookies; see headers.py
        MAX_CONTENT_LENGTH=1024 * 1024,
        CSRF_ENABLED=True,
        RATE_LIMITS_ENABLED=True,
        # Token buckets, (per minute, burst): per user, except failed sign-ins: per (account, address)
        # and, looser, per address (a campus NAT is one address; see auth/throttle.py).
        RATE_LIMITS={"check": (120, 30), "submit": (60, 20), "preview": (240, 40), "login": (10, 5),
                     "login_address": (120, 60)},
        CHECK_SANDBOXES=2,  # sandbox children serving POST /check
        CHECK_BUDGET_S=CHECK_BUDGET_S,
        CHECK_QUEUE_TIMEOUT_S=30.0,
        DERIVE_TIMEOUT_S=DERIVE_TIMEOUT_S,  # one scene's derivation, in a derivation worker's child
        DERIVE_MEMORY_MB=DERIVE_MEMORY_MB,
        DERIVE_WORKERS=1,  # scenes derived at once (``grader serve``), apart from checks and requests
        DERIVE_MAX_ACTIVE=MAX_ACTIVE_PER_REQUESTER,  # an instructor's derivations queued or running at once
        CHECKER_FACTORY=sandbox_checker,
    )
    app.config.from_prefixed_env("LAGRADE")
    if test_config:
        app.config.from_mapping(test_config)
    app.config["DATABASE_URL"] = app.config["DATABASE_URL"] or default_url()
    if not app.config.get("SECRET_KEY"):
        app.config["SECRET_KEY"] = _instance_secret(Path(app.instance_path))
    app.logger.setLevel(logging.INFO)

    db.init_app(app)
    errors.init_app(app)
    security.init_app(app)
    text_input.init_app(app)
    headers.init_app(app)
    app.extensions["lagrade.checkers"] = CheckerPool(app.config["CHECK_SANDBOXES"], app.config["CHECKER_FACTORY"])

    from grader.web.api import bp as api_bp

    app.register_blueprint(api_bp)
    for name in PAGE_BLUEPRINTS:
        if importlib.util.find_spec(f"grader.web.{name}") is not None:
            blueprint = getattr(importlib.import_module(f"grader.web.{name}"), "bp", None)
            if blueprint is not None:
                app.register_blueprint(blueprint)
    return app


def _instance_secret(instance: Path) -> str:
    """The session-signing key kept in ``instance/secret_key``, made on first start."""
    path = instance / "secret_key"
    if path.exists():
        return path.read_text().strip()
    instance.mkdir(parents=True, exist_ok=True)
    key = secrets.token_hex(32)
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    with os.fdopen(fd, "w") as f:
        f.write(key)
    return key
