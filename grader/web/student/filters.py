"""Template filters for every page (instructor pages use them too): math, statements, times, verdicts."""

from __future__ import annotations

from datetime import datetime

from grader.web.student import bp
from grader.web.student.statement import render_inline, render_math, render_statement
from grader.web.student.verdicts import VERDICT_LABELS, status_label


@bp.app_template_filter("statement")
def _statement(text: str):
    return render_statement(text or "")


@bp.app_template_filter("inline")
def _inline(text: str):
    return render_inline(text or "")


@bp.app_template_filter("math")
def _math(tex: str | None, display: bool = False):
    return render_math(tex, display=display)


@bp.app_template_filter("when")
def _when(moment: datetime | None) -> str:
    """A stored UTC time, short: "2026-11-21 13:04 UTC"."""
    return moment.strftime("%Y-%m-%d %H:%M UTC") if moment else ""


@bp.app_template_filter("verdict_label")
def _verdict_label(verdict: str | None) -> str:
    return VERDICT_LABELS.get(verdict or "", verdict or "")


@bp.app_template_global("status_label")
def _status_label(submission) -> tuple[str, str]:
    return status_label(submission)
