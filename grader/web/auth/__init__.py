"""Signing in and out of the web pages with a session cookie, and who the signed-in user is."""

from flask import Blueprint

bp = Blueprint("auth", __name__)

from grader.web.auth import account, session, views  # noqa: E402,F401  (they register on bp)
