"""The verdict on one answer, as stored by the service and printed by ``grader check --jsonl``.

This module imports nothing heavy, so the sandbox's parent process can build a verdict for a
child it had to kill without loading sympy.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = ["Verdict", "VERDICTS", "CERTAINTIES", "points"]

VERDICTS = ("equivalent", "not_equivalent", "invalid")
CERTAINTIES = ("proved", "numeric", "none")


@dataclass
class Verdict:
    """What the checker says about one answer.

    Attributes
    ----------
    verdict : str
        ``"equivalent"``, ``"not_equivalent"`` or ``"invalid"`` (unreadable, or not decided).
    certainty : str
        ``"proved"``: a symbolic identity, a dimension mismatch, or a counterexample certified in
        ball arithmetic. ``"numeric"``: agreement at ``evidence["points"]`` sample points to
        ``evidence["digits"]`` digits. ``"none"``: no verdict on the mathematics.
    reason : str
        One sentence, for people.
    parsed : dict
        ``{"text", "latex", "notes"}``: how the answer was read.
    counterexample : dict or None
        For ``not_equivalent``: ``{"values": {name: value}, "answer": ..., "reference": ...}``.
    feedback : list of dict
        ``{"code", "message"}`` items: instructor messages and detected slips.
    ms : float
        Wall-clock time of the check.
    evidence : dict
        How the verdict was reached (method, points, digits).
    budget_exceeded : bool
        True when the time budget ran out (the check was stopped or its child process killed).
    score : float or None
        Partial credit in [0, 1] given by the instructor's feedback entry the wrong answer matched
        (its ``score``); None otherwise (``grader.jobs.grading.score`` then scores by the verdict).

    Examples
    --------
    >>> v = Verdict("invalid", "none", "budget exceeded", budget_exceeded=True)
    >>> v.to_json()["verdict"], v.to_json()["budget_exceeded"]
    ('invalid', True)
    """

    verdict: str
    certainty: str
    reason: str
    parsed: dict = field(default_factory=lambda: {"text": "", "latex": "", "notes": []})
    counterexample: dict | None = None
    feedback: list = field(default_factory=list)
    ms: float = 0.0
    evidence: dict = field(default_factory=dict)
    budget_exceeded: bool = False
    # True when the checker itself failed (not the answer): the grading queue retries such checks
    # instead of storing them as the student's grade.
    checker_failure: bool = False
    # Partial credit: the score of the instructor's feedback entry a wrong answer matched
    # (``[[answers.feedback]] score``); None when no such entry matched.
    score: float | None = None

    def __post_init__(self) -> None:
        if self.verdict not in VERDICTS:
            raise ValueError(f"verdict {self.verdict!r} is not one of {VERDICTS}")
        if self.certainty not in CERTAINTIES:
            raise ValueError(f"certainty {self.certainty!r} is not one of {CERTAINTIES}")

    @property
    def equivalent(self) -> bool:
        return self.verdict == "equivalent"

    def to_json(self) -> dict[str, Any]:
        """The JSON object of the ``grader check --jsonl`` contract."""
        return {
            "verdict": self.verdict,
            "certainty": self.certainty,
            "reason": self.reason,
            "parsed": self.parsed,
            "counterexample": self.counterexample,
            "feedback": self.feedback,
            "ms": round(self.ms, 3),
            "evidence": self.evidence,
            "budget_exceeded": self.budget_exceeded,
            **({"checker_failure": True} if self.checker_failure else {}),
            **({"score": self.score} if self.score is not None else {}),
        }

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> "Verdict":
        """The inverse of `to_json` (unknown keys are ignored).

        >>> Verdict.from_json(Verdict("equivalent", "proved", "identical").to_json()).certainty
        'proved'
        """
        keys = ("verdict", "certainty", "reason", "parsed", "counterexample", "feedback", "ms",
                "evidence", "budget_exceeded", "checker_failure", "score")
        return cls(**{k: data[k] for k in keys if k in data and (data[k] is not None or k == "counterexample")})

    @classmethod
    def invalid(cls, reason: str, text: str = "", **extra) -> "Verdict":
        """An ``invalid`` verdict for text that could not be checked."""
        return cls("invalid", "none", reason, parsed={"text": text, "latex": "", "notes": []}, **extra)


def points(result: dict[str, Any]) -> float:
    """The points a checked answer earns, from its verdict JSON: 1 for ``equivalent``; for a wrong
    answer the partial credit of the instructor's feedback entry it matched (``score``), else 0.

    The one rule for scoring an answer: the grading queue (`grader.jobs.grading.score`) and the
    question tests use it.

    Examples
    --------
    >>> points({"verdict": "equivalent"}), points({"verdict": "not_equivalent", "score": 0.5})
    (1.0, 0.5)
    >>> points({"verdict": "invalid", "score": 0.5})
    0.0
    """
    if result.get("verdict") == "equivalent":
        return 1.0
    partial = result.get("score")
    if result.get("verdict") == "not_equivalent" and isinstance(partial, (int, float)) and not isinstance(partial, bool):
        return min(max(float(partial), 0.0), 1.0)
    return 0.0
