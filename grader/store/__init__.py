"""Storage: typed SQLAlchemy 2 models, short sessions, Alembic migrations (``migrations/``)."""

from grader.store.db import Database, db, default_url, make_engine
from grader.store.models import (
    ApiToken,
    Base,
    Course,
    Enrolment,
    Problem,
    ProblemVersion,
    Submission,
    User,
    Verdict,
)
from grader.store import lti_models  # noqa: E402,F401  (the LTI tool's tables join Base.metadata)
from grader.store import lengths  # noqa: E402,F401  (every flushed row's text must fit its column)

__all__ = [
    "ApiToken",
    "Base",
    "Course",
    "Database",
    "Enrolment",
    "Problem",
    "ProblemVersion",
    "Submission",
    "User",
    "Verdict",
    "db",
    "default_url",
    "make_engine",
]
