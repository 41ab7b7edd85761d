"""The REST API under ``/api/v1``: JSON in and out, bearer tokens, problem+json errors."""

from flask import Blueprint

import grader
from grader.web.api.spec import ApiSpec

bp = Blueprint("api", __name__, url_prefix="/api/v1")
spec = ApiSpec(bp, title="lagrade API", version=grader.__version__,
               description="Check answers to Lagrangian-mechanics problems, submit them for grading, "
                           "manage problems and read grades.")

# They register routes on bp.
from grader.web.api import (check, courses, derivations, docs, grades, problems, submissions,  # noqa: E402,F401
                            versions)
