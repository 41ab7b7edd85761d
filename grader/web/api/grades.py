"""Grades of a problem (JSON or CSV) and regrading, for instructors."""

from __future__ import annotations

from typing import Any

from flask import request, url_for
from sqlalchemy import select
from sqlalchemy.orm import joinedload, selectinload

from grader import jobs
from grader.store.db import db
from grader.store.models import ProblemVersion, Submission
from grader.store.scores import practice_scores
from grader.web.api import spec
from grader.web.api.problems import INSTRUCTORS, visible_version
from grader.web.csv_export import csv_response
from grader.web.errors import ApiProblem
from grader.web.policy import Action, current_principal, students_in_view
from grader.web.problem_life import regrade_version

CSV_COLUMNS = ["user_id", "external_id", "name", "answer", "submissions", "latest_submission", "latest_status",
               "latest_verdict", "latest_score", "best_score", "score", "problem_score"]

_COLUMN_TYPES = {"user_id": "integer", "external_id": "string", "name": "string", "answer": "string",
                 "submissions": "integer", "latest_submission": "integer", "latest_status": "string",
                 "latest_verdict": "string", "latest_score": "number", "best_score": "number",
                 "score": "number", "problem_score": "number"}
GRADES = spec.schema("Grades", {"type": "object", "properties": {
    "problem": {"type": "string"},
    "grades": {"type": "array", "items": {"type": "object", "properties": {
        name: {"type": _COLUMN_TYPES[name], "nullable": True} for name in CSV_COLUMNS}}}}})


def grade_rows(slug: str, action: Action = Action.READ_GRADES) -> list[dict[str, Any]]:
    """One row per (student, answer): submission count, the latest one's verdict, the best score,
    if the access policy lets the caller ``action`` (read or export) the problem's grades."""
    version = visible_version(slug, action=action)
    query = (select(Submission)
             .join(ProblemVersion, Submission.problem_version_id == ProblemVersion.id)
             .where(ProblemVersion.problem_id == version.problem_id)
             .options(joinedload(Submission.user), selectinload(Submission.verdicts))
             .order_by(Submission.user_id, Submission.answer_name, Submission.id))
    in_view = students_in_view(current_principal(), version.problem.course_id)
    if in_view is not None:  # a shared problem: the caller's students only (see the policy)
        query = query.where(in_view(Submission.user_id, Submission.assignment_id))
    submissions = db.session.scalars(query)
    rows: dict[tuple[int, str], dict[str, Any]] = {}
    for submission in submissions:
        verdict = submission.verdict
        row = rows.setdefault((submission.user_id, submission.answer_name), {
            "user_id": submission.user_id, "external_id": submission.user.external_id,
            "name": submission.user.name, "answer": submission.answer_name, "submissions": 0, "best_score": None})
        row["submissions"] += 1
        row.update(latest_submission=submission.id, latest_status=submission.status,
                   latest_verdict=verdict.verdict if verdict else None, latest_score=verdict.score if verdict else None)
        if verdict is not None:
            row["best_score"] = max(row["best_score"] or 0.0, verdict.score)
    # The scores every view shows (grader/store/scores.py): this answer's and the whole problem's,
    # over practice submissions (outside assignments; the course gradebook has those).
    scores = practice_scores(db.session, version)
    for (user_id, answer), row in rows.items():
        mine = scores.get(user_id)
        row["score"] = mine.answers[answer].score if mine is not None and answer in mine.answers else None
        row["problem_score"] = mine.score if mine is not None else None
    return list(rows.values())


@spec.route("/problems/<slug>/grades", "GET", roles=INSTRUCTORS | {"lms"}, errors=(404,),
            parameters=[{"name": "format", "in": "query", "schema": {"type": "string", "enum": ["json", "csv"]},
                         "description": "csv for a spreadsheet (or send 'Accept: text/csv')."}],
            responses={200: ("One row per student and answer.", {
                "application/json": GRADES,
                "text/csv": {"type": "string", "description": f"Columns: {', '.join(CSV_COLUMNS)}."}})})
def get_grades(slug: str):
    """Grades of every student on every answer of a problem, as JSON or CSV.

    An LMS reads the JSON grades of problems in its own courses (not the CSV export).
    """
    wants_csv = request.args.get("format") == "csv" or (
        request.accept_mimetypes.best_match(["application/json", "text/csv"]) == "text/csv"
        and request.accept_mimetypes["text/csv"] > request.accept_mimetypes["application/json"])
    rows = grade_rows(slug, Action.EXPORT if wants_csv else Action.READ_GRADES)
    if wants_csv:
        return csv_response(rows, f"{slug}-grades.csv", header=CSV_COLUMNS)
    return {"problem": slug, "grades": rows}


@spec.route("/problems/<slug>/regrade", "POST", roles=INSTRUCTORS, errors=(404, 409),
            responses={202: ("Every submission of the problem is queued for a new grading round.", {
                "application/json": {"type": "object", "properties": {
                    "queued": {"type": "integer"}, "version": {"type": "integer"}, "links": {"type": "object"}}}})})
def regrade(slug: str):
    """Grade every submission of a problem again, against its newest published version's references
    (never a draft's; ``409`` when no version is published), as the instructor page does.

    Each submission gets a new grading round; its earlier verdicts stay stored but only the new
    one is in effect.
    """
    with db.read() as session:
        version = regrade_version(session, visible_version(slug, session, Action.REGRADE).problem)
        if version is None:
            raise ApiProblem(409, f"Problem {slug!r} has no published version: publish one before regrading.",
                             kind="conflict")
    queued = jobs.regrade(db, version)
    return {"queued": queued, "version": version.number,
            "links": {"grades": url_for("api.get_grades", slug=slug)}}, 202
