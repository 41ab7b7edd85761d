"""How a submission's state and verdict read to a student: a label, a CSS class, and feedback.

The checker's words (``equivalent``...) are about mathematics; students read "correct". The counter-
example shows the student's own value at a point but never the reference's: students never see
references, not even one number of them.
"""

from __future__ import annotations

from typing import Any

from grader.expressions import parse_dimension
from grader.expressions.names import latex_name
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
    """Everything the verdict partial shows, none of it from the reference.

    ``summary`` is one sentence a student can act on (None when the feedback says it already);
    ``reason`` is the checker's technical account, for instructors' pages only. ``feedback`` holds
    each distinct message once.
    """
    label, css = status_label(submission)
    reference = submission.problem_version.reference(submission.answer_name) or {}
    view: dict[str, Any] = {"id": submission.id, "status": submission.status, "label": label, "css": css,
                            "pending": submission.status in PENDING, "answer": submission.answer_name,
                            "prompt": reference.get("prompt") or submission.answer_name,
                            "text": submission.text, "reason": None, "summary": None, "feedback": [],
                            "latex": None, "notes": [], "point": None, "score": None}
    verdict = submission.verdict
    if submission.status in PENDING or verdict is None:
        if submission.status == "failed":
            view["summary"] = _FAILED
        return view
    parsed = verdict.parsed or {}
    items = [item for item in (verdict.feedback or []) if isinstance(item, dict) and item.get("message")]
    if any(item.get("code") == "instructor" for item in items):
        # The instructor wrote this for exactly this wrong answer: the grader's own guess at the slip
        # ("off by a constant factor") would say the same thing again, differently.
        items = [item for item in items if item.get("code") == "instructor"]
    feedback = list(dict.fromkeys(item["message"] for item in items))
    example = verdict.counterexample or {}
    view.update(reason=verdict.reason, score=verdict.score, latex=parsed.get("latex") or None,
                notes=list(parsed.get("notes") or []), feedback=feedback)
    if verdict.verdict == "not_equivalent" and example.get("values"):
        view["point"] = _point(example, reference)
    if not feedback:
        view["summary"] = student_summary(verdict.verdict, verdict.reason, point=view["point"] is not None)
    return view


_FAILED = "The grader failed on this answer (not your fault): your instructor can see it and regrade it."
# The checker's reasons (grader.answers) by how they begin, in words a student can act on. Reasons
# that already are such words (a dimension, an undefined answer) are kept as they are.
_NOT_EQUIVALENT = (
    ("your answer differs from the correct one by a constant", "Your answer is off by a constant term: "
     "check for a missing or extra term that does not depend on anything."),
    ("your answer is defined at a point", "Your answer has a value where the correct answer is undefined: "
     "check what should divide by zero or leave the domain there."),
    ("your answer is undefined at a point", "Your answer is undefined somewhere the correct answer is not: "
     "check for a division by zero or a square root of a negative number."),
    ("your equation is undefined", "Your equation is undefined somewhere the correct one is not: check for a "
     "division by zero."),
    ("your equation is the reference multiplied by a factor that depends", "Your equation is the right one "
     "multiplied by something that changes with the motion: that is a different equation. Check which "
     "terms belong on each side."),
    ("your equation is not the reference multiplied", "Your equation is not the correct one, nor a constant "
     "multiple of it: check each term."),
    ("expected ", "You sent a different number of equations than the question asks for."),
    ("the ratio to the reference depends", "Your equation is not a constant multiple of the correct one: "
     "check each term."),
    ("your equations are not combinations", "Your equations do not follow from the correct ones: check "
     "each of them."),
    ("your equations are not independent", "Your equations are not independent: together they say less than "
     "the question asks for."),
    # A system mixed by factors that change with the motion (θ̇, cos θ) and vanish somewhere.
    ("your equations are combinations of the reference equations whose mixing matrix depends on the state and "
     "is singular", "Your equations are the right ones multiplied or combined by something that changes with "
     "the motion and becomes zero somewhere: there they no longer determine the motion. Check which factors "
     "you multiplied by."),
    ("your equations are combinations of the reference", "Your equations could not be shown to determine the "
     "motion everywhere: check which factors you multiplied the equations by."),
    ("your equations agree with combinations", "Your equations could not be confirmed: write each of them "
     "more directly, as the equation of motion of one coordinate."),
    ("your equation holds where", "Your equation holds at states where the correct one does not: check each "
     "term."),
)
_INVALID = (
    ("budget exceeded", "The grader ran out of time on this answer. Write it more simply (cancel what "
     "cancels, avoid huge powers) and send it again; your instructor can see this attempt."),
    ("the checker cannot evaluate", "The grader cannot evaluate part of this answer: write it with the "
     "functions listed under the input."),
    ("give a unit", None),
)


