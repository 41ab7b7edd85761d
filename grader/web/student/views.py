"""Student routes.

``GET  /problems``                       the problems this student may do
``GET  /problems/<slug>``                statement, one input per answer, latest verdicts, history
``POST /problems/<slug>/preview``        the same page with a preview of each typed answer (no JavaScript)
``POST /problems/<slug>/submit``         queue every non-empty answer for grading
``POST /preview``                        JSON {problem, answer, text} -> how the text is read (live preview)
``GET  /submissions/<id>``               one attempt and its verdict
``GET  /submissions/<id>/status``        JSON status of an attempt, for polling
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from flask import abort, flash, g, jsonify, redirect, render_template, request, url_for

from grader.jobs import AnswerUnreadable, SubmissionRejected, submit
from grader.store.assignments import pending_assignment
from grader.store.db import Database, db
from grader.store.models import ProblemVersion, Submission
from grader.store.scores import practice_score
from grader.web.api.bodies import validated_body
from grader.web import clock
from grader.web.auth.session import login_required
from grader.web.errors import ApiProblem
from grader.web.security import limiter
from grader.web.student import bp
from grader.web.policy import STUDENT_ROLES, Action, current_principal, find_submission, find_version, visible_versions
from grader.web.student.attempts import history
from grader.web.student.preview import allowed_names, expected_dimension, preview
from grader.web.student.verdicts import verdict_view

STUDENTS = STUDENT_ROLES
FIELD = "answer-"  # form field of answer NAME: "answer-NAME"


def _answers(version: ProblemVersion, texts: dict[str, str], previews: dict[str, dict],
             attempts: list[Submission], refused: dict[str, str]) -> list[dict[str, Any]]:
    """One entry per answer of the version: what the student sees about it (never the reference)."""
    latest: dict[str, Submission] = {}
    for submission in attempts:  # newest first
        latest.setdefault(submission.answer_name, submission)
    answers = []
    for reference in version.references:
        name = reference["name"]
        last = latest.get(name)
        answers.append({
            "name": name, "prompt": reference.get("prompt") or name, "kind": reference.get("kind", "expression"),
            "dimension": expected_dimension(reference), "unit": reference.get("unit", ""),
            # A numeric answer is a number with its unit: no names to use.
            "names": allowed_names(reference) if reference.get("kind") != "numeric" else [],
            "text": texts.get(name, last.text if last is not None else ""),
            "preview": previews.get(name), "refused": refused.get(name),
            "latest": verdict_view(last) if last is not None else None,
        })
    return answers


def _problem_page(version: ProblemVersion, texts: dict[str, str] | None = None,
                  previews: dict[str, dict] | None = None, status: int = 200, refused: dict[str, str] | None = None):
    attempts = history(db.session, g.user, version.problem)
    answers = _answers(version, texts or {}, previews or {}, attempts, refused or {})
    pending = any(a["latest"] and a["latest"]["pending"] for a in answers)
    return render_template("student/problem.html", version=version, answers=answers, pending=pending,
                           numbers=_numbers(version),
                           attempts=[dict(verdict_view(s), received_at=s.received_at) for s in attempts]), status


def _numbers(version: ProblemVersion) -> dict[str, str]:
    """The numbers a numeric or randomised problem is checked with outside an assignment (the fixed
    values and the preview draw, `grader.answers.randomised`, as the grader uses them), with their SI
    units: ``{"g": "9.81 m/s²"}``; none for other problems."""
    from grader.answers.randomised import PREVIEW_SEED, draw_parameters, is_randomised
    from grader.expressions import parse_dimension

    specs = (version.derivation or {}).get("parameters") or {}
    if not (is_randomised(specs) or any(r.get("kind") == "numeric" for r in version.references)):
        return {}
    shown = {}
    for name, value in draw_parameters(specs, PREVIEW_SEED).items():
        try:
            dimension = parse_dimension(specs[name].get("dimension") or "dimensionless")
        except ValueError:
            dimension = None
        unit = "" if dimension is None or dimension.is_dimensionless else f" {dimension.unit()}"
        shown[name] = f"{value:g}{unit}"
    return shown


def _typed(version: ProblemVersion) -> dict[str, str]:
    return {r["name"]: request.form.get(FIELD + r["name"], "") for r in version.references}


@bp.get("/problems")
@login_required(STUDENTS)
def problems():
    versions = visible_versions(db.session, current_principal())
    progress = {}
    for version in versions:
        latest: dict[str, Submission] = {}
        for submission in history(db.session, g.user, version.problem):
            latest.setdefault(submission.answer_name, submission)
        names = [r["name"] for r in version.references]
        correct = sum(1 for n in names if n in latest and latest[n].verdict is not None
                      and latest[n].status == "done" and latest[n].verdict.verdict == "equivalent")
        progress[version.id] = {"answers": len(names), "correct": correct, "tried": sum(n in latest for n in names),
                                "score": practice_score(db.session, g.user.id, version).score}
    return render_template("student/problems.html", versions=versions, progress=progress)


@bp.get("/problems/<slug>")
@login_required(STUDENTS)
def problem(slug: str):
    return _problem_page(find_version(db.session, current_principal(), slug))


@bp.post("/problems/<slug>/preview")
@login_required(STUDENTS)
def preview_page(slug: str):
    version = find_version(db.session, current_principal(), slug)
    texts = _typed(version)
    previews = {r["name"]: preview(r, texts[r["name"]]) for r in version.references if texts[r["name"]].strip()}
    return _problem_page(version, texts, previews)


@dataclass
class _Outcome:
    """What became of each answer of one submit: stored, already stored, or not stored and why."""

    sent: int = 0
    again: int = 0
    unreadable: dict[str, dict] = field(default_factory=dict)  # name -> its preview, with the caret
    refused: dict[str, str] = field(default_factory=dict)      # name -> why it was not stored
    limited: bool = False                                        # refused by the rate limit


def _submit_each(version: ProblemVersion, texts: dict[str, str]) -> _Outcome:
    """Submit every answer, carrying on past a refused one (as an assignment's hand-in does)."""
    outcome, limit = _Outcome(), None
    for name, text in texts.items():
        limit = limiter.refusal("submit", g.user.id, limit)
        if limit is not None:
            outcome.refused[name], outcome.limited = limit, True
            continue
        try:
            _, created = submit(Database.current(), user=g.user, version=version, answer=name, text=text.strip())
        except AnswerUnreadable:
            # Not an attempt: shown next to its input, with the caret, as the preview shows it.
            outcome.unreadable[name] = preview(version.reference(name), text)
        except SubmissionRejected as error:
            outcome.refused[name] = str(error)
        else:
            outcome.sent += created
            outcome.again += not created
    return outcome


def _flash_outcome(outcome: _Outcome) -> None:
    if outcome.sent:
        flash(f"Submitted {outcome.sent} answer{'s' if outcome.sent != 1 else ''} for grading.", "success")
    if outcome.again:
        flash("You had already sent " + ("this answer" if outcome.again == 1 else "these answers")
              + " exactly as typed: " + ("its" if outcome.again == 1 else "their") + " verdict is shown below, and "
              "it is not counted as another attempt.", "success")
    if outcome.unreadable:
        flash("The grader cannot read " + ("an answer" if len(outcome.unreadable) == 1
                                           else f"{len(outcome.unreadable)} answers")
              + ": fix what is marked next to it and submit again. Nothing was counted as an attempt for it.",
              "error")
    if outcome.refused:
        names = ", ".join(outcome.refused)
        why = " (too many submissions in a short time)" if outcome.limited else ""
        flash(f"Not submitted{why}: {names}. Your text is kept below, with the reason next to each; "
              f"submit again once it is fixed.", "error")


@bp.post("/problems/<slug>/submit")
@login_required(STUDENTS)
def submit_answers(slug: str):
    # Reads in a short session of their own: the queue commits each submission in its own transaction.
    me = current_principal()
    with db.read() as session:
        version = find_version(session, me, slug, Action.SUBMIT)
        assignment = pending_assignment(session, g.user.id, version.problem_id, clock.now())
        if assignment is not None:  # answered there until it closes (its attempt limit holds)
            flash(f"This problem is part of {assignment.title}: hand it in there.", "error")
            return redirect(url_for("student.assignment", code=assignment.course.code, assignment=assignment.slug))
    texts = {name: text for name, text in _typed(version).items() if text.strip()}
    if not texts:
        flash("Type at least one answer before submitting.", "error")
        return _problem_page(find_version(db.session, me, slug, Action.SUBMIT), status=422)
    outcome = _submit_each(version, texts)
    _flash_outcome(outcome)
    if outcome.unreadable or outcome.refused:
        # Every typed text stays in the form; what was not stored is marked next to its input.
        return _problem_page(find_version(db.session, me, slug, Action.SUBMIT), _typed(version), outcome.unreadable,
                             status=429 if outcome.limited else 422, refused=outcome.refused)
    return redirect(url_for("student.problem", slug=slug) + "#answers")


PREVIEW_REQUEST = {"type": "object", "required": ["problem", "answer", "text"], "additionalProperties": False,
                   "properties": {"problem": {"type": "string", "maxLength": 100},
                                  "answer": {"type": "string", "maxLength": 64},
                                  # longer than the preview reads, so that it says why it stops
                                  "text": {"type": "string", "maxLength": 20_000}}}


@bp.post("/preview")
@login_required(STUDENTS)
def preview_json():
    try:  # strict JSON (no deep nesting, lone surrogates, NaN) of this shape, as the API's bodies
        body = validated_body(PREVIEW_REQUEST, {})
    except ApiProblem as refused:
        status = 400 if refused.status == 422 else refused.status  # this page's JSON says 400 for any bad shape
        return jsonify(error=f"Send JSON {{problem, answer, text}}, all strings: {refused.detail}"), status
    try:
        limiter.hit("preview", g.user.id)
    except ApiProblem as problem:
        return jsonify(error=problem.detail), 429, problem.headers
    me = current_principal()
    with db.read() as session:  # a POST, but it only reads: no write transaction for a keystroke
        version = find_version(session, me, body["problem"])
    reference = version.reference(body["answer"])
    if reference is None:
        abort(404, "This problem has no such answer.")
    result = preview(reference, body["text"])
    result["html"] = render_template("student/_preview.html", p=result, answer=body["answer"])
    return jsonify(result)


@bp.get("/submissions/<int:submission_id>")
@login_required(STUDENTS)
def submission(submission_id: int):
    found = find_submission(db.session, current_principal(), submission_id)
    view = verdict_view(found)
    return render_template("student/submission.html", submission=found, v=view,
                           prompt=(found.problem_version.reference(found.answer_name) or {}).get("prompt"))


@bp.get("/submissions/<int:submission_id>/status")
@login_required(STUDENTS)
def submission_status(submission_id: int):
    view = verdict_view(find_submission(db.session, current_principal(), submission_id))
    html = render_template("student/_verdict.html", v=view)
    return jsonify(id=view["id"], status=view["status"], pending=view["pending"], label=view["label"],
                   css=view["css"], html=html)
