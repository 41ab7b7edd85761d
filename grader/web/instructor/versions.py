"""A problem's life after registration: edit its draft, unpublish, archive, compare versions, regrade.

``GET  /problems/<slug>/edit``, ``POST``                 the newest scene file in a form; saving queues it
                                                         for derivation as a new draft version
``POST /problems/<slug>/versions/<n>/unpublish``         students stop seeing version n
``POST /problems/<slug>/archive``                        archive (``restore=1``: bring back) the problem
``GET  /problems/<slug>/diff?from=a&to=b``               what changed: scene file and reference answers
``GET  /problems/<slug>/regrade``                        how many submissions a regrade would queue (confirm)
``GET  /problems/<slug>/regrade/progress``               queued / grading / graded counts, reloading itself

Every view asks :mod:`grader.web.policy` (``manage`` or ``regrade``) before it reads or changes anything.
Editing, unpublishing and archiving call the functions the REST API calls for the same
(:mod:`grader.web.problem_life`, :mod:`grader.store.problems`): one rule for both.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from typing import Any

from flask import abort, current_app, flash, redirect, render_template, request, url_for
from sqlalchemy import func, select

from grader.store.db import db
from grader.store.models import Problem, ProblemVersion, Submission
from grader.store.problems import latest_version, set_archived, set_published
from grader.web.auth.session import INSTRUCTOR_ROLES, login_required
from grader.web.instructor import bp
from grader.web.instructor.views import version_of
from grader.web.policy import Action, current_principal, find_problem, find_problem_version
from grader.web.problem_life import SceneRefused, queue_scene

REGRADE_REFRESH_S = 2  # how often the regrade progress page reloads itself while submissions wait
DIFF_CONTEXT_LINES = 3
# What a reference answer holds besides its name, in the order the comparison table lists changes.
REFERENCE_FIELDS = ("reference", "kind", "prompt", "dimension", "variables", "feedback", "feedback_detail",
                    "weight", "unit", "tolerance", "implicit")


# --- edit the draft ------------------------------------------------------------------------------

@bp.route("/problems/<slug>/edit", methods=["GET", "POST"])
@login_required(INSTRUCTOR_ROLES)
def edit(slug: str):
    """The newest version's scene file, editable; saving derives it (in a derivation worker) as a draft."""
    me = current_principal()
    with db.read() as session:  # not the request's writer: the queue writes in its own transaction
        problem = find_problem(session, me, slug, Action.MANAGE)
        newest = problem.versions[-1]
        base = {"problem": problem, "newest": newest, "published": latest_version(session, problem,
                                                                                  published_only=True)}
    if request.method == "GET":
        return render_template("instructor/edit.html", source=newest.source, **base)
    source = request.form.get("source", "")
    try:
        # The API's POST /problems/{id}/versions takes the same path (grader.web.problem_life).
        queued = queue_scene(me, source, filename=f"{slug}.toml", publish=False, problem=problem,
                             max_active=current_app.config["DERIVE_MAX_ACTIVE"])
    except SceneRefused as refused:
        if refused.kind == "too-many-derivations":
            return _edit_error(base, source, refused.message, status=429,
                               headers={"Retry-After": str(refused.retry_after_s)})
        # A file too large is not sent back into the form (it would be as large again).
        return _edit_error(base, "" if refused.kind == "too-large" else source, refused.message)
    if queued.job_id is None:
        flash(f"Nothing changed: the scene file is the same as version {queued.same_as}.", "")
        return redirect(url_for("instructor.review", slug=slug, version=queued.same_as))
    return redirect(url_for("instructor.derivation", job_id=queued.job_id))


def _edit_error(base: dict, source: str, message: str, *, status: int = 422, headers: dict[str, str] | None = None):
    return render_template("instructor/edit.html", source=source, error=message, **base), status, headers or {}


# --- unpublish, archive --------------------------------------------------------------------------

@bp.post("/problems/<slug>/versions/<int:number>/unpublish")
@login_required(INSTRUCTOR_ROLES)
def unpublish(slug: str, number: int):
    version = find_problem_version(db.session, current_principal(), slug, number, Action.MANAGE)
    if not set_published(version, False):  # the same rule as the API's .../unpublish
        flash(f"Version {number} is not published.", "")
    else:
        db.session.commit()
        still = latest_version(db.session, version.problem, published_only=True)
        flash(f"Version {number} is a draft again: students now see "
              + (f"version {still.number}." if still else "nothing of this problem."), "success")
    return redirect(url_for("instructor.review", slug=slug, version=number))


@bp.post("/problems/<slug>/archive")
@login_required(INSTRUCTOR_ROLES)
def archive(slug: str):
    """Archive the problem (students no longer see or answer it), or with ``restore=1`` bring it back."""
    problem = find_problem(db.session, current_principal(), slug, Action.MANAGE)
    restore = request.form.get("restore") == "1"
    if not set_archived(problem, not restore):  # the same rule as the API's .../archive and .../restore
        flash("The problem is not archived." if restore else "The problem is archived already.", "")
    else:
        db.session.commit()
        flash("The problem is back: students who may see it see it again." if restore else
              "Archived: students no longer see or answer it; its submissions and grades stay here.", "success")
    return redirect(url_for("instructor.review", slug=slug))


