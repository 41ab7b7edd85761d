"""The LTI 1.3 tool: launches from an LMS, deep linking, grade passback (AGS) and rosters (NRPS)."""

from flask import Blueprint

bp = Blueprint("lti", __name__, url_prefix="/lti")

from grader.web.lti import views  # noqa: E402,F401  (they register on bp)