def student_summary(verdict: str, reason: str | None, point: bool = False) -> str | None:
    """One sentence for a student about a verdict whose feedback is empty.

    >>> student_summary("not_equivalent", "your answer and the correct one differ at the point in the "
    ...                 "counterexample", point=True) is None   # the point itself says it, with values
    True
    >>> student_summary("invalid", "budget exceeded: the time budget ran out while comparing")[:41]
    'The grader ran out of time on this answer'
    """
    text = (reason or "").strip()
    if verdict == "equivalent":
        return None
    if verdict == "not_equivalent":
        for start, words in _NOT_EQUIVALENT:
            if text.startswith(start):
                return words
        if point:
            return None
        if text.startswith(("your answer is", "wrong unit")):
            return text[:1].upper() + text[1:] + ("" if text.endswith(".") else ".")
        return "Your answer is not equivalent to the correct one."
    for start, words in _INVALID:
        if text.startswith(start):
            return words if words is not None else text[:1].upper() + text[1:] + "."
    if text.startswith("your answer"):
        return text[:1].upper() + text[1:] + ("" if text.endswith(".") else ".")
    return "The grader could not decide whether this answer is right; your instructor can see it and regrade it."


# Units a student reads for the declared dimensions; others are the SI unit of the dimension.
_UNIT_NAMES = {"angle": "rad", "angular_velocity": "rad/s", "angular_acceleration": "rad/s²", "dimensionless": "",
               "kg·m/s²": "N", "kg·m²/s²": "J", "kg·m²/s³": "W", "1": ""}


def _unit(dimension: Any) -> str:
    if not isinstance(dimension, str) or not dimension:
        return ""
    if dimension in _UNIT_NAMES:
        return _UNIT_NAMES[dimension]
    try:
        si = parse_dimension(dimension).unit()
    except (ValueError, KeyError):
        return ""
    return _UNIT_NAMES.get(si, si)


def _point(example: dict[str, Any], reference: dict[str, Any]) -> dict[str, Any]:
    """Where the student's answer fails, with the names as math and units: never the reference's value."""
    variables = reference.get("variables") or {}
    values = []
    for name, value in example["values"].items():
        spec = variables.get(name) if isinstance(variables.get(name), dict) else {}
        values.append({"name": name, "latex": latex_name(name), "value": _short(value),
                       "unit": _unit(spec.get("dimension"))})
    answer = example.get("answer")
    kind = "undefined" if answer == "undefined" else "reference_undefined" \
        if example.get("reference") == "undefined" else "differ"
    if reference.get("kind") == "equation" and kind == "differ":
        # An equation's "value" is its residual (one per equation), a number nobody wrote: say where only.
        return {"values": values, "answer": None, "unit": "", "kind": "equation"}
    unit = "" if reference.get("kind") == "equation" else _unit(reference.get("dimension"))
    return {"values": values, "answer": None if answer is None or kind == "undefined" else _short(answer),
            "unit": unit, "kind": kind}


def _short(value: Any) -> Any:
    """4 significant digits for a float; other values as they are."""
    return f"{value:.4g}" if isinstance(value, float) else value
