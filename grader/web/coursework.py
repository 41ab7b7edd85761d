"""What an assignment looks like to one person, built once for the API and the pages alike.

The times, the state (not open, open, late, closed), the attempts left, what a late submission
costs and the scores all come from :mod:`grader.store.assignments` and :mod:`grader.store.scores`;
this module only puts them into words and dictionaries, so the JSON and the HTML say the same.
"""

from __future__ import annotations

from datetime import datetime
from typing import Any

from flask import current_app
from sqlalchemy.orm import Session

from grader.answers.numeric import reference_value
from grader.answers.reference import ReferenceAnswer
from grader.store.assignments import deadline_state, late_days, late_factor, local_time, solutions_open
from grader.store.db import Database
from grader.store.draws import parameters_for
from grader.store.models import Assignment, User
from grader.store.scores import StudentRow, gradebook

__all__ = ["GRADEBOOK_COLUMNS", "assignment_view", "gradebook_rows", "rules_in_words", "stamp"]

STATE_WORDS = {"not_open": "not open yet", "open": "open", "late": "past due: late submissions accepted",
               "closed": "closed"}
_STUDENT_ANSWER_KEYS = ("name", "prompt", "kind", "dimension", "variables")


def stamp(assignment: Assignment, moment: datetime | None) -> str | None:
    """A stored time as ISO 8601 in the assignment's time zone (with its offset)."""
    local = local_time(assignment, moment)
    return local.isoformat() if local is not None else None


def _words(assignment: Assignment, moment: datetime) -> str:
    local = local_time(assignment, moment)
    return f"{local:%a %d %b %Y, %H:%M:%S} ({assignment.time_zone})"


def rules_in_words(assignment: Assignment) -> list[str]:
    """The assignment's rules, as sentences a student reads on its page."""
    rules = [f"Opens {_words(assignment, assignment.opens_at)}.", f"Due {_words(assignment, assignment.due_at)}."]
    if assignment.closes_at is not None and assignment.closes_at > assignment.due_at:
        penalty = assignment.late_penalty_per_day or 0.0
        cost = (f"each started day late costs {penalty:.0%} of the score" if penalty
                else "late submissions cost nothing")
        rules.append(f"Late submissions are accepted until {_words(assignment, assignment.closes_at)}; {cost}.")
    else:
        rules.append("Nothing is accepted after the due time.")
    rules.append(f"Each answer gets {assignment.max_attempts} attempt{'s' if assignment.max_attempts != 1 else ''}."
                 if assignment.max_attempts else "Each answer may be submitted any number of times.")
    rules.append("Your score for an answer is your best attempt." if assignment.score_policy == "best"
                 else "Your score for an answer is your latest graded attempt.")
    if assignment.late_penalty_per_day:
        rules[-1] = rules[-1][:-1] + ", after its late penalty."
    rules.append("Worked solutions appear here once the assignment closes.")
    return rules


def assignment_view(session: Session, assignment: Assignment, now: datetime, *, student: User | None) -> dict[str, Any]:
    """The assignment as ``student`` sees it at ``now`` (their attempts, scores, parameter values and,
    once allowed, the solutions); with ``student`` None, as its instructors and TAs see it."""
    state = deadline_state(assignment, now)
    solutions = solutions_open(assignment, now)
    row: StudentRow | None = None
    if student is not None:
        rows = gradebook(session, assignment, user_id=student.id)
        row = rows[0] if rows else None
    problems = []
    for index, item in enumerate(assignment.problems):
        version = item.problem_version
        score = row.problems[index] if row is not None else None
        entry: dict[str, Any] = {"id": item.problem.slug, "version": version.number, "title": version.title,
                                 "position": item.position}
        if student is None or state != "not_open":
            entry["statement"] = version.statement
            answers = []
            for reference in version.references:
                answer = {k: reference.get(k) for k in _STUDENT_ANSWER_KEYS}
                answer["weight"] = reference.get("weight", 1)
                if score is not None:
                    mine = score.answers[reference["name"]]
                    answer.update(attempts_used=mine.attempts, score=mine.score, pending=mine.pending,
                                  attempts_left=(max(0, assignment.max_attempts - mine.attempts)
                                                 if assignment.max_attempts else None))
                answers.append(answer)
            entry["answers"] = answers
        if student is not None:
            entry["parameters"] = parameters_for(Database.current(), assignment.id, student.id, item,
                                                 current_app.config["SECRET_KEY"])
            entry["score"] = score.score if score is not None else 0.0
        if solutions:
            drawn = entry.get("parameters") or None
            entry["solution"] = {"steps": version.derivation.get("steps") or [],
                                 "answers": [{"name": r["name"], "prompt": r.get("prompt"), "latex": r.get("latex"),
                                              "reference": r.get("reference"), "value": _value_at(r, drawn)}
                                             for r in version.references]}
        problems.append(entry)
    view: dict[str, Any] = {
        "id": assignment.slug, "title": assignment.title, "course": assignment.course.code,
        "time_zone": assignment.time_zone, "opens_at": stamp(assignment, assignment.opens_at),
        "due_at": stamp(assignment, assignment.due_at), "closes_at": stamp(assignment, assignment.closes_at),
        "state": state, "state_words": STATE_WORDS[state], "max_attempts": assignment.max_attempts,
        "late_penalty_per_day": assignment.late_penalty_per_day, "score_policy": assignment.score_policy,
        "solutions_released": bool(assignment.solutions_released), "solutions_available": solutions,
        "rules": rules_in_words(assignment), "problems": problems,
    }
    if state in ("open", "late"):
        view["late_now"] = {"late_days": late_days(assignment, now), "keeps": late_factor(assignment, now)}
    if row is not None:
        view["score"] = row.total
    return view


def _value_at(reference: dict[str, Any], drawn: dict[str, Any] | None) -> str | None:
    """A numeric answer's value at the student's numbers (their draw, else the problem's own), as
    the solution states it: "0.981 N". None for symbolic answers."""
    if reference.get("kind") != "numeric":
        return None
    try:
        answer = ReferenceAnswer.from_json(reference)
        value = reference_value(answer.reference, answer.variables, answer.values(drawn), answer.implicit)
    except (ValueError, ArithmeticError):  # a reference that has no number here: say nothing
        return None
    return f"{value:.4g} {answer.unit or ''}".strip()


GRADEBOOK_COLUMNS = ["course", "assignment", "user_id", "external_id", "email", "name", "problem", "score",
                     "attempts", "pending", "late_days"]


def gradebook_rows(session: Session, assignments: list[Assignment], user_id: int | None = None) -> list[dict[str, Any]]:
    """One row per (assignment, student, problem), in the gradebook's order: the rows of the CSV, the
    API's JSON and the gradebook page."""
    rows = []
    for assignment in assignments:
        for student in gradebook(session, assignment, user_id=user_id):
            for score in student.problems:
                rows.append({"course": assignment.course.code, "assignment": assignment.slug,
                             "user_id": student.user.id, "external_id": student.user.external_id,
                             "email": student.user.email, "name": student.user.name, "problem": score.problem,
                             "score": score.score, "attempts": score.attempts, "pending": score.pending,
                             "late_days": score.late_days})
    return rows
