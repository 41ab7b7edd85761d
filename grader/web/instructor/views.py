"""Instructor routes (all under ``/instructor``).

``GET  /``                                       dashboard: the problems this instructor manages
``GET  /problems/new``, ``POST``                 register a scene file (upload or paste): queued for derivation
``GET  /derivations/<id>``                       its progress (queued, deriving), then a link to the review
``GET  /problems/<slug>/review[?version=N]``     statement, reference answers and derivation of a version
``POST /problems/<slug>/versions/<n>/publish``   let students see version n
``GET  /problems/<slug>``                        results: scores, grouped wrong answers, submissions
``GET  /problems/<slug>/submissions.csv``        every submission with its verdict in effect
``POST /problems/<slug>/regrade``                grade every submission again against the newest published
                                                 version (confirmed on ``GET``, followed on ``.../progress``:
                                                 :mod:`grader.web.instructor.versions`)
"""

from __future__ import annotations

from flask import abort, current_app, flash, g, redirect, render_template, request, url_for

from grader.jobs import regrade as queue_regrade
from grader.jobs.derivation import DerivationError, read_scene_id
from grader.jobs.derivation_queue import TooManyDerivations, enqueue, queued_ahead, unfinished_business
from grader.jobs.grading import check_request
from grader.store.db import Database, db
from grader.store.models import Problem, ProblemVersion
from grader.store.problems import latest_version, problem_by_slug, set_published
from grader.store.scores import practice_scores
from grader.web.auth.session import INSTRUCTOR_ROLES, login_required
from grader.web.csv_export import csv_response
from grader.web.instructor import bp
from grader.answers.grouping import GroupingCache, group_wrong_answers
from grader.web.instructor.stats import CSV_HEADER, csv_rows, per_answer, results, score_distribution, signature
from grader.web.policy import (Action, allowed, current_principal, find_derivation, find_problem,
                               find_problem_version, managed_courses, managed_problems, students_in_view)
from grader.web.problem_life import MAX_SCENE_BYTES, regrade_version
from grader.web.student.statement import statement_problems

SHOWN_GROUPS = 8
SHOWN_SUBMISSIONS = 50
GROUP_CHECK_BUDGET_S = 2.0
DERIVATION_REFRESH_S = 2  # how often the derivation page reloads itself while the scene waits or derives



def version_of(problem: Problem, number: int | None) -> ProblemVersion:
    """Version ``number`` of ``problem`` (the newest when None), else 404."""
    if number is None:
        return problem.versions[-1]
    version = next((v for v in problem.versions if v.number == number), None)
    if version is None:
        abort(404, "There is no such version.")
    return version


def _grouping_cache() -> GroupingCache:
    """The app's cache of wrong-answer groupings (one per app, so one per database)."""
    return current_app.extensions.setdefault("lagrade.grouping", GroupingCache())


@bp.get("/")
@login_required(INSTRUCTOR_ROLES)
def dashboard():
    items = []
    for problem in managed_problems(db.session, current_principal()):
        if not problem.versions:
            continue
        newest = problem.versions[-1]
        published = latest_version(db.session, problem, published_only=True)
        rows = results(db.session, problem)
        items.append({"problem": problem, "newest": newest, "published": published,
                      "submissions": len(rows), "students": len({r.user_id for r in rows}),
                      "pending": sum(1 for r in rows if r.status in ("queued", "running"))})
    return render_template("instructor/dashboard.html", items=items,
                           uploads=unfinished_business(db.session, g.user.id))


@bp.route("/problems/new", methods=["GET", "POST"])
@login_required(INSTRUCTOR_ROLES)
def new_problem():
    with db.read() as session:  # not the request's writer: the queue writes in its own transaction
        courses = managed_courses(session, current_principal())
    if request.method == "GET":
        return render_template("instructor/new_problem.html", courses=courses, source="", course_id="")
    upload = request.files.get("scene")
    source, filename = request.form.get("source", ""), "pasted.toml"
    if upload is not None and upload.filename:
        filename = upload.filename.rsplit("/", 1)[-1][:100] or "upload.toml"
        raw = upload.read(MAX_SCENE_BYTES + 1)
        try:
            source = raw.decode("utf-8")
        except UnicodeDecodeError:
            return _new_problem_error(courses, "", "The file is not UTF-8 text; save it as UTF-8 and try again.")
    course_id = request.form.get("course", "")
    if course_id and course_id not in {str(c.id) for c in courses}:
        return _new_problem_error(courses, source, "Choose one of your courses.")
    if not source.strip():
        return _new_problem_error(courses, source, "Upload a scene file or paste one.")
    if len(source.encode()) > MAX_SCENE_BYTES:
        return _new_problem_error(courses, "", f"A scene file may be at most {MAX_SCENE_BYTES // 1024} KiB.")
    # Refused at once what needs no engine: not TOML, or an id of a problem this instructor may not
    # change; the derivation itself runs in a derivation worker, off this request thread.
    try:
        slug = read_scene_id(source, filename)
    except DerivationError as error:
        return _new_problem_error(courses, source, str(error), course_id)
    principal = current_principal()
    with db.read() as session:
        existing = problem_by_slug(session, slug) if slug else None
        if existing is not None and not allowed(principal, Action.MANAGE, existing):
            return _new_problem_error(courses, source, f"The problem id {slug!r} is taken by another course; "
                                                       "give the scene another id.", course_id)
    try:
        job_id = enqueue(Database.current(), requester_id=g.user.id, source=source, filename=filename,
                         course_id=int(course_id) if course_id else None, publish=False,
                         max_active=current_app.config["DERIVE_MAX_ACTIVE"])
    except TooManyDerivations as refused:
        return _new_problem_error(courses, source, str(refused), course_id, status=429,
                                  headers={"Retry-After": str(refused.retry_after_s)})
    return redirect(url_for("instructor.derivation", job_id=job_id))


