"""Derivation jobs: an uploaded scene's way to a problem version, polled by the instructor who sent it.

``POST /problems`` answers ``202 Accepted`` with ``Location: /api/v1/derivations/{id}``; the scene is
derived by a derivation worker, off the request threads, and ``GET /derivations/{id}`` says how far
it got: ``queued`` (with how many uploads are ahead), ``running``, ``done`` (with a link to the
problem) or ``failed`` (with the scene's error, for its author).
"""

from __future__ import annotations

from typing import Any

from flask import url_for
from sqlalchemy.orm import Session

from grader.jobs.derivation_queue import queued_ahead
from grader.store.db import db
from grader.store.models import DerivationJob
from grader.web.api import spec
from grader.web.policy import INSTRUCTOR_ROLES, current_principal, find_derivation

__all__ = ["DERIVATION", "derivation_json"]

INSTRUCTORS = INSTRUCTOR_ROLES

DERIVATION = spec.schema("Derivation", {"type": "object", "required": ["id", "status", "links"], "properties": {
    "id": {"type": "integer"},
    "status": {"type": "string", "enum": ["queued", "running", "done", "failed"]},
    "filename": {"type": "string"},
    "queued_ahead": {"type": "integer", "nullable": True,
                     "description": "Queued: how many uploads will be derived before this one."},
    "error": {"type": "string", "nullable": True, "description": "Failed: why the scene could not be used."},
    "problem": {"type": "object", "nullable": True, "description": "Done: the problem version it made.",
                "properties": {"id": {"type": "string"}, "version": {"type": "integer"},
                               "new_version": {"type": "boolean",
                                               "description": "False: the source equalled the newest version's."}}},
    "created_at": {"type": "string"}, "started_at": {"type": "string", "nullable": True},
    "finished_at": {"type": "string", "nullable": True},
    "links": {"type": "object", "properties": {"self": {"type": "string"}, "problem": {"type": "string"}}}}})


def _time(value) -> str | None:
    return value.isoformat() + "Z" if value is not None else None


def derivation_json(session: Session, job: DerivationJob) -> dict[str, Any]:
    """A job as the API shows it (only ever to those the policy lets view it)."""
    body: dict[str, Any] = {
        "id": job.id, "status": job.status, "filename": job.filename, "queued_ahead": queued_ahead(session, job),
        "error": job.error, "problem": None, "created_at": _time(job.created_at),
        "started_at": _time(job.started_at), "finished_at": _time(job.finished_at),
        "links": {"self": url_for("api.get_derivation", job_id=job.id)},
    }
    version = job.problem_version
    if job.status == "done" and version is not None:
        slug = version.problem.slug
        body["problem"] = {"id": slug, "version": version.number, "new_version": bool(job.new_version)}
        body["links"]["problem"] = url_for("api.get_problem", slug=slug)
    return body


@spec.route("/derivations/<int:job_id>", "GET", roles=INSTRUCTORS, errors=(404,),
            responses={200: ("How far the derivation got.", {"application/json": DERIVATION})})
def get_derivation(job_id: int):
    """Follow an uploaded scene's derivation: queued, running, done (a problem version) or failed.

    Only the instructor who uploaded it, the instructors of its course and admins may see it. Poll
    until ``status`` is ``done`` or ``failed``; a derivation takes at most the server's time limit
    (``DERIVE_TIMEOUT_S``) once it runs.
    """
    session = db.session
    return derivation_json(session, find_derivation(session, current_principal(), job_id))
