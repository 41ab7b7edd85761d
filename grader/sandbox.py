"""Run a trusted handler in a long-lived child process under a hard wall clock and memory cap.

The child (``python -m grader.sandbox``) caps its own address space with ``RLIMIT_AS``, imports
its handler once, then answers one JSON request per line on stdin with one JSON line on stdout.
The parent gives each request ``budget_s`` (plus a short grace) of wall-clock time; a child that
overruns is killed with SIGKILL (hostile input cannot catch or delay that) and a replacement is
started at once.

The sandbox knows nothing about answers or scenes: every run ends in one neutral `Outcome`,
``ok`` (with the handler's reply), ``timeout``, ``crashed`` or ``out_of_memory``. Its users say
what that means for them: `grader.answers.sandbox` turns outcomes into verdicts,
`grader.jobs.derivation` into scene errors. This module imports nothing from ``grader``, so any
layer may use it without breaking the one-way data flow.
"""

from __future__ import annotations

import importlib
import json
import os
import select
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from typing import Any, Callable

__all__ = ["Sandbox", "Outcome", "OUTCOMES", "DEFAULT_MEMORY_MB"]

OUTCOMES = ("ok", "timeout", "crashed", "out_of_memory")
DEFAULT_MEMORY_MB = 1024
# The handler's own cooperative deadline (if it has one) fires first; the kill comes this much later.
GRACE_S = 0.3
START_TIMEOUT_S = 60.0
_EOF = b"<eof>"  # sentinel of `Sandbox._readline` (compared by identity)


@dataclass(frozen=True)
class Outcome:
    """How one request to a sandboxed handler ended.

    Attributes
    ----------
    status : str
        ``"ok"``: the handler replied (``reply``). ``"timeout"``: it overran its budget and was
        killed. ``"out_of_memory"``: it hit the memory cap. ``"crashed"``: the child died, never
        started, answered garbage, or the handler raised.
    reply : Any
        The handler's JSON reply when ``status == "ok"``, else None.
    ms : float
        Wall-clock time of the request, as the parent saw it.
    detail : str
        For people and logs: what happened (never shown to students as is).
    during_start : bool
        True when the child failed before it could take the request (the request is not to blame).

    Examples
    --------
    >>> Outcome("timeout", detail="stopped after 2 s").ok
    False
    """

    status: str
    reply: Any = None
    ms: float = 0.0
    detail: str = ""
    during_start: bool = False

    def __post_init__(self) -> None:
        if self.status not in OUTCOMES:
            raise ValueError(f"outcome {self.status!r} is not one of {OUTCOMES}")

    @property
    def ok(self) -> bool:
        return self.status == "ok"


