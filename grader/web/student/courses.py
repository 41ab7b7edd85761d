"""Student course pages.

``GET  /courses``                                      the courses I am in, with their assignments
``GET  /courses/<code>/assignments/<assignment>``      what is open, due when, attempts left, the late cost,
                                                       my scores; the worked solutions once it closes
``POST /courses/<code>/assignments/<assignment>/submit``  hand in the typed answers of one problem
"""

from __future__ import annotations

from flask import abort, current_app, flash, g, redirect, render_template, request, url_for
from sqlalchemy import select

from grader.jobs.assignment_submissions import HandInRefused, hand_in
from grader.jobs.queue import SubmissionRejected
from grader.store.assignments import deadline_state
from grader.store.db import Database, db
from grader.store.models import Submission
from grader.web import clock
from grader.web.auth.session import login_required
from grader.web.coursework import STATE_WORDS, assignment_view, rules_in_words
from grader.web.student.verdicts import verdict_view
from grader.web.policy import PAGE_ROLES, Action, allowed, current_principal, find_assignment, my_courses, require
from grader.web.security import limiter
from grader.web.student import bp

FIELD = "answer-"


@bp.get("/courses")
@login_required(PAGE_ROLES)
def courses():
    principal = current_principal()
    mine, now = my_courses(db.session, principal), clock.now()
    states = {a.id: (STATE_WORDS[deadline_state(a, now)], rules_in_words(a)[1])
              for c in mine for a in c.assignments}  # ("open", "Due Tue 08 Dec 2026, ...")
    return render_template("courses/list.html", courses=mine, states=states,
                           grading={c.id for c in mine if allowed(principal, Action.GRADE_COURSE, c)})


@bp.get("/courses/<code>/assignments/<assignment>")
@login_required(PAGE_ROLES)
def assignment(code: str, assignment: str):
    return _assignment_page(code, assignment)


def _assignment_page(code: str, assignment: str, kept: dict[tuple[str, str], str] | None = None,
                     refused: dict[tuple[str, str], str] | None = None, status: int = 200):
    """The assignment page; ``kept`` texts stay in their inputs, ``refused`` ones say why next to
    them (both by (problem, answer))."""
    principal = current_principal()
    found = find_assignment(db.session, principal, code, assignment)
    grader_view = allowed(principal, Action.GRADE_COURSE, found)
    view = assignment_view(db.session, found, clock.now(), student=None if grader_view else g.user)
    latest: dict[tuple[str, str], dict] = {}  # (problem, answer) -> the student's latest attempt's verdict
    if not grader_view:
        for submission in db.session.scalars(select(Submission).where(
                Submission.assignment_id == found.id, Submission.user_id == g.user.id).order_by(Submission.id.desc())):
            latest.setdefault((submission.problem_version.problem.slug, submission.answer_name),
                              verdict_view(submission))
    return render_template("courses/assignment.html", a=view, code=code, grader_view=grader_view, latest=latest,
                           pending=any(v["pending"] for v in latest.values()), kept=kept or {},
                           refused=refused or {}, manage=allowed(principal, Action.MANAGE_COURSE, found)), status


@bp.post("/courses/<code>/assignments/<assignment>/submit")
@login_required(PAGE_ROLES)
def hand_in_page(code: str, assignment: str):
    principal = current_principal()
    with db.read() as session:
        found = find_assignment(session, principal, code, assignment)
        item = next((p for p in found.problems if p.problem.slug == request.form.get("problem", "")), None)
        if item is None:
            flash("Choose one of the assignment's problems.", "error")
            return redirect(url_for("student.assignment", code=code, assignment=assignment))
        require(principal, Action.SUBMIT, item.problem_version)
        names = [r["name"] for r in item.problem_version.references]
        assignment_id, problem_id, slug = found.id, item.problem_id, item.problem.slug
        graders = allowed(principal, Action.GRADE_COURSE, found)
    if graders:
        abort(403, "Only the course's students hand in answers for its assignments.")
    texts = {n: request.form.get(FIELD + n, "").strip() for n in names}
    texts = {n: t for n, t in texts.items() if t}
    if not texts:
        flash("Type at least one answer before submitting.", "error")
    sent, late, refused, limit = 0, 0, {}, None
    for name, text in texts.items():
        limit = limiter.refusal("submit", g.user.id, limit)
        if limit is not None:
            refused[(slug, name)] = limit
            continue
        try:
            _, late, created = hand_in(Database.current(), user=g.user, assignment_id=assignment_id,
                                       problem_id=problem_id, answer=name, text=text, now=clock.now(),
                                       secret=current_app.config["SECRET_KEY"])
            if created:
                sent += 1
            else:
                flash(f"{name}: you already sent exactly this answer; it was not counted again.", "info")
        except (HandInRefused, SubmissionRejected) as error:
            refused[(slug, name)] = str(error)
    if sent:
        lateness = f" ({late} day{'s' if late != 1 else ''} late)" if late else ""
        flash(f"Submitted {sent} answer{'s' if sent != 1 else ''} for grading{lateness}.", "success")
    if refused:
        why = " (too many submissions in a short time)" if limit else ""
        flash(f"Not submitted{why}: {', '.join(name for _, name in refused)}. Your text is kept below, with the "
              f"reason next to each.", "error")
        return _assignment_page(code, assignment, {(slug, n): t for n, t in texts.items() if (slug, n) in refused},
                                refused, status=429 if limit else 422)
    return redirect(url_for("student.assignment", code=code, assignment=assignment) + f"#problem-{slug}")