# --- compare two versions ------------------------------------------------------------------------

@dataclass(frozen=True)
class ReferenceChange:
    """One answer's reference between two versions: ``added``, ``removed``, ``changed`` or ``same``."""

    name: str
    change: str
    fields: tuple[str, ...]
    before: dict[str, Any] | None
    after: dict[str, Any] | None


def reference_changes(before: list[dict[str, Any]], after: list[dict[str, Any]]) -> list[ReferenceChange]:
    """How the reference answers changed from ``before`` to ``after`` (by answer name, in ``after``'s order).

    >>> [(c.name, c.change, c.fields) for c in reference_changes(
    ...     [{"name": "T", "reference": "m*g"}, {"name": "a", "reference": "g"}],
    ...     [{"name": "T", "reference": "m*g/2"}, {"name": "w", "reference": "0"}])]
    [('T', 'changed', ('reference',)), ('w', 'added', ()), ('a', 'removed', ())]
    """
    old = {r["name"]: r for r in before}
    new = {r["name"]: r for r in after}
    changes = []
    for name, ref in new.items():
        if name not in old:
            changes.append(ReferenceChange(name, "added", (), None, ref))
            continue
        keys = [k for k in REFERENCE_FIELDS if k in ref or k in old[name]]
        keys += sorted((set(ref) | set(old[name])) - set(REFERENCE_FIELDS) - {"name"})
        fields = tuple(k for k in keys if ref.get(k) != old[name].get(k))
        changes.append(ReferenceChange(name, "changed" if fields else "same", fields, old[name], ref))
    changes += [ReferenceChange(name, "removed", (), ref, None) for name, ref in old.items() if name not in new]
    return changes


def source_diff(before: ProblemVersion, after: ProblemVersion) -> list[tuple[str, str]]:
    """The unified diff of two versions' scene files, as (css class, line) pairs."""
    lines = difflib.unified_diff(before.source.splitlines(), after.source.splitlines(),
                                 f"version {before.number}", f"version {after.number}",
                                 n=DIFF_CONTEXT_LINES, lineterm="")
    kinds = {"+": "add", "-": "del", "@": "hunk"}
    return [("head" if line.startswith(("+++", "---")) else kinds.get(line[:1], "same"), line) for line in lines]


@bp.get("/problems/<slug>/diff")
@login_required(INSTRUCTOR_ROLES)
def diff(slug: str):
    problem = find_problem(db.session, current_principal(), slug, Action.MANAGE)
    numbers = [v.number for v in problem.versions]
    after = version_of(problem, _number_arg("to"))
    default_before = max((n for n in numbers if n < after.number), default=after.number)
    before = version_of(problem, _number_arg("from") or default_before)
    return render_template("instructor/diff.html", problem=problem, before=before, after=after, numbers=numbers,
                           lines=source_diff(before, after),
                           changes=reference_changes(before.references, after.references))


def _number_arg(name: str) -> int | None:
    value = request.args.get(name, "")
    if not value:
        return None
    if not value.isdigit() or len(value) > 9:
        abort(404, "There is no such version.")
    return int(value)


# --- regrade: confirm, then follow ---------------------------------------------------------------

def _submissions_of(problem: Problem):
    return select(Submission.status, func.count()).where(Submission.problem_version_id.in_(
        select(ProblemVersion.id).where(ProblemVersion.problem_id == problem.id))).group_by(Submission.status)


def status_counts(session, problem: Problem) -> dict[str, int]:
    """How many of the problem's submissions are queued, running, done and failed."""
    counts = {"queued": 0, "running": 0, "done": 0, "failed": 0}
    counts.update({status: n for status, n in session.execute(_submissions_of(problem))})
    return counts


@bp.get("/problems/<slug>/regrade")
@login_required(INSTRUCTOR_ROLES)
def confirm_regrade(slug: str):
    """What a regrade would do (how many submissions, against which version), with the button to start it."""
    problem = find_problem(db.session, current_principal(), slug, Action.REGRADE)
    counts = status_counts(db.session, problem)
    return render_template("instructor/regrade.html", problem=problem, total=sum(counts.values()), counts=counts,
                           version=latest_version(db.session, problem, published_only=True))


@bp.get("/problems/<slug>/regrade/progress")
@login_required(INSTRUCTOR_ROLES)
def regrade_progress(slug: str):
    """Queued, grading and graded submissions of the problem; reloads itself (meta refresh) until none waits."""
    problem = find_problem(db.session, current_principal(), slug, Action.REGRADE)
    counts = status_counts(db.session, problem)
    total = sum(counts.values())
    finished = counts["done"] + counts["failed"]
    return render_template("instructor/regrade_progress.html", problem=problem, counts=counts, total=total,
                           finished=finished, waiting=counts["queued"] + counts["running"],
                           percent=round(100 * finished / total) if total else 100, refresh_s=REGRADE_REFRESH_S,
                           version=latest_version(db.session, problem, published_only=True))
