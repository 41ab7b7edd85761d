"""Grading one claimed task with a sandboxed checker, and the score a verdict is worth.

A *checker* has ``run(request, budget_s) -> Verdict.to_json()`` and ``close()``: in production a
:class:`grader.answers.sandbox.SandboxedChecker`, a long-lived child process under a hard wall-clock
and memory limit, so a runaway check is killed there, not here; it turns every way the child's run
can end into a verdict. Each worker owns one.
"""

from __future__ import annotations

import queue
import threading
from contextlib import contextmanager
from typing import Any, Callable, Iterator, Protocol

from grader.answers.reference import ReferenceAnswer, ReferenceAnswerError
from grader.answers.sandbox import DEFAULT_BUDGET_S, SandboxedChecker
from grader.answers.verdict import points
from grader.jobs.queue import Task

__all__ = ["CHECK_BUDGET_S", "Checker", "CheckerFailure", "CheckerPool", "CheckersBusy", "check_task", "check_request", "sandbox_checker", "score"]

CHECK_BUDGET_S = DEFAULT_BUDGET_S


class Checker(Protocol):
    def run(self, request: dict[str, Any], budget_s: float | None = None) -> dict[str, Any]: ...

    def close(self) -> None: ...


def sandbox_checker() -> Checker:
    """A checker backed by its own sandbox child (the production checker)."""
    return SandboxedChecker(budget_s=CHECK_BUDGET_S)


def check_request(reference: dict[str, Any], text: str, values: dict[str, Any] | None = None) -> dict[str, Any]:
    """The checker request for ``text`` against a stored reference answer.

    ``values``: the student's parameter values of a randomised problem (used by numeric answers;
    None: the problem's fixed values and preview draw, `grader.answers.randomised`).

    The stored JSON is read through the contract, `grader.answers.reference.ReferenceAnswer`;
    raises :class:`grader.answers.reference.ReferenceAnswerError` when it breaks it.
    """
    return ReferenceAnswer.from_json(reference).request(text, values)


class CheckerFailure(RuntimeError):
    """The checker itself failed (it could not start, kept dying, answered garbage)."""


def check_task(checker: Checker, task: Task, *, budget_s: float = CHECK_BUDGET_S) -> dict[str, Any]:
    """Check the task's answer text against its stored reference; returns ``Verdict.to_json()``.

    Raises :class:`CheckerFailure` when the checker, not the answer, failed: that is no grade, so
    the worker gives the task back to the queue rather than recording it.
    """
    try:
        request = check_request(task.reference, task.text, task.values)
    except ReferenceAnswerError as error:  # a stored reference that breaks the contract: no grade
        raise CheckerFailure(str(error)) from None
    result = checker.run(request, budget_s)
    if result.get("checker_failure"):
        raise CheckerFailure(result.get("reason", "checker failure"))
    return result


def score(result: dict[str, Any]) -> float:
    """The points a checked answer earns: 1 for an equivalent answer, the instructor's partial credit
    for a wrong answer that matched a feedback entry with a ``score``, else 0.

    Examples
    --------
    >>> score({"verdict": "equivalent"}), score({"verdict": "not_equivalent", "score": 0.5})
    (1.0, 0.5)
    >>> score({"verdict": "invalid"})
    0.0
    """
    return points(result)


class CheckersBusy(RuntimeError):
    """Every checker of a pool stayed busy for the whole wait."""


class CheckerPool:
    """At most ``size`` checkers (sandbox children), each lent to one caller at a time.

    Stateless ``POST /check`` requests borrow from it; a checker that raised is closed rather than
    lent again.
    """

    def __init__(self, size: int, factory: Callable[[], Checker] = sandbox_checker):
        self.factory = factory
        self._slots = threading.BoundedSemaphore(size)
        self._idle: queue.LifoQueue[Checker] = queue.LifoQueue()

    @contextmanager
    def borrow(self, timeout: float) -> Iterator[Checker]:
        if not self._slots.acquire(timeout=timeout):
            raise CheckersBusy(f"no checker became free within {timeout:g} s")
        try:
            try:
                checker = self._idle.get_nowait()
            except queue.Empty:
                checker = self.factory()
            try:
                yield checker
            except BaseException:
                checker.close()
                raise
            self._idle.put(checker)
        finally:
            self._slots.release()

    def close(self) -> None:
        while True:
            try:
                self._idle.get_nowait().close()
            except queue.Empty:
                return
