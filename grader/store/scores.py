"""The one place a score is computed. Every view (the student's list, the instructor's results, the
API, the CSV exports, the gradebook) asks this module, so they cannot disagree.

- An *attempt* scores its verdict's score (0 to 1) times what a late submission keeps
  (:func:`grader.store.assignments.late_factor`); attempts not yet graded do not count (yet).
- An *answer* scores, by the policy: ``best``, its best attempt; ``latest``, its latest graded one.
- A *problem* scores the weighted mean of its answers (each reference's ``weight``, default 1;
  an answer never tried scores 0).
- An *assignment* scores the sum of its problems' scores (each problem is out of 1).

Scores are rounded to 4 decimals here, once, so every surface shows the same number. Outside an
assignment (practice), the policy is ``best`` and nothing is late.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from datetime import datetime
from typing import Iterable, Union

from sqlalchemy import and_, select
from sqlalchemy.orm import Session

from grader.store.assignments import late_days, late_factor
from grader.store.models import Assignment, Enrolment, ProblemVersion, Submission, User, Verdict

__all__ = ["AnswerScore", "Attempt", "ProblemScore", "StudentRow", "answer_weight", "gradebook", "problem_score",
           "practice_score", "practice_scores", "DIGITS"]

DIGITS = 4


def answer_weight(reference: dict) -> float:
    """An answer's weight in its problem's score (the reference's ``weight``, default 1)."""
    weight = reference.get("weight", 1.0)
    return float(weight) if isinstance(weight, (int, float)) and weight >= 0 else 1.0


@dataclass(frozen=True)
class Attempt:
    """What scoring reads of one submission: ``score`` is its verdict in effect's (None: not graded)."""

    id: int
    answer: str
    status: str
    received_at: datetime
    score: float | None

    @classmethod
    def of(cls, submission: Submission) -> Attempt:
        verdict = submission.verdict
        return cls(submission.id, submission.answer_name, submission.status, submission.received_at,
                   verdict.score if verdict is not None else None)


# The columns an Attempt is read from in bulk: one row per submission, its verdict in effect joined
# (no ORM objects: a course's gradebook reads thousands of rows).
_IN_EFFECT = and_(Verdict.submission_id == Submission.id, Verdict.grading_round == Submission.grading_round)
_ATTEMPT_COLUMNS = (Submission.id, Submission.answer_name, Submission.status, Submission.received_at, Verdict.score)


def _attempts(session: Session, *where) -> Iterable[tuple[int, int, Attempt]]:
    """(user id, problem id, attempt) of every submission matching ``where``."""
    query = (select(Submission.user_id, ProblemVersion.problem_id, *_ATTEMPT_COLUMNS)
             .join(ProblemVersion, ProblemVersion.id == Submission.problem_version_id)
             .outerjoin(Verdict, _IN_EFFECT).where(*where))
    for user_id, problem_id, *columns in session.execute(query):
        yield user_id, problem_id, Attempt(*columns)


@dataclass
class AnswerScore:
    name: str
    score: float = 0.0
    attempts: int = 0
    pending: int = 0  # attempts not yet graded
    late_days: int = 0  # of the attempt that counts
    counted: int | None = None  # the id of the submission that counts


@dataclass
class ProblemScore:
    problem: str  # the problem's id (slug)
    score: float = 0.0
    answers: dict[str, AnswerScore] = field(default_factory=dict)

    @property
    def attempts(self) -> int:
        return sum(a.attempts for a in self.answers.values())

    @property
    def pending(self) -> int:
        return sum(a.pending for a in self.answers.values())

    @property
    def late_days(self) -> int:
        """The most late days among the attempts that count (0: all on time)."""
        return max((a.late_days for a in self.answers.values()), default=0)


def problem_score(version: ProblemVersion, submissions: Iterable[Union[Attempt, Submission]],
                  assignment: Assignment | None = None) -> ProblemScore:
    """The score of one student's ``submissions`` (attempts or submissions, in any order) to
    ``version``'s problem, under ``assignment``'s rules (None: practice, best attempt, never late).

    Examples
    --------
    >>> v = ProblemVersion(references=[{"name": "a"}, {"name": "b", "weight": 3}], problem=None)
    >>> problem_score(v, []).score
    0.0
    """
    policy = assignment.score_policy if assignment is not None else "best"
    answers = {r["name"]: AnswerScore(r["name"]) for r in version.references}
    weights = {r["name"]: answer_weight(r) for r in version.references}
    attempts = [a if isinstance(a, Attempt) else Attempt.of(a) for a in submissions]
    for attempt in sorted(attempts, key=lambda a: a.id):
        answer = answers.get(attempt.answer)
        if answer is None:  # an answer this version no longer has
            continue
        answer.attempts += 1
        if attempt.status not in ("done", "failed") or attempt.score is None:
            answer.pending += 1
            continue
        keeps = late_factor(assignment, attempt.received_at) if assignment is not None else 1.0
        value = round(attempt.score * keeps, DIGITS)
        if policy == "latest" or answer.counted is None or value > answer.score:
            answer.score, answer.counted = value, attempt.id
            answer.late_days = late_days(assignment, attempt.received_at) if assignment is not None else 0
    total = sum(weights.values())
    score = sum(weights[n] * a.score for n, a in answers.items()) / total if total else 0.0
    slug = version.problem.slug if version.problem is not None else ""
    return ProblemScore(problem=slug, score=round(score, DIGITS), answers=answers)


def practice_score(session: Session, user_id: int, version: ProblemVersion) -> ProblemScore:
    """A student's score on a problem outside any assignment, against ``version``'s answers."""
    attempts = [a for _, _, a in _attempts(session, Submission.user_id == user_id, Submission.assignment_id.is_(None),
                                           ProblemVersion.problem_id == version.problem_id)]
    return problem_score(version, attempts)


@dataclass
class StudentRow:
    """One student's line of a gradebook: a score per problem (in the assignment's order) and the total."""

    user: User
    problems: list[ProblemScore]

    @property
    def total(self) -> float:
        return round(sum(p.score for p in self.problems), DIGITS)


def gradebook(session: Session, assignment: Assignment, user_id: int | None = None) -> list[StudentRow]:
    """Every student of the assignment's course (or only ``user_id``) × its problems, by name."""
    students = select(User).join(Enrolment, Enrolment.user_id == User.id).where(
        Enrolment.course_id == assignment.course_id, Enrolment.role == "student")
    if user_id is not None:
        students = students.where(User.id == user_id)
    users = sorted(session.scalars(students), key=lambda u: (u.name.lower(), u.id))
    where = [Submission.assignment_id == assignment.id]
    if user_id is not None:
        where.append(Submission.user_id == user_id)
    mine: dict[tuple[int, int], list[Attempt]] = {}
    for student, problem_id, attempt in _attempts(session, *where):
        mine.setdefault((student, problem_id), []).append(attempt)
    return [StudentRow(user, [problem_score(item.problem_version, mine.get((user.id, item.problem_id), []),
                                            assignment) for item in assignment.problems])
            for user in users]


def practice_scores(session: Session, version: ProblemVersion) -> dict[int, ProblemScore]:
    """Every student's practice score on ``version``'s problem (submissions outside assignments),
    by user id: what the problem's results page, its grades API and its CSV show."""
    mine: dict[int, list[Attempt]] = {}
    for user_id, _, attempt in _attempts(session, Submission.assignment_id.is_(None),
                                         ProblemVersion.problem_id == version.problem_id):
        mine.setdefault(user_id, []).append(attempt)
    return {user_id: problem_score(version, attempts) for user_id, attempts in mine.items()}