@bp.get("/derivations/<int:job_id>")
@login_required(INSTRUCTOR_ROLES)
def derivation(job_id: int):
    """How far an uploaded scene got; reloads itself (a meta refresh, no script) until it is done."""
    job = find_derivation(db.session, current_principal(), job_id)
    if job.status == "failed":
        with db.read() as session:
            courses = managed_courses(session, current_principal())
        return render_template("instructor/new_problem.html", courses=courses, source=job.source, error=job.error,
                               course_id=str(job.course_id or ""), job=job)
    return render_template("instructor/derivation.html", job=job, queued_ahead=queued_ahead(db.session, job),
                           refresh_s=DERIVATION_REFRESH_S)


def _new_problem_error(courses, source: str, message: str, course_id: str = "", *, status: int = 422,
                       headers: dict[str, str] | None = None):
    return render_template("instructor/new_problem.html", courses=courses, source=source, error=message,
                           course_id=course_id), status, headers or {}


@bp.get("/problems/<slug>/review")
@login_required(INSTRUCTOR_ROLES)
def review(slug: str):
    problem = find_problem(db.session, current_principal(), slug, Action.MANAGE)
    version = version_of(problem, request.args.get("version", type=int))
    published = latest_version(db.session, problem, published_only=True)
    texts = [version.statement] + [r.get("prompt") or "" for r in version.references]
    return render_template("instructor/review.html", problem=problem, version=version, published=published,
                           math_problems=sorted({c for t in texts for c in statement_problems(t)}),
                           steps=version.derivation.get("steps") or [])


@bp.post("/problems/<slug>/versions/<int:number>/publish")
@login_required(INSTRUCTOR_ROLES)
def publish(slug: str, number: int):
    version = find_problem_version(db.session, current_principal(), slug, number, Action.MANAGE)
    if not set_published(version, True):  # the same rule as the API's .../publish
        flash(f"Version {number} is already published.", "")
    else:
        db.session.commit()
        flash(f"Published version {number}: students now see it.", "success")
    return redirect(url_for("instructor.review", slug=slug, version=number))


@bp.get("/problems/<slug>")
@login_required(INSTRUCTOR_ROLES)
def problem(slug: str):
    principal = current_principal()
    found = find_problem(db.session, principal, slug, Action.READ_GRADES)
    version = latest_version(db.session, found, published_only=True) or found.versions[-1]
    rows = results(db.session, found, students_in_view(principal, found.course_id))
    names = [r["name"] for r in version.references]
    grouped, cache = {}, _grouping_cache()
    for reference in version.references:
        key = (found.id, reference["name"], version.id)
        wrong = [(r.user_id, r.text) for r in rows if r.answer == reference["name"] and r.verdict == "not_equivalent"]
        groups = cache.groups(key, signature(rows), lambda: group_wrong_answers(
            reference, wrong, lambda a, b, ref=reference: cache.equivalent(ref, a, b, _checker_says(ref))))
        grouped[reference["name"]] = {"groups": groups[:SHOWN_GROUPS], "more": max(0, len(groups) - SHOWN_GROUPS),
                                      "wrong": len(wrong), "prompt": reference.get("prompt") or reference["name"]}
    students = {r.user_id: r.student for r in rows}
    scores = sorted(((students[user_id], score) for user_id, score in practice_scores(db.session, version).items()
                     if user_id in students), key=lambda item: (item[0].lower(), item[1].problem))
    return render_template("instructor/problem.html", problem=found, version=version, grouped=grouped, scores=scores,
                           distribution=score_distribution(rows, names), answers=per_answer(rows, names),
                           recent=list(reversed(rows[-SHOWN_SUBMISSIONS:])), total=len(rows))


def _checker_says(reference: dict):
    """``equivalent(a, b)`` by the sandboxed checker, as grading decides it; "no" if it cannot answer."""
    def equivalent(a: str, b: str) -> bool:
        checkers = current_app.extensions["lagrade.checkers"]
        try:
            with checkers.borrow(timeout=current_app.config["CHECK_QUEUE_TIMEOUT_S"]) as checker:
                verdict = checker.run(dict(check_request(reference, b), reference=a, feedback=[]), GROUP_CHECK_BUDGET_S)
        except Exception:  # busy or broken checkers: keep the forms apart rather than fail the page
            current_app.logger.exception("grouping check failed")
            return False
        return verdict.get("verdict") == "equivalent"

    return equivalent


@bp.get("/problems/<slug>/submissions.csv")
@login_required(INSTRUCTOR_ROLES)
def export_csv(slug: str):
    principal = current_principal()
    found = find_problem(db.session, principal, slug, Action.EXPORT)
    rows = results(db.session, found, students_in_view(principal, found.course_id))
    return csv_response(csv_rows(rows), f"{found.slug}-submissions.csv", header=CSV_HEADER)


@bp.post("/problems/<slug>/regrade")
@login_required(INSTRUCTOR_ROLES)
def regrade(slug: str):
    me = current_principal()
    with db.read() as session:  # the queue writes in its own transaction
        found = find_problem(session, me, slug, Action.REGRADE)
        version = regrade_version(session, found)
    if version is None:
        flash("Publish a version before regrading.", "error")
        return redirect(url_for("instructor.problem", slug=slug))
    queued = queue_regrade(Database.current(), version)
    flash(f"Queued {queued} submission{'s' if queued != 1 else ''} for regrading against version "
          f"{version.number}.", "success")
    return redirect(url_for("instructor.regrade_progress", slug=slug))
