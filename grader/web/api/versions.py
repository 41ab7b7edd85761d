"""A problem's life over the API, as on the instructor pages: versions, a new one, (un)publish, archive.

``GET  /problems/{id}/versions``                       every version, which one students see, archived or not
``POST /problems/{id}/versions``                       a scene file: derived in the background as a new draft
``POST /problems/{id}/versions/{n}/publish``           students see version n (the newest published one)
``POST /problems/{id}/versions/{n}/unpublish``         version n is a draft again
``POST /problems/{id}/archive``, ``.../restore``       students no longer see or answer it; and back

Each asks :mod:`grader.web.policy` (``manage``: an instructor of another course gets 404) and calls the
functions the pages call (:mod:`grader.web.problem_life`, :mod:`grader.store.problems`). Doing what is
done already (publishing a published version, archiving an archived problem, the same scene again)
changes nothing and says so (``"changed": false``), as the pages do: a retried request is harmless.
"""

from __future__ import annotations

from typing import Any

from flask import current_app, url_for
from sqlalchemy.orm import Session

from grader.store.db import db
from grader.store.models import Problem, ProblemVersion
from grader.store.problems import latest_version, set_archived, set_published
from grader.web.api import spec
from grader.web.api.derivations import DERIVATION
from grader.web.api.problems import INSTRUCTORS, accepted, scene_problem, scene_text
from grader.web.policy import Action, current_principal, find_problem, find_problem_version
from grader.web.problem_life import SceneRefused, queue_scene

__all__ = ["versions_json"]


def _time(value) -> str | None:
    return value.isoformat() + "Z" if value is not None else None


VERSIONS = spec.schema("ProblemVersions", {
    "type": "object", "required": ["id", "archived", "published_version", "versions", "links"], "properties": {
        "id": {"type": "string"},
        "archived": {"type": "boolean", "description": "Archived: only its managers see it; nobody answers it."},
        "archived_at": {"type": "string", "nullable": True},
        "published_version": {"type": "integer", "nullable": True,
                              "description": "The version students see: the newest published one (null: none)."},
        "versions": {"type": "array", "items": {"type": "object", "properties": {
            "version": {"type": "integer"}, "title": {"type": "string"}, "published": {"type": "boolean"},
            "created_at": {"type": "string"}, "engine_version": {"type": "string"},
            "source_sha256": {"type": "string"}, "links": {"type": "object"}}}},
        "links": {"type": "object"}}})
CHANGE = spec.schema("ProblemChange", {
    "type": "object", "required": ["changed", "detail", "problem"], "properties": {
        "changed": {"type": "boolean", "description": "False: it was so already, and nothing was done."},
        "detail": {"type": "string", "description": "What changed (or why nothing did), in words."},
        "problem": VERSIONS}})


def versions_json(session: Session, problem: Problem) -> dict[str, Any]:
    """A problem's versions and state, as those who manage it see them."""
    slug = problem.slug
    shown = latest_version(session, problem, published_only=True)
    return {
        "id": slug, "archived": problem.archived_at is not None, "archived_at": _time(problem.archived_at),
        "published_version": shown.number if shown else None,
        "versions": [{"version": v.number, "title": v.title, "published": v.published,
                      "created_at": _time(v.created_at), "engine_version": v.engine_version,
                      "source_sha256": v.source_sha256,
                      "links": {"publish": url_for("api.publish_version", slug=slug, number=v.number),
                                "unpublish": url_for("api.unpublish_version", slug=slug, number=v.number)}}
                     for v in problem.versions],
        "links": {"self": url_for("api.list_versions", slug=slug), "problem": url_for("api.get_problem", slug=slug),
                  "archive": url_for("api.archive_problem", slug=slug),
                  "restore": url_for("api.restore_problem", slug=slug)},
    }


def _change(problem: Problem, changed: bool, detail: str) -> dict[str, Any]:
    if changed:
        db.session.commit()
    return {"changed": changed, "detail": detail, "problem": versions_json(db.session, problem)}


_CHANGED = {200: ("Done, or (``changed`` false) it was so already.", {"application/json": CHANGE})}


@spec.route("/problems/<slug>/versions", "GET", roles=INSTRUCTORS, errors=(404,),
            responses={200: ("The problem's versions.", {"application/json": VERSIONS})})
def list_versions(slug: str):
    """List a problem's versions, drafts included, and say which one students see.

    Students see the newest published version, unless the problem is archived. Only those who manage
    the problem may list its versions (an instructor of another course gets ``404``).
    """
    return versions_json(db.session, find_problem(db.session, current_principal(), slug, Action.MANAGE))


