"""The student pages: problems, a problem with live previews of each answer, verdicts and history."""

from flask import Blueprint

bp = Blueprint("student", __name__)

from grader.web.student import courses, filters, views  # noqa: E402,F401  (they register on bp)
