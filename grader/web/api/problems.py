"""Problems: upload a scene (instructors), list and read problems (students never see references)."""

from __future__ import annotations

from typing import Any

from flask import current_app, request, url_for
from sqlalchemy.orm import Session

from grader.store.db import Database, db
from grader.store.models import DerivationJob, ProblemVersion
from grader.web.api import spec
from grader.web.api.derivations import DERIVATION, derivation_json
from grader.web.errors import ApiProblem
from grader.web.policy import (API_ROLES, INSTRUCTOR_ROLES, Action, allowed, current_principal, find_version,
                               visible_versions)
from grader.web.problem_life import MAX_SCENE_BYTES, SceneRefused, queue_scene

__all__ = ["INSTRUCTORS", "accepted", "problem_json", "scene_problem", "scene_text", "visible_version"]

INSTRUCTORS, EVERYONE = INSTRUCTOR_ROLES, API_ROLES

_ANSWER = {"type": "object", "properties": {
    "name": {"type": "string"}, "prompt": {"type": "string"}, "kind": {"type": "string"},
    "dimension": {"type": "string"}, "variables": {"type": "object"},
    "reference": {"type": "string", "description": "Instructors only."},
    "latex": {"type": "string", "description": "Instructors only."},
    "feedback": {"type": "array", "description": "Instructors only."}}}
PROBLEM = spec.schema("ProblemDetail", {"type": "object", "properties": {
    "id": {"type": "string"}, "version": {"type": "integer"}, "title": {"type": "string"},
    "statement": {"type": "string"}, "answers": {"type": "array", "items": _ANSWER},
    "published": {"type": "boolean"}, "links": {"type": "object"},
    "engine_version": {"type": "string", "description": "Instructors only."},
    "derivation": {"type": "object", "description": "Instructors only: Derivation.to_json()."}}})
PROBLEM_LIST = spec.schema("ProblemList", {"type": "object", "properties": {"problems": {"type": "array", "items": {
    "type": "object", "properties": {"id": {"type": "string"}, "title": {"type": "string"},
                                     "version": {"type": "integer"}, "links": {"type": "object"}}}}}})
_STUDENT_ANSWER_KEYS = ("name", "prompt", "kind", "dimension", "variables")


def visible_version(slug: str, session: Session | None = None, action: Action = Action.SEE) -> ProblemVersion:
    """The version of problem ``slug`` the caller works with, if the access policy lets them ``action``
    it (those who manage it: the newest, maybe a draft; others: the newest published); else 404/403."""
    return find_version(session or db.session, current_principal(), slug, action)


def problem_json(version: ProblemVersion, *, full: bool) -> dict[str, Any]:
    """A version as the API shows it; ``full`` (instructors) adds references and the derivation."""
    slug = version.problem.slug
    answers = version.references if full else [{k: r.get(k) for k in _STUDENT_ANSWER_KEYS} for r in version.references]
    body: dict[str, Any] = {
        "id": slug, "version": version.number, "title": version.title, "statement": version.statement,
        "published": version.published, "answers": answers,
        "links": {"self": url_for("api.get_problem", slug=slug),
                  "submissions": url_for("api.create_submission", slug=slug)},
    }
    if full:
        body.update(engine_version=version.engine_version, created_at=version.created_at.isoformat() + "Z",
                    source_sha256=version.source_sha256, derivation=version.derivation)
        body["links"].update(grades=url_for("api.get_grades", slug=slug), regrade=url_for("api.regrade", slug=slug),
                             versions=url_for("api.list_versions", slug=slug))
    return body


@spec.route("/problems", "POST", roles=INSTRUCTORS, errors=(400, 413, 415, 422, 429),
            request={"application/toml": {"type": "string", "description": "A scene file (docs/scene-format.md)."}},
            parameters=[{"name": "published", "in": "query", "schema": {"type": "boolean", "default": True},
                         "description": "Whether students see this version."}],
            responses={202: ("The scene is queued for derivation; follow Location until it is done or failed.",
                             {"application/json": DERIVATION})},
            headers={202: {"Location": {"description": "The derivation job to poll.", "schema": {"type": "string"}}}})
def create_problem():
    """Upload a scene file: it is derived in the background and stored as a problem version.

    The scene's ``id`` names the problem; uploading the same id with a changed source adds a new
    version. The answer is ``202`` with the derivation job to poll (``GET /derivations/{id}``): the
    engine runs in a child process under a time and memory limit, off the request threads. Each
    instructor may have a few derivations queued or running at once; beyond that, ``429``.
    """
    source = scene_text()
    published = request.args.get("published", "true").lower() not in ("false", "0", "no")
    try:
        queued = queue_scene(current_principal(), source, filename="upload.toml", publish=published,
                             max_active=current_app.config["DERIVE_MAX_ACTIVE"])
    except SceneRefused as refused:
        raise scene_problem(refused) from None
    return accepted(queued.job_id)


def scene_text() -> str:
    """The request's body as a scene file's text: 415 unless TOML, 413 if too large, 400 unless UTF-8."""
    if request.mimetype != "application/toml":
        raise ApiProblem(415, "Send the scene file with 'Content-Type: application/toml'.", kind="unsupported-media-type")
    too_large = ApiProblem(413, f"A scene file may be at most {MAX_SCENE_BYTES // 1024} KiB.", kind="too-large")
    if (request.content_length or 0) > MAX_SCENE_BYTES:
        raise too_large  # before reading a byte of it
    raw = request.get_data(cache=False)
    if len(raw) > MAX_SCENE_BYTES:
        raise too_large
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        raise ApiProblem(400, "The scene file is not UTF-8 text.", kind="invalid-scene") from None


# The API's status for each reason the shared intake (grader.web.problem_life) refuses a scene file.
_REFUSALS = {"empty": (422, "invalid-scene"), "too-large": (413, "too-large"), "invalid-scene": (422, "invalid-scene"),
             "wrong-id": (422, "wrong-scene-id"), "too-many-derivations": (429, "too-many-derivations")}


def scene_problem(refused: SceneRefused) -> ApiProblem:
    """A refused scene file as the API answers it."""
    status, kind = _REFUSALS[refused.kind]
    headers = {"Retry-After": str(refused.retry_after_s)} if refused.retry_after_s is not None else None
    return ApiProblem(status, refused.message, kind=kind, headers=headers)


def accepted(job_id: int):
    """``202 Accepted`` with the queued derivation job, and its address in ``Location``."""
    database = Database.current()
    with database.read() as session:
        body = derivation_json(session, session.get(DerivationJob, job_id))
    return body, 202, {"Location": body["links"]["self"]}


@spec.route("/problems", "GET", roles=EVERYONE,
            responses={200: ("The problems this token may see.", {"application/json": PROBLEM_LIST})})
def list_problems():
    """List the problems this token may see: published ones of its courses and of no course, and
    (instructors) every version's newest of the problems they manage, drafts included."""
    versions = sorted(visible_versions(db.session, current_principal()), key=lambda v: v.problem.slug)
    return {"problems": [{"id": v.problem.slug, "title": v.title, "version": v.number,
                          "links": {"self": url_for("api.get_problem", slug=v.problem.slug)}}
                         for v in versions]}


@spec.route("/problems/<slug>", "GET", roles=EVERYONE, errors=(404,),
            responses={200: ("The problem (students: statement and prompts only).", {"application/json": PROBLEM})})
def get_problem(slug: str):
    """Read a problem: statement and answer prompts; instructors also get references and the derivation."""
    version = visible_version(slug)
    return problem_json(version, full=allowed(current_principal(), Action.MANAGE, version))