@spec.route("/problems/<slug>/versions", "POST", roles=INSTRUCTORS, errors=(400, 404, 413, 415, 422, 429),
            request={"application/toml": {"type": "string", "description": "The problem's scene file, edited "
                                                                           "(docs/scene-format.md); its id stays."}},
            responses={202: ("The scene is queued for derivation as a new draft; follow Location.",
                             {"application/json": DERIVATION}),
                       200: ("The scene file is the newest version's: nothing to derive (``changed`` false).",
                             {"application/json": CHANGE})},
            headers={202: {"Location": {"description": "The derivation job to poll.", "schema": {"type": "string"}}}})
def create_version(slug: str):
    """Upload an edited scene file of a problem: it is derived in the background as a new draft version.

    The same path as ``POST /problems`` and the instructors' edit page: ``202`` with the derivation
    job to poll (``GET /derivations/{id}``), ``429`` beyond an instructor's derivations at once. The
    scene must keep the problem's ``id`` (else ``422``). The version is a draft: students keep the
    published one until ``POST /problems/{id}/versions/{n}/publish``. The newest version's own
    scene file again is not derived: ``200`` with ``changed`` false.
    """
    principal = current_principal()
    with db.read() as session:  # not the request's writer: the queue writes in its own transaction
        problem = find_problem(session, principal, slug, Action.MANAGE)  # before the body: 404 says nothing
    source = scene_text()
    try:
        queued = queue_scene(principal, source, filename=f"{slug}.toml", publish=False, problem=problem,
                             max_active=current_app.config["DERIVE_MAX_ACTIVE"])
    except SceneRefused as refused:
        raise scene_problem(refused) from None
    if queued.job_id is None:
        with db.read() as session:
            return {"changed": False, "detail": f"Nothing changed: the scene file is the same as version "
                                                f"{queued.same_as}.",
                    "problem": versions_json(session, session.get(Problem, problem.id))}
    return accepted(queued.job_id)


def _set_published(slug: str, number: int, published: bool) -> dict[str, Any]:
    version: ProblemVersion = find_problem_version(db.session, current_principal(), slug, number, Action.MANAGE)
    changed = set_published(version, published)
    if not changed:
        detail = f"Version {number} is {'already published' if published else 'not published'}."
    elif published:
        detail = f"Published version {number}: students now see it."
    else:
        still = latest_version(db.session, version.problem, published_only=True)
        detail = f"Version {number} is a draft again: students now see " + (
            f"version {still.number}." if still else "nothing of this problem.")
    return _change(version.problem, changed, detail)


@spec.route("/problems/<slug>/versions/<int:number>/publish", "POST", roles=INSTRUCTORS, errors=(404,),
            responses=_CHANGED)
def publish_version(slug: str, number: int):
    """Publish a version: students who may see the problem see it, if it is the newest published one.

    Publishing a published version changes nothing (``changed`` false).
    """
    return _set_published(slug, number, True)


@spec.route("/problems/<slug>/versions/<int:number>/unpublish", "POST", roles=INSTRUCTORS, errors=(404,),
            responses=_CHANGED)
def unpublish_version(slug: str, number: int):
    """Unpublish a version: it is a draft again, and students see the newest published one before it, or nothing.

    Their submissions to it are kept. Unpublishing a draft changes nothing (``changed`` false).
    """
    return _set_published(slug, number, False)


def _set_archived(slug: str, archived: bool) -> dict[str, Any]:
    problem = find_problem(db.session, current_principal(), slug, Action.MANAGE)
    changed = set_archived(problem, archived)
    if not changed:
        detail = "The problem is archived already." if archived else "The problem is not archived."
    elif archived:
        detail = "Archived: students no longer see or answer it; its submissions and grades stay."
    else:
        detail = "The problem is back: students who may see it see it again."
    return _change(problem, changed, detail)


@spec.route("/problems/<slug>/archive", "POST", roles=INSTRUCTORS, errors=(404,), responses=_CHANGED)
def archive_problem(slug: str):
    """Archive a problem: students no longer see or answer it; its managers keep it, its submissions and grades.

    Archiving an archived problem changes nothing (``changed`` false; ``archived_at`` stays).
    """
    return _set_archived(slug, True)


@spec.route("/problems/<slug>/restore", "POST", roles=INSTRUCTORS, errors=(404,), responses=_CHANGED)
def restore_problem(slug: str):
    """Bring an archived problem back: students who may see it see it and answer it again.

    Restoring a problem that is not archived changes nothing (``changed`` false).
    """
    return _set_archived(slug, False)
