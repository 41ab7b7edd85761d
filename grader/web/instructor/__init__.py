"""The instructor dashboard: register problems from scene files, review and publish, follow results."""

from flask import Blueprint

bp = Blueprint("instructor", __name__, url_prefix="/instructor")

from grader.web.instructor import courses, docs, versions, views  # noqa: E402,F401  (they register on bp)
