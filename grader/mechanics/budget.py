"""Time budgets for the engine's symbolic steps.

A symbolic solve or simplification can take minutes on an input where an equivalent one is
instant (a cubic in sin θ that is trivial in S = sin θ). Every such step therefore runs under a
budget and has a cheaper fallback; the whole derivation runs under an overall budget, and when it
runs out the instructor is told which step and which answer were being worked on.

Budgets interrupt with ``SIGALRM`` (sympy is pure Python, so the signal lands between bytecodes).
Signals only reach the main thread; elsewhere (a web worker thread) a step is not interrupted and
the caller's own limit (a killed child process) applies.

Examples
--------
>>> def spin():
...     while True:
...         pass
>>> attempt(spin, 0.05, fallback=lambda: "fallback")
'fallback'
>>> attempt(lambda: "quick", 1.0, fallback=lambda: "fallback")
'quick'
"""

from __future__ import annotations

import gc
import signal
import threading
from contextlib import contextmanager
from typing import Callable, TypeVar

__all__ = ["BudgetExceeded", "attempt", "overall_budget", "step"]

T = TypeVar("T")


class _Timeout(BaseException):
    """Raised by the alarm handler; BaseException so that ``except Exception`` in sympy won't eat it."""

    def __init__(self, token: object):
        super().__init__("budget exceeded")
        self.token = token
        self.where = current_step()  # captured now: the step's context unwinds on the way out


class BudgetExceeded(RuntimeError):
    """The overall budget of a derivation ran out; ``step`` and ``answer`` say where."""

    def __init__(self, budget_s: float, step: str, answer: str | None):
        self.budget_s, self.step, self.answer = budget_s, step, answer
        where = f" for the answer '{answer}'" if answer else ""
        super().__init__(f"the derivation ran out of its {budget_s:g} s budget while {step}{where}")


_state = threading.local()
_collecting = [False]  # inside a garbage collection (see _alarm's handler)


def _track_collection(phase: str, _info: dict) -> None:
    _collecting[0] = phase == "start"


gc.callbacks.append(_track_collection)


def _exception_would_be_lost(frame) -> bool:
    """Whether an exception raised now would be lost (reported as unraisable) instead of unwinding.

    That is so inside a garbage collection and inside a finaliser (``__del__``). The flag covers the
    collection itself; the frames cover the other collection callbacks, which may run before ours
    at the start or after it at the stop (hypothesis registers one of its own), and finalisers run
    by a reference count dropping to zero.
    """
    if _collecting[0]:
        return True
    callbacks = {getattr(callback, "__code__", None) for callback in gc.callbacks}
    while frame is not None:
        if frame.f_code in callbacks or frame.f_code.co_name == "__del__":
            return True
        frame = frame.f_back
    return False


def _can_interrupt() -> bool:
    return threading.current_thread() is threading.main_thread() and hasattr(signal, "setitimer")


@contextmanager
def _alarm(seconds: float, token: object, cpu: bool = False):
    """Raise ``_Timeout(token)`` after ``seconds`` unless an outer alarm of the same clock is due first.

    ``cpu``: count this process's CPU time (ITIMER_VIRTUAL) rather than wall-clock time, so that
    a budget that decides *what* the engine computes does not depend on how loaded the machine is.
    """
    signum, timer = (signal.SIGVTALRM, signal.ITIMER_VIRTUAL) if cpu else (signal.SIGALRM, signal.ITIMER_REAL)
    previous_handler = signal.getsignal(signum)
    remaining, _ = signal.getitimer(timer)
    if remaining and remaining <= seconds:
        yield  # the outer budget is shorter: let it fire
        return

    armed = [True]

    def handler(signum, frame):
        if not armed[0]:
            return  # the step has finished: a late tick changes nothing
        if _exception_would_be_lost(frame):
            # come back right after the collection or the finaliser instead
            signal.setitimer(timer, 0.005)
            return
        # Should this exception be swallowed anyway (a weakref callback that runs now), fire again shortly.
        signal.setitimer(timer, 0.05)
        raise _Timeout(token)

    signal.signal(signum, handler)
    signal.setitimer(timer, seconds)
    try:
        yield
    finally:
        armed[0] = False
        left, _ = signal.getitimer(timer)
        signal.setitimer(timer, 0)
        signal.signal(signum, previous_handler)
        if remaining:
            # Give the outer budget back what is left of it.
            used = seconds - left
            signal.setitimer(timer, max(remaining - used, 1e-3))


def attempt(function: Callable[[], T], seconds: float, fallback: Callable[[], T]) -> T:
    """``function()`` if it finishes within ``seconds`` of CPU time, else ``fallback()``.

    CPU time, not wall-clock: what the engine derives must not depend on the machine's load.
    """
    if not _can_interrupt():
        return function()
    token = object()
    try:
        with _alarm(seconds, token, cpu=True):
            return function()
    except _Timeout as exc:
        if exc.token is not token:
            raise
    return fallback()


@contextmanager
def step(description: str, answer: str | None = None):
    """Name the step being worked on, for the message when the overall budget runs out.

    >>> with step("solving the equations of motion"):
    ...     current_step()
    ('solving the equations of motion', None)
    """
    previous = getattr(_state, "step", None)
    _state.step = (description, answer)
    try:
        yield
    finally:
        _state.step = previous


def current_step() -> tuple[str, str | None] | None:
    return getattr(_state, "step", None)


@contextmanager
def overall_budget(seconds: float | None):
    """Raise :class:`BudgetExceeded` naming the current step when ``seconds`` run out.

    >>> import time
    >>> try:
    ...     with overall_budget(0.05), step("simplifying", "tension"):
    ...         time.sleep(5)
    ... except BudgetExceeded as exc:
    ...     print(exc)
    the derivation ran out of its 0.05 s budget while simplifying for the answer 'tension'
    """
    if seconds is None or not _can_interrupt():
        yield
        return
    token = object()
    try:
        with _alarm(seconds, token):
            yield
    except _Timeout as exc:
        if exc.token is not token:
            raise
        where = exc.where or ("deriving", None)
        raise BudgetExceeded(seconds, *where) from None
