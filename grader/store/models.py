"""The tables of the grading service, as typed SQLAlchemy 2 models.

One row per fact, nothing derived twice:

- ``User``: a person or a program (``student``, ``instructor``, ``admin``, ``lms``); students coming
  from an LMS carry its ``external_id``; people who sign in on the web carry a password hash.
- ``Course`` and ``Enrolment``: who takes, assists in (``ta``: grades, never publishes) or teaches what.
- ``Assignment`` and ``AssignmentProblem``: an ordered set of pinned problem versions in a course, with
  its opening, due and closing times (stored in UTC, shown in the assignment's time zone), attempt
  limit, late penalty and score policy. ``ParameterDraw``: one student's drawn parameter values for
  one problem of an assignment (randomised problems).
- ``Problem`` and ``ProblemVersion``: a problem is a scene id; every change of its scene source is a new
  version, holding the source and the references the engine derived from it (so grading never needs
  the engine again).
- ``Submission``: one answer text for one named answer of one problem version, with its status in the
  grading queue (``queued`` → ``running`` → ``done`` | ``failed``) and its current ``grading_round``.
- ``Verdict``: the result of one grading round of one submission. ``UNIQUE(submission_id,
  grading_round)`` makes "exactly one verdict in effect" a property of the schema: the verdict in
  effect is the one whose round equals the submission's round.
- ``ApiToken``: the sha256 of a bearer token's secret, never the secret itself.
- ``DerivationJob``: an uploaded scene waiting for, undergoing or done with its derivation
  (``queued`` → ``running`` → ``done`` | ``failed``), run by derivation workers off the request threads.
"""

from __future__ import annotations

from datetime import datetime, timezone
from typing import Any

from sqlalchemy import JSON, ForeignKey, Index, MetaData, String, Text, UniqueConstraint, func
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column, relationship

__all__ = [
    "ApiToken",
    "Assignment",
    "AssignmentProblem",
    "Base",
    "Course",
    "DerivationJob",
    "ENROLMENT_ROLES",
    "Enrolment",
    "ParameterDraw",
    "Problem",
    "ProblemVersion",
    "ROLES",
    "SCORE_POLICIES",
    "STATUSES",
    "Submission",
    "User",
    "Verdict",
    "utcnow",
]

ROLES = ("student", "instructor", "admin", "lms")
STATUSES = ("queued", "running", "done", "failed")
ENROLMENT_ROLES = ("student", "ta", "instructor")  # and "lms": an LMS account linked to the course
SCORE_POLICIES = ("best", "latest")

# Named constraints, so that Alembic's batch mode on SQLite can find and alter them later.
_NAMING = {
    "ix": "ix_%(column_0_label)s",
    "uq": "uq_%(table_name)s_%(column_0_N_name)s",
    "ck": "ck_%(table_name)s_%(constraint_name)s",
    "fk": "fk_%(table_name)s_%(column_0_name)s_%(referred_table_name)s",
    "pk": "pk_%(table_name)s",
}


def utcnow() -> datetime:
    """Now, in UTC, without tzinfo (SQLite stores naive datetimes; every stored time is UTC)."""
    return datetime.now(timezone.utc).replace(tzinfo=None)


class Base(DeclarativeBase):
    metadata = MetaData(naming_convention=_NAMING)
    type_annotation_map = {dict[str, Any]: JSON, list[Any]: JSON}


class User(Base):
    __tablename__ = "users"

    id: Mapped[int] = mapped_column(primary_key=True)
    role: Mapped[str] = mapped_column(String(16))
    name: Mapped[str] = mapped_column(String(200))
    email: Mapped[str | None] = mapped_column(String(320), unique=True)
    external_id: Mapped[str | None] = mapped_column(String(200), unique=True)
    password_hash: Mapped[str | None] = mapped_column(String(256))
    created_at: Mapped[datetime] = mapped_column(default=utcnow)

    tokens: Mapped[list[ApiToken]] = relationship(back_populates="user")
    enrolments: Mapped[list[Enrolment]] = relationship(back_populates="user")

    def __repr__(self) -> str:
        return f"<User {self.id} {self.role} {self.name!r}>"


