"""Run checks in a long-lived child process under a hard wall clock and memory cap.

The child (``python -m grader.answers.sandbox``) caps its own address space with ``RLIMIT_AS``,
imports the checker once, then answers one JSON request per line on stdin with one JSON line on
stdout. The parent gives each request ``budget_s`` (plus a short grace) of wall-clock time; a
child that overruns is killed with SIGKILL (a hostile input cannot catch or delay that), a
replacement is started at once, and the caller gets an ``invalid`` verdict with
``budget_exceeded: true``. A child that dies (memory cap, crash) is replaced the same way.

The grading worker and ``grader check --jsonl`` both go through `Sandbox`.
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
from typing import Any, Callable

from grader.answers.verdict import Verdict

__all__ = ["Sandbox", "DEFAULT_HANDLER", "DEFAULT_BUDGET_S", "DEFAULT_MEMORY_MB"]

DEFAULT_HANDLER = "grader.answers.checker:check_request"
DEFAULT_BUDGET_S = 2.0
DEFAULT_MEMORY_MB = 1024
# The child's own cooperative deadline fires first; the kill comes this much later.
GRACE_S = 0.3
START_TIMEOUT_S = 60.0
_EOF = b"<eof>"  # sentinel of `Sandbox._readline` (compared by identity)


class Sandbox:
    """A checker in a child process that can always be stopped.

    Parameters
    ----------
    budget_s : float
        Default wall-clock budget of one request (the request's ``budget_s`` overrides it).
    memory_mb : int
        Address-space cap of the child, in MiB.
    handler : str
        ``"module:function"`` the child calls with each request dict; the function returns a
        JSON-serialisable dict. Trusted code chosen by the caller, never by a request.

    Examples
    --------
    >>> with Sandbox(budget_s=1.0) as box:  # doctest: +SKIP
    ...     box.run({"reference": "m*g", "answer": "g*m",
    ...              "variables": {"m": {"dimension": "mass", "domain": "positive"},
    ...                            "g": {"dimension": "acceleration", "domain": "positive"}}})["verdict"]
    'equivalent'
    """

    def __init__(
        self,
        budget_s: float = DEFAULT_BUDGET_S,
        memory_mb: int = DEFAULT_MEMORY_MB,
        handler: str = DEFAULT_HANDLER,
    ):
        self.budget_s = budget_s
        self.memory_mb = memory_mb
        self.handler = handler
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
            [sys.executable, "-m", "grader.answers.sandbox", "--handler", self.handler,
             "--memory-mb", str(self.memory_mb)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            env=env,
            start_new_session=True,
        )
        self._ready = False
        self._buffer = b""

    def _ensure_ready(self) -> None:
        if self._child is None or self._child.poll() is not None:
            self._spawn()
        if not self._ready:
            line = self._readline(time.monotonic() + START_TIMEOUT_S)
            if line is None or json.loads(line).get("ready") is not True:
                self._kill()
                raise RuntimeError("the sandboxed checker did not start")
            self._ready = True

    def start(self) -> "Sandbox":
        """Start the child now (otherwise the first request starts it)."""
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

    def run(self, request: dict[str, Any], budget_s: float | None = None) -> dict[str, Any]:
        """Check one request; always returns a verdict dict, whatever the request does.

        Parameters
        ----------
        request : dict
            ``{"reference", "answer", "variables", "kind", "feedback"?, "state"?}``.
        budget_s : float, optional
            Wall-clock budget (default: the request's ``budget_s``, else the sandbox's).
        """
        if not isinstance(request, dict):
            return Verdict.invalid("the request must be a JSON object").to_json()
        try:
            budget = float(budget_s or request.get("budget_s") or self.budget_s)
        except (TypeError, ValueError):
            budget = self.budget_s
        budget = min(max(budget, 0.05), 600.0)
        text = request.get("answer", "")
        text = text if isinstance(text, str) else ""
        try:
            data = (json.dumps(dict(request, budget_s=budget)) + "\n").encode()
        except (TypeError, ValueError):
            return Verdict.invalid("the request is not JSON-serialisable", text).to_json()
        with self._lock:
            started = time.monotonic()
            # A child that died after its last reply (memory cap) shows only when we next talk
            # to it: then the request was never read, and one retry on a fresh child is fair.
            for attempt in range(2):
                try:
                    self._ensure_ready()
                except RuntimeError as error:
                    return Verdict.invalid(f"checker unavailable: {error}", text, checker_failure=True).to_json()
                sent = time.monotonic()
                try:
                    assert self._child is not None and self._child.stdin is not None
                    self._child.stdin.write(data)
                    self._child.stdin.flush()
                except (BrokenPipeError, OSError):
                    self._restart()
                    continue
                line = self._readline(sent + budget + GRACE_S)
                elapsed_ms = (time.monotonic() - started) * 1000
                if line is None:
                    self._restart()
                    return Verdict.invalid(
                        f"budget exceeded: the check took longer than {budget:g} s and was stopped",
                        text, budget_exceeded=True, ms=elapsed_ms,
                    ).to_json()
                if line is _EOF:
                    self._restart()
                    if attempt == 0 and time.monotonic() - sent < 0.05:
                        continue
                    return Verdict.invalid(
                        "the check was stopped: it exceeded the memory limit or crashed", text, ms=elapsed_ms
                    ).to_json()
                try:
                    return json.loads(line)
                except ValueError:
                    self._restart()
                    return Verdict.invalid("the checker returned garbage; it has been restarted", text,
                                           checker_failure=True).to_json()
            return Verdict.invalid("the checker process keeps dying", text, checker_failure=True).to_json()

    def _restart(self) -> None:
        """Kill the child and start a replacement now, so it is warm for the next request."""
        self._kill()
        self.restarts += 1
        self._spawn()


# -- the child ---------------------------------------------------------------------------------


def _limit_memory(memory_mb: int) -> None:
    import resource

    cap = memory_mb * 1024 * 1024
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def _load(target: str) -> Callable[[dict], dict]:
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
            reply = function(request)
        except MemoryError:
            reply = Verdict.invalid("memory limit exceeded").to_json()
            out.write(json.dumps(reply) + "\n")
            return 3  # the heap may be in a bad state: let the parent start a fresh child
        except Exception as error:  # the handler should not raise; never let the child die of it
            reply = Verdict.invalid(f"internal error: {type(error).__name__}", checker_failure=True).to_json()
        out.write(json.dumps(reply) + "\n")
    return 0


def _test_runaway(request: dict) -> dict:
    """Test-only handler: misbehaves as asked (``{"sleep": s}`` or ``{"allocate_mb": n}``)."""
    if request.get("sleep"):
        time.sleep(float(request["sleep"]))
    if request.get("allocate_mb"):
        hog = bytearray(int(request["allocate_mb"]) * 1024 * 1024)
        return {"verdict": "invalid", "reason": f"allocated {len(hog)} bytes"}
    if request.get("spin"):
        while True:
            pass
    return {"verdict": "equivalent", "reason": "ok", "pid": os.getpid()}


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="sandboxed checker child (started by Sandbox)")
    parser.add_argument("--handler", default=DEFAULT_HANDLER)
    parser.add_argument("--memory-mb", type=int, default=DEFAULT_MEMORY_MB)
    args = parser.parse_args()
    sys.exit(_child_main(args.handler, args.memory_mb))
