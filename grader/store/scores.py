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
from typing import Iterable

from sqlalchemy import select
from sqlalchemy.orm import Session, joinedload, selectinload

from grader.store.assignments import late_days, late_factor
from grader.store.models import Assignment, Enrolment, ProblemVersion, Submission, User

__all__ = ["AnswerScore", "ProblemScore", "StudentRow", "answer_weight", "gradebook", "problem_score",
           "practice_score", "practice_scores", "DIGITS"]

DIGITS = 4


def answer_weight(reference: dict) -> float:
    """An answer's weight in its problem's score (the reference's ``weight``, default 1)."""
    weight = reference.get("weight", 1.0)
    return float(weight) if isinstance(weight, (int, float)) and weight >= 0 else 1.0


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


def problem_score(version: ProblemVersion, submissions: Iterable[Submission],
                  assignment: Assignment | None = None) -> ProblemScore:
    """The score of one student's ``submissions`` (oldest first or in any order) to ``version``'s
    problem, under ``assignment``'s rules (None: practice, best attempt, never late).

    Examples
    --------
    >>> v = ProblemVersion(references=[{"name": "a"}, {"name": "b", "weight": 3}], problem=None)
    >>> problem_score(v, []).score
    0.0
    """
    policy = assignment.score_policy if assignment is not None else "best"
    answers = {r["name"]: AnswerScore(r["name"]) for r in version.references}
    weights = {r["name"]: answer_weight(r) for r in version.references}
    for submission in sorted(submissions, key=lambda s: s.id):
        answer = answers.get(submission.answer_name)
        if answer is None:  # an answer this version no longer has
            continue
        answer.attempts += 1
        verdict = submission.verdict if submission.status in ("done", "failed") else None
        if verdict is None:
            answer.pending += 1
            continue
        keeps = late_factor(assignment, submission.received_at) if assignment is not None else 1.0
        value = round(verdict.score * keeps, DIGITS)
        if policy == "latest" or answer.counted is None or value > answer.score:
            answer.score, answer.counted = value, submission.id
            answer.late_days = late_days(assignment, submission.received_at) if assignment is not None else 0
    total = sum(weights.values())
    score = sum(weights[n] * a.score for n, a in answers.items()) / total if total else 0.0
    slug = version.problem.slug if version.problem is not None else ""
    return ProblemScore(problem=slug, score=round(score, DIGITS), answers=answers)


def practice_score(session: Session, user_id: int, version: ProblemVersion) -> ProblemScore:
    """A student's score on a problem outside any assignment, against ``version``'s answers."""
    versions = select(ProblemVersion.id).where(ProblemVersion.problem_id == version.problem_id)
    submissions = session.scalars(select(Submission).options(selectinload(Submission.verdicts))
                                  .where(Submission.user_id == user_id, Submission.assignment_id.is_(None),
                                         Submission.problem_version_id.in_(versions)))
    return problem_score(version, submissions)


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
    query = (select(Submission).options(selectinload(Submission.verdicts), joinedload(Submission.problem_version))
             .where(Submission.assignment_id == assignment.id))
    if user_id is not None:
        query = query.where(Submission.user_id == user_id)
    mine: dict[tuple[int, int], list[Submission]] = {}
    for submission in session.scalars(query):
        mine.setdefault((submission.user_id, submission.problem_version.problem_id), []).append(submission)
    return [StudentRow(user, [problem_score(item.problem_version, mine.get((user.id, item.problem_id), []),
                                            assignment) for item in assignment.problems])
            for user in users]


def practice_scores(session: Session, version: ProblemVersion) -> dict[int, ProblemScore]:
    """Every student's practice score on ``version``'s problem (submissions outside assignments),
    by user id: what the problem's results page, its grades API and its CSV show."""
    versions = select(ProblemVersion.id).where(ProblemVersion.problem_id == version.problem_id)
    mine: dict[int, list[Submission]] = {}
    for submission in session.scalars(select(Submission).options(selectinload(Submission.verdicts))
                                      .where(Submission.assignment_id.is_(None),
                                             Submission.problem_version_id.in_(versions))):
        mine.setdefault(submission.user_id, []).append(submission)
    return {user_id: problem_score(version, submissions) for user_id, submissions in mine.items()}
