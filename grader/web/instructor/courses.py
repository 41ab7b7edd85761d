"""Instructor course pages (under ``/instructor``).

``GET  /courses``, ``POST``                                 my courses; start one
``GET  /courses/<code>``                                    roster, assignments, forms to enrol and to build
``POST /courses/<code>/members``                            enrol one person, or a CSV roster (file or pasted)
``POST /courses/<code>/assignments``                        build an assignment
``GET  /courses/<code>/assignments/<assignment>``           its gradebook: students × problems
``POST /courses/<code>/assignments/<assignment>/release``   show its solutions now
``GET  /courses/<code>/gradebook.csv[?assignment=]``        the gradebook as CSV (the API's rows)

Teaching assistants see rosters and gradebooks; only instructors enrol, build and release.
"""

from __future__ import annotations

from datetime import datetime

from flask import abort, flash, g, redirect, render_template, request, url_for
from sqlalchemy.exc import IntegrityError

from grader.store.assignments import AssignmentError, create_assignment, zone
from grader.store.courses import CourseError, Member, add_member, create_course, parse_roster, roster
from grader.store.db import db
from grader.store.models import ENROLMENT_ROLES, SCORE_POLICIES, Course, User
from grader.store.scores import gradebook
from grader.web import clock
from grader.web.auth.session import login_required
from grader.web.coursework import GRADEBOOK_COLUMNS, assignment_view, gradebook_rows
from grader.web.csv_export import csv_response
from grader.web.instructor import bp
from grader.web.policy import (INSTRUCTOR_ROLES, PAGE_ROLES, Action, allowed, current_principal, find_assignment,
                               find_course, managed_problems, my_courses, require)

MAX_ROSTER_BYTES = 512 * 1024


@bp.route("/courses", methods=["GET", "POST"])
@login_required(INSTRUCTOR_ROLES)
def courses():
    principal = current_principal()
    if request.method == "POST":
        require(principal, Action.CREATE_COURSE, None)
        code, title = request.form.get("code", "").strip(), request.form.get("title", "").strip()
        if not title or len(title) > 200:
            flash("A course needs a title (at most 200 characters).", "error")
        else:
            try:  # create_course checks the code by the rule the API and the command line apply
                with db.write() as session:
                    create_course(session, code=code, title=title, instructor=session.get(User, g.user.id))
                return redirect(url_for("instructor.course", code=code))
            except (CourseError, IntegrityError) as error:
                flash(str(error) if isinstance(error, CourseError) else f"There is already a course {code!r}.", "error")
    return render_template("courses/instructor_list.html", courses=my_courses(db.session, principal)), (
        422 if request.method == "POST" else 200)


@bp.get("/courses/<code>")
@login_required(PAGE_ROLES)
def course(code: str):
    principal = current_principal()
    found = find_course(db.session, principal, code, Action.GRADE_COURSE)
    problems = [p for p in managed_problems(db.session, principal)
                if p.course_id in (None, found.id) and any(v.published for v in p.versions)]
    return render_template("courses/course.html", course=found, members=roster(db.session, found),
                           manage=allowed(principal, Action.MANAGE_COURSE, found), problems=problems,
                           roles=ENROLMENT_ROLES, policies=SCORE_POLICIES)


@bp.post("/courses/<code>/members")
@login_required(INSTRUCTOR_ROLES)
def add_members(code: str):
    with db.read() as session:
        course_id = find_course(session, current_principal(), code, Action.MANAGE_COURSE).id
    upload = request.files.get("roster")
    text = upload.read(MAX_ROSTER_BYTES + 1).decode("utf-8", "replace") if upload and upload.filename else \
        request.form.get("roster_text", "")
    try:
        if len(text) > MAX_ROSTER_BYTES:
            raise CourseError(f"A roster may be at most {MAX_ROSTER_BYTES // 1024} KiB.")
        if text.strip():
            members = parse_roster(text)
        else:
            members = [Member(name=request.form.get("name", "").strip()[:200],
                              email=request.form.get("email", "").strip()[:320] or None,
                              external_id=request.form.get("external_id", "").strip()[:200] or None,
                              role=request.form.get("role", "student"))]
            if members[0].email and "@" not in members[0].email:
                raise CourseError(f"{members[0].email!r} is not an e-mail address.")
        with db.write() as session:
            found = session.get(Course, course_id)
            created = sum(add_member(session, found, m)[1] for m in members)
        flash(f"Enrolled {len(members)} {'person' if len(members) == 1 else 'people'}"
              f" ({created} new account{'s' if created != 1 else ''}).", "success")
    except CourseError as error:
        flash(str(error), "error")
    return redirect(url_for("instructor.course", code=code) + "#roster")