class Sandbox:
    """A handler in a child process that can always be stopped.

    Parameters
    ----------
    handler : str
        ``"module:function"`` the child calls with each decoded request; the function returns
        JSON-serialisable data. Trusted code chosen by the caller, never by a request.
    budget_s : float
        Default wall-clock budget of one request.
    memory_mb : int
        Address-space cap of the child, in MiB.

    Examples
    --------
    >>> with Sandbox("json:dumps", budget_s=5.0) as box:
    ...     outcome = box.run([1, 2])
    >>> outcome.status, outcome.reply
    ('ok', '[1, 2]')
    """

    def __init__(self, handler: str, budget_s: float = 2.0, memory_mb: int = DEFAULT_MEMORY_MB):
        self.handler = handler
        self.budget_s = budget_s
        self.memory_mb = memory_mb
        self.restarts = 0
        self._child: subprocess.Popen | None = None
        self._ready = False
        self._buffer = b""
        self._lock = threading.Lock()

    # -- lifecycle ---------------------------------------------------------------------------

    def _spawn(self) -> None:
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1",
                   PYTHONUNBUFFERED="1")
        self._child = subprocess.Popen(
            [sys.executable, "-m", "grader.sandbox", "--handler", self.handler,
             "--memory-mb", str(self.memory_mb)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            env=env,
            start_new_session=True,
        )
        self._ready = False
        self._buffer = b""

    def _ensure_ready(self) -> str | None:
        """Start the child if needed; the reason it could not start, else None."""
        if self._child is None or self._child.poll() is not None:
            try:
                self._spawn()
            except OSError as error:
                return f"the sandbox child could not be started ({error})"
        if not self._ready:
            line = self._readline(time.monotonic() + START_TIMEOUT_S)
            if line is None or line is _EOF or _decode(line) != {"ready": True}:
                self._kill()
                return "the sandbox child died or misbehaved while starting"
            self._ready = True
        return None

    def start(self) -> "Sandbox":
        """Start the child now (otherwise the first request starts it); a failure shows in `run`."""
        with self._lock:
            self._ensure_ready()
        return self

    def _kill(self) -> None:
        child, self._child = self._child, None
        self._ready = False
        if child is None:
            return
        try:
            os.killpg(child.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        try:
            child.kill()
        except ProcessLookupError:
            pass
        child.wait()
        for stream in (child.stdin, child.stdout):
            try:
                stream.close()
            except OSError:
                pass

    def _restart(self) -> None:
        """Kill the child and start a replacement now, so it is warm for the next request."""
        self._kill()
        self.restarts += 1
        try:
            self._spawn()
        except OSError:
            pass  # the next request tries again and reports it

    def close(self) -> None:
        """Stop the child."""
        with self._lock:
            self._kill()

    def __enter__(self) -> "Sandbox":
        return self.start()

    def __exit__(self, *exc) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self._kill()
        except Exception:
            pass

    @property
    def pid(self) -> int | None:
        """The child's process id (None before it starts)."""
        return self._child.pid if self._child is not None else None

    # -- requests ----------------------------------------------------------------------------

    def _readline(self, deadline: float) -> bytes | None:
        """One line from the child; None at the deadline; `_EOF` when the child has gone."""
        assert self._child is not None and self._child.stdout is not None
        fd = self._child.stdout.fileno()
        while b"\n" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            ready, _, _ = select.select([fd], [], [], left)
            if not ready:
                return None
            chunk = os.read(fd, 1 << 16)
            if not chunk:
                return _EOF
            self._buffer += chunk
        line, self._buffer = self._buffer.split(b"\n", 1)
        return line

    def run(self, request: Any, budget_s: float | None = None) -> Outcome:
        """Send one JSON request to the handler; returns an `Outcome` whatever the child does.

        Parameters
        ----------
        request : JSON data
            What the handler is called with. Text may hold anything, lone surrogates included.
        budget_s : float, optional
            Wall-clock budget (default: the sandbox's), clamped to [0.05, 600] s.

        Raises
        ------
        TypeError, ValueError
            When ``request`` is not JSON data (a bug of the caller, not something a user sent).
        """
        started = time.monotonic()

        def outcome(status: str, reply: Any = None, detail: str = "", during_start: bool = False) -> Outcome:
            return Outcome(status, reply, (time.monotonic() - started) * 1000, detail, during_start)

        try:
            budget = float(budget_s if budget_s is not None else self.budget_s)
        except (TypeError, ValueError):
            budget = self.budget_s
        budget = min(max(budget, 0.05), 600.0) if budget == budget else self.budget_s
        # ASCII JSON: a lone surrogate in a text travels as its \u escape, not as bad UTF-8.
        data = (json.dumps(request) + "\n").encode()  # TypeError/ValueError: the caller's bug
        with self._lock:
            # A child that died after its last reply (memory cap) shows only when we next talk
            # to it: then the request was never read, and one retry on a fresh child is fair.
            for attempt in range(2):
                problem = self._ensure_ready()
                if problem is not None:
                    return outcome("crashed", detail=problem, during_start=True)
                sent = time.monotonic()
                try:
                    assert self._child is not None and self._child.stdin is not None
                    self._child.stdin.write(data)
                    self._child.stdin.flush()
                except OSError:
                    self._restart()
                    continue
                line = self._readline(sent + budget + GRACE_S)
                if line is None:
                    self._restart()
                    return outcome("timeout", detail=f"stopped after {budget:g} s")
                if line is _EOF:
                    code = _exit_code(self._child)
                    self._restart()
                    if attempt == 0 and time.monotonic() - sent < 0.05:
                        continue
                    return outcome("crashed", detail=f"the child exited ({_exit_text(code)})")
                message = _decode(line)
                if not isinstance(message, dict):
                    self._restart()
                    return outcome("crashed", detail="the child answered garbage and was restarted")
                if "reply" in message:
                    return outcome("ok", message["reply"])
                if message.get("failure") == "out_of_memory":
                    self._restart()  # the child exits after a MemoryError; be warm for the next one
                    return outcome("out_of_memory", detail=f"over the {self.memory_mb} MiB memory cap")
                return outcome("crashed", detail=str(message.get("detail") or "the handler failed"))
            return outcome("crashed", detail="the sandbox child keeps dying", during_start=True)


def _decode(line: bytes) -> Any:
    try:
        return json.loads(line)
    except ValueError:
        return None


def _exit_code(child: subprocess.Popen | None) -> int | None:
    try:
        return child.wait(timeout=1.0) if child is not None else None
    except subprocess.TimeoutExpired:
        return None  # it closed its output but lingers: `_restart` kills it


def _exit_text(code: int | None) -> str:
    if code is None:
        return "unknown status"
    if code < 0:
        try:
            return f"signal {signal.Signals(-code).name}"
        except ValueError:
            return f"signal {-code}"
    return f"code {code}"


# -- the child ---------------------------------------------------------------------------------


def _limit_memory(memory_mb: int) -> None:
    import resource

    cap = memory_mb * 1024 * 1024
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def _load(target: str) -> Callable[[Any], Any]:
    module, _, name = target.partition(":")
    return getattr(importlib.import_module(module), name)


def _child_main(handler: str, memory_mb: int) -> int:
    # Replies go to the real stdout; anything else printed goes to stderr and cannot corrupt them.
    out = os.fdopen(os.dup(1), "w", buffering=1)
    os.dup2(2, 1)
    _limit_memory(memory_mb)
    function = _load(handler)
    out.write(json.dumps({"ready": True}) + "\n")
    for line in sys.stdin:
        try:
            request = json.loads(line)
        except ValueError:
            request = None
        try:
            message = {"reply": function(request)}
            text = json.dumps(message)
        except MemoryError:
            out.write(json.dumps({"failure": "out_of_memory"}) + "\n")
            return 3  # the heap may be in a bad state: let the parent start a fresh child
        except Exception as error:  # the handler should not raise; never let the child die of it
            text = json.dumps({"failure": "crashed", "detail": f"the handler raised {type(error).__name__}"})
        out.write(text + "\n")
    return 0


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="sandboxed handler child (started by grader.sandbox.Sandbox)")
    parser.add_argument("--handler", required=True)
    parser.add_argument("--memory-mb", type=int, default=DEFAULT_MEMORY_MB)
    args = parser.parse_args()
    sys.exit(_child_main(args.handler, args.memory_mb))
