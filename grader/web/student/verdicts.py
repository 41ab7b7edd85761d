"""How a submission's state and verdict read to a student: a label, a CSS class, and feedback.

The checker's words (``equivalent``...) are about mathematics; students read "correct". The counter-
example shows the student's own value at a point but never the reference's: students never see
references, not even one number of them.
"""

from __future__ import annotations

from typing import Any

from grader.store.models import Submission

__all__ = ["VERDICT_LABELS", "status_label", "verdict_view"]

VERDICT_LABELS = {"equivalent": "correct", "not_equivalent": "incorrect", "invalid": "not graded"}
_CLASSES = {"equivalent": "correct", "not_equivalent": "incorrect", "invalid": "invalid"}
PENDING = ("queued", "running")


def status_label(submission: Submission) -> tuple[str, str]:
    """(text, css class) for the badge of a submission."""
    if submission.status == "queued":
        return "queued", "queued"
    if submission.status == "running":
        return "grading…", "running"
    verdict = submission.verdict
    if submission.status == "failed" or verdict is None:
        return "could not be graded", "failed"
    return VERDICT_LABELS.get(verdict.verdict, verdict.verdict), _CLASSES.get(verdict.verdict, "invalid")


def verdict_view(submission: Submission) -> dict[str, Any]:
    """Everything the verdict partial shows, none of it from the reference."""
    label, css = status_label(submission)
    view: dict[str, Any] = {"id": submission.id, "status": submission.status, "label": label, "css": css,
                            "pending": submission.status in PENDING, "answer": submission.answer_name,
                            "text": submission.text, "reason": None, "feedback": [], "latex": None,
                            "notes": [], "point": None, "score": None}
    verdict = submission.verdict
    if submission.status in PENDING or verdict is None:
        return view
    parsed = verdict.parsed or {}
    feedback = [item.get("message") for item in (verdict.feedback or []) if item.get("message")]
    example = verdict.counterexample or {}
    reason = verdict.reason
    if reason in feedback or (reason or "").endswith("the point in the counterexample"):
        reason = None  # said again below, in the feedback or with the point itself
    view.update(reason=reason, score=verdict.score, latex=parsed.get("latex") or None,
                notes=list(parsed.get("notes") or []), feedback=feedback)
    if verdict.verdict == "not_equivalent" and example.get("values"):
        view["point"] = {"values": {k: _short(v) for k, v in example["values"].items()},
                         "answer": _short(example.get("answer"))}
    return view


def _short(value: Any) -> Any:
    """4 significant digits for a float; other values as they are."""
    return f"{value:.4g}" if isinstance(value, float) else value
