"""Results of one problem: every submission with the verdict in effect, scores, and CSV rows.

One query reads everything (a course of 300 makes a few thousand rows); the rest is arithmetic.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from dataclasses import dataclass
from datetime import datetime
from typing import Any, Iterator

from sqlalchemy import and_, select
from sqlalchemy.orm import Session

from grader.store.models import Problem, ProblemVersion, Submission, User, Verdict

__all__ = ["CSV_HEADER", "Row", "csv_rows", "results", "score_distribution", "signature"]

CSV_HEADER = ["submission", "student", "email", "external_id", "answer", "text", "received_at", "status",
              "verdict", "score", "grading_round", "problem_version"]


@dataclass(frozen=True)
class Row:
    submission: int
    user_id: int
    student: str
    email: str | None
    external_id: str | None
    answer: str
    text: str
    received_at: datetime
    status: str
    verdict: str | None
    score: float | None
    grading_round: int
    version: int
    verdict_id: int | None


def results(session: Session, problem: Problem, in_view=None) -> list[Row]:
    """Every submission to any version of ``problem`` with the verdict in effect, oldest first
    (``in_view``: of the students `grader.web.policy.students_in_view` lets the caller see)."""
    in_effect = and_(Verdict.submission_id == Submission.id, Verdict.grading_round == Submission.grading_round)
    query = (select(Submission.id, Submission.user_id, User.name, User.email, User.external_id,
                    Submission.answer_name, Submission.text, Submission.received_at, Submission.status,
                    Verdict.verdict, Verdict.score, Submission.grading_round, ProblemVersion.number, Verdict.id)
             .join(User, User.id == Submission.user_id)
             .join(ProblemVersion, ProblemVersion.id == Submission.problem_version_id)
             .outerjoin(Verdict, in_effect)
             .where(ProblemVersion.problem_id == problem.id)
             .order_by(Submission.id))
    if in_view is not None:
        query = query.where(in_view(Submission.user_id, Submission.assignment_id))
    return [Row(*row) for row in session.execute(query)]


def signature(rows: list[Row]) -> tuple:
    """Changes whenever a verdict in effect changes: the key for cached groupings."""
    return (len(rows), max((r.verdict_id or 0 for r in rows), default=0),
            sum(1 for r in rows if r.verdict is None))


def score_distribution(rows: list[Row], answers: list[str]) -> dict[str, Any]:
    """Students by how many answers they got right (any attempt in effect counts), 0..len(answers)."""
    solved: dict[int, set[str]] = defaultdict(set)
    for row in rows:
        solved.setdefault(row.user_id, set())
        if row.verdict == "equivalent" and row.answer in answers:
            solved[row.user_id].add(row.answer)
    counts = Counter(len(names) for names in solved.values())
    total = len(solved)
    buckets = [{"correct": k, "students": counts.get(k, 0),
                "share": counts.get(k, 0) / total if total else 0.0} for k in range(len(answers) + 1)]
    mean = sum(k * counts[k] for k in counts) / (total * len(answers)) if total and answers else 0.0
    return {"students": total, "answers": len(answers), "buckets": buckets, "mean": mean}


def per_answer(rows: list[Row], answers: list[str]) -> list[dict[str, Any]]:
    """For each answer: submissions, students who tried, students with a correct attempt, pending."""
    summary = []
    for name in answers:
        mine = [r for r in rows if r.answer == name]
        summary.append({"name": name, "submissions": len(mine), "students": len({r.user_id for r in mine}),
                        "correct": len({r.user_id for r in mine if r.verdict == "equivalent"}),
                        "wrong": sum(1 for r in mine if r.verdict == "not_equivalent"),
                        "pending": sum(1 for r in mine if r.status in ("queued", "running"))})
    return summary


def csv_rows(rows: list[Row]) -> Iterator[list[Any]]:
    """The export's rows, under ``CSV_HEADER``; :mod:`grader.web.csv_export` makes every cell safe to open."""
    for r in rows:
        yield [r.submission, r.student, r.email or "", r.external_id or "", r.answer,
               r.text, r.received_at.isoformat() + "Z", r.status, r.verdict or "",
               "" if r.score is None else r.score, r.grading_round, r.version]
