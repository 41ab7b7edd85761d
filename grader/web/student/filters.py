"""Template filters for every page (instructor pages use them too): math, statements, times, verdicts."""

from __future__ import annotations

from datetime import datetime, timezone

from markupsafe import Markup

from grader.web.student import bp
from grader.web.student.statement import render_inline, render_math, render_statement, render_text
from grader.web.student.verdicts import VERDICT_LABELS, status_label


@bp.app_template_filter("statement")
def _statement(text: str):
    return render_statement(text or "")


@bp.app_template_filter("inline")
def _inline(text: str):
    return render_inline(text or "")


@bp.app_template_filter("message")
def _message(text: str | None):
    """Feedback, a verdict's reason, a scene error: plain text with ``$...$`` math."""
    return render_text(text or "")


@bp.app_template_filter("math")
def _math(tex: str | None, display: bool = False):
    return render_math(tex, display=display)


@bp.app_template_filter("when")
def _when(moment: datetime | None) -> Markup:
    """A stored UTC time as ``<time>``: "2026-11-21 13:04 UTC", which ``static/js/local-time.js``
    rewrites in the reader's own time zone (without script the UTC text stays, and says so)."""
    if moment is None:
        return Markup("")
    stamp = moment.replace(tzinfo=timezone.utc) if moment.tzinfo is None else moment.astimezone(timezone.utc)
    return Markup('<time datetime="{}" data-local>{}</time>').format(
        stamp.isoformat(timespec="seconds").replace("+00:00", "Z"), stamp.strftime("%Y-%m-%d %H:%M UTC"))


@bp.app_template_filter("verdict_label")
def _verdict_label(verdict: str | None) -> str:
    return VERDICT_LABELS.get(verdict or "", verdict or "")


@bp.app_template_global("status_label")
def _status_label(submission) -> tuple[str, str]:
    return status_label(submission)