def _local(field: str, time_zone: str) -> datetime | None:
    """A form's ``datetime-local`` value, in the chosen time zone."""
    value = request.form.get(field, "").strip()
    if not value:
        return None
    try:
        return datetime.fromisoformat(value).replace(tzinfo=zone(time_zone))
    except ValueError:
        raise AssignmentError(f"{field.replace('_', ' ')}: {value[:40]!r} is not a date and time.") from None


@bp.post("/courses/<code>/assignments")
@login_required(INSTRUCTOR_ROLES)
def create_assignment_page(code: str):
    with db.read() as session:
        course_id = find_course(session, current_principal(), code, Action.MANAGE_COURSE).id
    form = request.form
    slug = form.get("id", "").strip()
    try:
        time_zone = form.get("time_zone", "UTC").strip() or "UTC"
        if not slug or len(slug) > 64 or not slug.replace("-", "").replace("_", "").isalnum():
            raise AssignmentError("An assignment needs an id: letters, digits, - and _ (at most 64).")
        attempts = form.get("max_attempts", "").strip()
        penalty = form.get("late_penalty_percent", "").strip()
        with db.write() as session:
            create_assignment(session, session.get(Course, course_id), slug=slug,
                              title=form.get("title", "").strip()[:200] or slug,
                              problems=form.getlist("problems")[:50], opens_at=_local("opens_at", time_zone),
                              due_at=_local("due_at", time_zone), closes_at=_local("closes_at", time_zone),
                              time_zone=time_zone, max_attempts=int(attempts) if attempts.isdigit() else None,
                              late_penalty_per_day=float(penalty) / 100 if penalty else 0.0,
                              score_policy=form.get("score_policy", "best"))
    except (AssignmentError, ValueError, TypeError) as error:
        message = str(error) if isinstance(error, AssignmentError) else "Fill in the times, attempts and penalty."
        if "opens before" not in message and _local_missing(form):
            message = "Give the opening and due times."
        flash(message, "error")
        return redirect(url_for("instructor.course", code=code) + "#new-assignment")
    except IntegrityError:
        flash(f"The course already has an assignment {slug!r}.", "error")
        return redirect(url_for("instructor.course", code=code) + "#new-assignment")
    flash(f"Assignment {slug!r} created.", "success")
    return redirect(url_for("instructor.assignment_gradebook", code=code, assignment=slug))


def _local_missing(form) -> bool:
    return not form.get("opens_at", "").strip() or not form.get("due_at", "").strip()


@bp.get("/courses/<code>/assignments/<assignment>")
@login_required(PAGE_ROLES)
def assignment_gradebook(code: str, assignment: str):
    principal = current_principal()
    found = find_assignment(db.session, principal, code, assignment, Action.GRADE_COURSE)
    return render_template("courses/gradebook.html", a=assignment_view(db.session, found, clock.now(), student=None),
                           code=code, rows=gradebook(db.session, found),
                           manage=allowed(principal, Action.MANAGE_COURSE, found))


@bp.post("/courses/<code>/assignments/<assignment>/release")
@login_required(INSTRUCTOR_ROLES)
def release_solutions(code: str, assignment: str):
    found = find_assignment(db.session, current_principal(), code, assignment, Action.MANAGE_COURSE)
    found.solutions_released = True
    db.session.commit()
    flash("Solutions released: the students see them now.", "success")
    return redirect(url_for("instructor.assignment_gradebook", code=code, assignment=assignment))


@bp.get("/courses/<code>/gradebook.csv")
@login_required(PAGE_ROLES)
def gradebook_csv(code: str):
    found = find_course(db.session, current_principal(), code, Action.GRADE_COURSE)
    assignments = list(found.assignments)
    only = request.args.get("assignment")
    if only is not None:
        assignments = [a for a in assignments if a.slug == only]
        if not assignments:
            abort(404, f"There is no assignment {only!r} in this course.")
    return csv_response(gradebook_rows(db.session, assignments), f"{code}-gradebook.csv", header=GRADEBOOK_COLUMNS)