class Course(Base):
    __tablename__ = "courses"

    id: Mapped[int] = mapped_column(primary_key=True)
    code: Mapped[str] = mapped_column(String(64), unique=True)
    title: Mapped[str] = mapped_column(String(200))
    created_at: Mapped[datetime] = mapped_column(default=utcnow)

    enrolments: Mapped[list[Enrolment]] = relationship(back_populates="course")
    problems: Mapped[list[Problem]] = relationship(back_populates="course")
    assignments: Mapped[list[Assignment]] = relationship(back_populates="course", order_by="Assignment.opens_at")


class Enrolment(Base):
    __tablename__ = "enrolments"
    __table_args__ = (UniqueConstraint("user_id", "course_id"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"))
    course_id: Mapped[int] = mapped_column(ForeignKey("courses.id", ondelete="CASCADE"))
    role: Mapped[str] = mapped_column(String(16), default="student")  # student | ta | instructor | lms

    user: Mapped[User] = relationship(back_populates="enrolments")
    course: Mapped[Course] = relationship(back_populates="enrolments")


class Problem(Base):
    __tablename__ = "problems"

    id: Mapped[int] = mapped_column(primary_key=True)
    slug: Mapped[str] = mapped_column(String(100), unique=True)  # the scene's `id`
    course_id: Mapped[int | None] = mapped_column(ForeignKey("courses.id", ondelete="SET NULL"))
    created_at: Mapped[datetime] = mapped_column(default=utcnow)
    # Archived: kept for the record, but seen and answered by its managers only (grader.web.policy).
    archived_at: Mapped[datetime | None]

    course: Mapped[Course | None] = relationship(back_populates="problems")
    versions: Mapped[list[ProblemVersion]] = relationship(
        back_populates="problem", order_by="ProblemVersion.number"
    )


class ProblemVersion(Base):
    __tablename__ = "problem_versions"
    __table_args__ = (UniqueConstraint("problem_id", "number"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    problem_id: Mapped[int] = mapped_column(ForeignKey("problems.id", ondelete="CASCADE"), index=True)
    number: Mapped[int]
    title: Mapped[str] = mapped_column(String(200))
    statement: Mapped[str] = mapped_column(Text)
    source: Mapped[str] = mapped_column(Text)
    source_sha256: Mapped[str] = mapped_column(String(64))
    derivation: Mapped[dict[str, Any]]  # Derivation.to_json()
    references: Mapped[list[Any]]  # [ReferenceAnswer as dict], exactly what answers.check takes
    engine_version: Mapped[str] = mapped_column(String(32))
    published: Mapped[bool] = mapped_column(default=True)
    created_at: Mapped[datetime] = mapped_column(default=utcnow)

    problem: Mapped[Problem] = relationship(back_populates="versions")

    def reference(self, answer: str) -> dict[str, Any] | None:
        """The stored reference answer called ``answer``, or None."""
        return next((r for r in self.references if r["name"] == answer), None)


class Submission(Base):
    __tablename__ = "submissions"
    __table_args__ = (
        UniqueConstraint("requester_id", "idempotency_key"),
        Index("ix_submissions_status_id", "status", "id"),
    )

    id: Mapped[int] = mapped_column(primary_key=True)
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id"), index=True)  # whose work
    requester_id: Mapped[int] = mapped_column(ForeignKey("users.id"))  # who sent it (student or LMS)
    problem_version_id: Mapped[int] = mapped_column(ForeignKey("problem_versions.id"), index=True)
    # The version whose references the current round grades against (a regrade moves it forward).
    grading_version_id: Mapped[int] = mapped_column(ForeignKey("problem_versions.id"))
    answer_name: Mapped[str] = mapped_column(String(64))
    text: Mapped[str] = mapped_column(Text)
    received_at: Mapped[datetime] = mapped_column(default=utcnow)
    status: Mapped[str] = mapped_column(String(16), default="queued")
    grading_round: Mapped[int] = mapped_column(default=1)
    attempts: Mapped[int] = mapped_column(default=0)  # claims so far in this round
    worker_id: Mapped[str | None] = mapped_column(String(64))
    lease_until: Mapped[datetime | None]
    idempotency_key: Mapped[str | None] = mapped_column(String(200))
    request_sha256: Mapped[str | None] = mapped_column(String(64))
    # The assignment it was handed in for (its deadlines, attempt limit and score policy apply); None:
    # practice outside any assignment.
    assignment_id: Mapped[int | None] = mapped_column(ForeignKey("assignments.id", ondelete="SET NULL"), index=True)
    updated_at: Mapped[datetime] = mapped_column(default=utcnow, server_default=func.current_timestamp())

    user: Mapped[User] = relationship(foreign_keys=[user_id])
    requester: Mapped[User] = relationship(foreign_keys=[requester_id])
    problem_version: Mapped[ProblemVersion] = relationship(foreign_keys=[problem_version_id])
    grading_version: Mapped[ProblemVersion] = relationship(foreign_keys=[grading_version_id])
    assignment: Mapped[Assignment | None] = relationship()
    verdicts: Mapped[list[Verdict]] = relationship(back_populates="submission", order_by="Verdict.grading_round")

    @property
    def verdict(self) -> Verdict | None:
        """The verdict in effect: the one of the current grading round, if graded."""
        return next((v for v in self.verdicts if v.grading_round == self.grading_round), None)


class Verdict(Base):
    __tablename__ = "verdicts"
    __table_args__ = (UniqueConstraint("submission_id", "grading_round"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    submission_id: Mapped[int] = mapped_column(ForeignKey("submissions.id", ondelete="CASCADE"))
    grading_round: Mapped[int]
    problem_version_id: Mapped[int] = mapped_column(ForeignKey("problem_versions.id"))
    verdict: Mapped[str] = mapped_column(String(32))
    certainty: Mapped[str | None] = mapped_column(String(32))
    score: Mapped[float]
    reason: Mapped[str | None] = mapped_column(Text)
    feedback: Mapped[list[Any] | None]
    counterexample: Mapped[dict[str, Any] | None]
    parsed: Mapped[dict[str, Any] | None]
    check_ms: Mapped[float | None]  # time inside the checker, as it reports
    wait_ms: Mapped[float | None]  # from receipt to the start of this grading
    grade_ms: Mapped[float | None]  # the sandboxed check as seen by the worker
    worker_id: Mapped[str | None] = mapped_column(String(64))
    graded_at: Mapped[datetime] = mapped_column(default=utcnow)

    submission: Mapped[Submission] = relationship(back_populates="verdicts")
    problem_version: Mapped[ProblemVersion] = relationship()


class ApiToken(Base):
    __tablename__ = "api_tokens"

    id: Mapped[int] = mapped_column(primary_key=True)
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"), index=True)
    name: Mapped[str] = mapped_column(String(200))
    role: Mapped[str] = mapped_column(String(16))
    secret_sha256: Mapped[str] = mapped_column(String(64), unique=True)
    created_at: Mapped[datetime] = mapped_column(default=utcnow)
    last_used_at: Mapped[datetime | None]
    revoked_at: Mapped[datetime | None]

    user: Mapped[User] = relationship(back_populates="tokens")


class DerivationJob(Base):
    """One uploaded scene file and what became of it: a problem version, or the scene's error."""

    __tablename__ = "derivation_jobs"
    __table_args__ = (Index("ix_derivation_jobs_status_id", "status", "id"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    requester_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"), index=True)
    # The course a new problem joins (the upload page's choice); None: no course.
    course_id: Mapped[int | None] = mapped_column(ForeignKey("courses.id", ondelete="SET NULL"))
    filename: Mapped[str] = mapped_column(String(100))
    source: Mapped[str] = mapped_column(Text)
    source_sha256: Mapped[str] = mapped_column(String(64))
    publish: Mapped[bool] = mapped_column(default=False)  # whether the new version is published at once
    status: Mapped[str] = mapped_column(String(16), default="queued")
    error: Mapped[str | None] = mapped_column(Text)  # failed: the scene's error, for the instructor
    problem_version_id: Mapped[int | None] = mapped_column(ForeignKey("problem_versions.id", ondelete="SET NULL"))
    new_version: Mapped[bool | None]  # done: False when the source equalled the newest version's
    attempts: Mapped[int] = mapped_column(default=0)
    worker_id: Mapped[str | None] = mapped_column(String(64))
    lease_until: Mapped[datetime | None]
    created_at: Mapped[datetime] = mapped_column(default=utcnow)
    started_at: Mapped[datetime | None]
    finished_at: Mapped[datetime | None]
    updated_at: Mapped[datetime] = mapped_column(default=utcnow, server_default=func.current_timestamp())

    requester: Mapped[User] = relationship()
    course: Mapped[Course | None] = relationship()
    problem_version: Mapped[ProblemVersion | None] = relationship()


class Assignment(Base):
    """Problems set in a course with deadlines. Times are naive UTC; ``time_zone`` (an IANA name) is
    how pages show them. No ``closes_at``: nothing is accepted after ``due_at``."""

    __tablename__ = "assignments"
    __table_args__ = (UniqueConstraint("course_id", "slug"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    course_id: Mapped[int] = mapped_column(ForeignKey("courses.id", ondelete="CASCADE"), index=True)
    slug: Mapped[str] = mapped_column(String(64))  # the assignment's id within its course
    title: Mapped[str] = mapped_column(String(200))
    opens_at: Mapped[datetime]
    due_at: Mapped[datetime]
    closes_at: Mapped[datetime | None]  # the hard close of late submissions
    time_zone: Mapped[str] = mapped_column(String(64), default="UTC")
    max_attempts: Mapped[int | None]  # per answer; None: unlimited
    late_penalty_per_day: Mapped[float] = mapped_column(default=0.0)  # fraction of the score per started day
    score_policy: Mapped[str] = mapped_column(String(16), default="best")  # best | latest
    solutions_released: Mapped[bool] = mapped_column(default=False)  # before the close, by the instructor
    created_at: Mapped[datetime] = mapped_column(default=utcnow)

    course: Mapped[Course] = relationship(back_populates="assignments")
    problems: Mapped[list[AssignmentProblem]] = relationship(
        back_populates="assignment", order_by="AssignmentProblem.position", cascade="all, delete-orphan")


class AssignmentProblem(Base):
    """One problem of an assignment, in its place, pinned to the version students answer."""

    __tablename__ = "assignment_problems"
    __table_args__ = (UniqueConstraint("assignment_id", "position"), UniqueConstraint("assignment_id", "problem_id"))

    id: Mapped[int] = mapped_column(primary_key=True)
    assignment_id: Mapped[int] = mapped_column(ForeignKey("assignments.id", ondelete="CASCADE"), index=True)
    position: Mapped[int]
    problem_id: Mapped[int] = mapped_column(ForeignKey("problems.id", ondelete="CASCADE"))
    problem_version_id: Mapped[int] = mapped_column(ForeignKey("problem_versions.id"))

    assignment: Mapped[Assignment] = relationship(back_populates="problems")
    problem: Mapped[Problem] = relationship()
    problem_version: Mapped[ProblemVersion] = relationship()


class ParameterDraw(Base):
    """The parameter values one student got for one problem of an assignment (randomised problems):
    drawn once from ``seed``, kept so that every page, check and solution uses the same numbers."""

    __tablename__ = "parameter_draws"
    __table_args__ = (UniqueConstraint("assignment_id", "user_id", "problem_id"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    assignment_id: Mapped[int] = mapped_column(ForeignKey("assignments.id", ondelete="CASCADE"), index=True)
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"))
    problem_id: Mapped[int] = mapped_column(ForeignKey("problems.id", ondelete="CASCADE"))
    seed: Mapped[int]
    values: Mapped[dict[str, Any]]  # {parameter name: value as text or number}
    created_at: Mapped[datetime] = mapped_column(default=utcnow)
