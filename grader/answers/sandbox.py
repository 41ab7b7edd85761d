"""The checker in a `grader.sandbox.Sandbox` child, and what each way a run can end means for a verdict.

`SandboxedChecker.run(request, budget_s)` always returns ``Verdict.to_json()``, whatever the
request or the child does:

- ``ok``: the checker's own verdict (``check_request`` never raises).
- ``timeout``: ``invalid`` with ``budget_exceeded: true``; the answer took too long.
- ``out_of_memory``: ``invalid``; the answer needed more memory than a check may use.
- ``crashed`` while starting (or a reply that is not a verdict): ``invalid`` with
  ``checker_failure: true``, so the grading queue retries instead of grading the student on it.
- ``crashed`` during the check: ``invalid`` without ``checker_failure``; the answer is what made it
  crash, and trying it again would crash again.

The grading worker, ``POST /check`` and ``grader check --jsonl`` all go through it.
"""

from __future__ import annotations

from typing import Any

from grader.answers.verdict import VERDICTS, Verdict
from grader.sandbox import DEFAULT_MEMORY_MB, Outcome, Sandbox

__all__ = ["SandboxedChecker", "verdict_of", "CHECK_HANDLER", "DEFAULT_BUDGET_S", "DEFAULT_MEMORY_MB"]

CHECK_HANDLER = "grader.answers.checker:check_request"
DEFAULT_BUDGET_S = 2.0


def verdict_of(outcome: Outcome, text: str = "") -> dict[str, Any]:
    """The verdict JSON a sandbox `Outcome` stands for (``text``: the answer, for ``parsed``).

    Examples
    --------
    >>> from grader.sandbox import Outcome
    >>> v = verdict_of(Outcome("timeout", detail="stopped after 2 s"), "x^x^x")
    >>> v["verdict"], v["budget_exceeded"], v["parsed"]["text"]
    ('invalid', True, 'x^x^x')
    >>> verdict_of(Outcome("crashed", during_start=True))["checker_failure"]
    True
    """
    if outcome.ok:
        reply = outcome.reply
        if isinstance(reply, dict) and reply.get("verdict") in VERDICTS:
            return reply
        return Verdict.invalid("the checker returned something that is not a verdict", text,
                               checker_failure=True, ms=outcome.ms).to_json()
    if outcome.status == "timeout":
        return Verdict.invalid(f"budget exceeded: the check was stopped ({outcome.detail})", text,
                               budget_exceeded=True, ms=outcome.ms).to_json()
    if outcome.status == "out_of_memory":
        return Verdict.invalid("the check was stopped: it exceeded the memory limit", text, ms=outcome.ms).to_json()
    if outcome.during_start:
        return Verdict.invalid(f"checker unavailable: {outcome.detail}", text, checker_failure=True,
                               ms=outcome.ms).to_json()
    return Verdict.invalid("the check was stopped: the checker crashed on this answer", text, ms=outcome.ms).to_json()


class SandboxedChecker:
    """``check_request`` in its own sandbox child: a check that can always be stopped.

    Parameters
    ----------
    budget_s : float
        Default wall-clock budget of one check (a request's ``budget_s`` overrides it).
    memory_mb : int
        Address-space cap of the child, in MiB.
    handler : str
        ``"module:function"`` run in the child; tests substitute a misbehaving one.

    Examples
    --------
    >>> with SandboxedChecker(budget_s=5.0) as checker:
    ...     checker.run({"reference": "m*g", "answer": "g m",
    ...                  "variables": {"m": {"dimension": "mass", "domain": "positive"},
    ...                                "g": {"dimension": "acceleration", "domain": "positive"}}})["verdict"]
    'equivalent'
    """

    def __init__(self, budget_s: float = DEFAULT_BUDGET_S, memory_mb: int = DEFAULT_MEMORY_MB,
                 handler: str = CHECK_HANDLER):
        self.budget_s = budget_s
        self._box = Sandbox(handler, budget_s=budget_s, memory_mb=memory_mb)

    @property
    def restarts(self) -> int:
        return self._box.restarts

    @property
    def pid(self) -> int | None:
        return self._box.pid

    def start(self) -> "SandboxedChecker":
        self._box.start()
        return self

    def close(self) -> None:
        self._box.close()

    def __enter__(self) -> "SandboxedChecker":
        return self.start()

    def __exit__(self, *exc) -> None:
        self.close()

    def run(self, request: Any, budget_s: float | None = None) -> dict[str, Any]:
        """Check one request; always returns a verdict dict, whatever the request does.

        Parameters
        ----------
        request : dict
            ``{"reference", "answer", "variables", "kind"?, "feedback"?, "state"?, "budget_s"?}``.
        budget_s : float, optional
            Wall-clock budget (default: the request's ``budget_s``, else the checker's).
        """
        if not isinstance(request, dict):
            return Verdict.invalid("malformed request: expected a JSON object").to_json()
        text = request.get("answer")
        text = text if isinstance(text, str) else ""
        budget = budget_s if budget_s is not None else request.get("budget_s")
        try:
            budget = float(budget if budget is not None else self.budget_s)
        except (TypeError, ValueError):
            budget = self.budget_s
        if not budget == budget or budget <= 0:  # NaN or nonsense: the default, not an error
            budget = self.budget_s
        budget = min(max(budget, 0.05), 600.0)
        try:
            outcome = self._box.run(dict(request, budget_s=budget), budget)
        except (TypeError, ValueError):
            return Verdict.invalid("malformed request: not JSON data", text).to_json()
        return verdict_of(outcome, text)
