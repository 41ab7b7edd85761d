"""Deriving uploaded scenes in a child process under a wall-clock and memory limit.

Scene files come from instructors over the web, so the engine runs them where a pathological
scene can only exhaust its own limits: a :class:`grader.sandbox.Sandbox` child (an
``RLIMIT_AS`` cap, killed with SIGKILL when it overruns its time) whose handler is
:func:`derive_request`. The child stays warm between uploads, so only the first pays for importing
sympy. The parent receives plain JSON and builds a :class:`grader.store.problems.DerivedProblem`.

Uploads are derived by the workers of :mod:`grader.jobs.derivation_workers`, each with its own
child from :func:`derivation_sandbox`; the shared child below serves ``grader serve``'s start-up
(loading ``problems/``) and the tests. The child lowers its own CPU priority, so a slow scene only
takes the processor time that checks and requests leave over.
"""

from __future__ import annotations

import hashlib
import logging
import math
import signal
import threading
import tomllib
import traceback
from pathlib import Path

from sqlalchemy import func, select
from sqlalchemy.orm import aliased

from grader.mechanics.budget import BudgetExceeded
from grader.sandbox import Sandbox
from grader.store.models import ProblemVersion
from grader.store.problems import DerivedProblem, save_problem

__all__ = ["DERIVE_MEMORY_MB", "DERIVE_TIMEOUT_S", "DerivationError", "SandboxUnavailable", "close_shared_sandboxes",
           "derivation_sandbox", "derive_request", "derive_source", "load_problem_files", "read_scene_id"]

log = logging.getLogger(__name__)

# Every textbook scene derives in a few seconds; a scene that needs more is refused, not waited for.
DERIVE_TIMEOUT_S = 20.0
DERIVE_MEMORY_MB = 2048
# The child's entry point, which first lowers its CPU priority (see grader.jobs.derivation_child).
HANDLER = "grader.jobs.derivation_child:derive_request"
# The child's own alarm fires this long after its budget, later than the parent's kill (see derive_request).
ORPHAN_MARGIN_S = 5

_sandboxes: dict[int, Sandbox] = {}  # one warm child per memory limit, made on first use
_sandboxes_lock = threading.Lock()


class DerivationError(ValueError):
    """A scene that cannot be derived: invalid, too slow, too big. The message is for the instructor."""


class SandboxUnavailable(RuntimeError):
    """The derivation child could not be started; the scene was not tried."""


def read_scene_id(source: str, filename: str = "upload.toml") -> str | None:
    """The scene's ``id``, read without the engine, so an upload can be refused before it is queued.

    Raises :class:`DerivationError` when ``source`` is not TOML at all; None when it has no string
    ``id`` (the derivation reports that, with the scene's other problems).

    Examples
    --------
    >>> read_scene_id('id = "yoyo"')
    'yoyo'
    >>> read_scene_id("id = ")
    Traceback (most recent call last):
    ...
    grader.jobs.derivation.DerivationError: upload.toml: not valid TOML: Invalid value (at end of document)
    """
    try:
        data = tomllib.loads(source)
    except tomllib.TOMLDecodeError as error:
        raise DerivationError(f"{filename}: not valid TOML: {error}") from None
    except RecursionError:  # tomllib recurses per level of [[[...]]] or {a={b=...}}
        raise DerivationError(f"{filename}: not valid TOML: nested too deeply") from None
    where = _holding_nul(data)
    if where is not None:
        # TOML's "\u0000" is a NUL, which no database column takes: refused here, not by the worker
        # after a derivation (which then failed as "interrupted").
        raise DerivationError(f"{filename}: {where} holds a NUL character (\\u0000), which is not text; remove it")
    slug = data.get("id")
    return slug if isinstance(slug, str) else None


def _holding_nul(data: dict) -> str | None:
    """The key path (``answers[0].prompt``) of the first key or string of ``data`` holding a NUL, or None.

    Examples
    --------
    >>> _holding_nul({"title": "Pendulum", "answers": [{"name": "T", "prompt": "The\\x00tension"}]})
    'answers[0].prompt'
    >>> _holding_nul({"variables": {"m\\x00": {"dimension": "mass"}}})
    'variables."m\\\\u0000"'
    """
    stack: list[tuple[str, object]] = [("", data)]  # a stack, not recursion: TOML nests deep
    while stack:
        where, value = stack.pop()
        if isinstance(value, str) and "\x00" in value:
            return where or "a value"
        if isinstance(value, dict):
            for key in value:
                if "\x00" in key:
                    return (f"{where}." if where else "") + '"' + key.replace("\x00", "\\u0000") + '"'
            stack.extend(reversed([(f"{where}.{key}" if where else key, item) for key, item in value.items()]))
        elif isinstance(value, list):
            stack.extend(reversed([(f"{where}[{index}]", item) for index, item in enumerate(value)]))
    return None


def derivation_sandbox(timeout_s: float = DERIVE_TIMEOUT_S, memory_mb: int = DERIVE_MEMORY_MB) -> Sandbox:
    """A sandbox child of its own for deriving scenes (started on its first request)."""
    return Sandbox(HANDLER, budget_s=timeout_s, memory_mb=memory_mb)


def derive_source(source: str, *, filename: str = "upload.toml", timeout_s: float = DERIVE_TIMEOUT_S,
                  memory_mb: int = DERIVE_MEMORY_MB, sandbox: Sandbox | None = None) -> DerivedProblem:
    """Parse and derive the scene ``source`` in a limited child; raises :class:`DerivationError`.

    ``sandbox`` is the child to use (a worker's own); by default a child shared by the process.
    """
    if sandbox is None:
        with _sandboxes_lock:
            sandbox = _sandboxes.get(memory_mb)
            if sandbox is None:
                sandbox = _sandboxes[memory_mb] = derivation_sandbox(timeout_s, memory_mb)
    ran = sandbox.run({"source": source, "filename": filename, "budget_s": timeout_s}, budget_s=timeout_s)
    if ran.during_start:
        # The child could not even start: not the scene's fault (a worker retries the job later).
        raise SandboxUnavailable(f"the derivation sandbox is unavailable: {ran.detail}")
    if ran.status == "timeout":
        raise DerivationError(f"{filename}: the derivation took longer than {timeout_s:g} s and was stopped")
    if ran.status == "out_of_memory":
        raise DerivationError(f"{filename}: the derivation was stopped: it needed more than {memory_mb} MB of memory")
    reply = ran.reply if ran.ok and isinstance(ran.reply, dict) else {}
    kind = reply.get("outcome")
    if kind == "ok":
        return DerivedProblem(source=source, **reply["problem"])
    if kind == "error":
        raise DerivationError(reply["message"])
    if kind == "internal":
        log.error("deriving %s failed inside the engine:\n%s", filename, reply["trace"])
    else:
        log.error("deriving %s: the sandbox child crashed: %s", filename, ran.detail)
    raise DerivationError(f"{filename}: the engine failed on this scene; the error was logged")


def derive_request(request: dict) -> dict:
    """The sandbox child's handler: ``{"source", "filename", "budget_s"?}`` -> ``{"outcome", ...}``.

    It never raises. With ``budget_s``, the child also arms an alarm a little after the parent's
    kill would come: should the parent die first (a ``kill -9`` of the server), the orphaned child
    still stops instead of deriving a pathological scene for minutes.
    """
    filename = request.get("filename", "upload.toml")
    budget = request.get("budget_s")
    if budget:
        signal.alarm(math.ceil(float(budget)) + ORPHAN_MARGIN_S)  # SIGALRM's default action ends the process
    try:
        # The engine's own budget, a little inside the parent's kill, names the step that ran out.
        engine_budget = float(budget) * 0.9 if budget else None
        return {"outcome": "ok", "problem": _derive(request["source"], filename, engine_budget)}
    except BudgetExceeded as error:
        return {"outcome": "error", "message": f"{filename}: {error}"}
    except MemoryError:
        raise  # the sandbox child answers for it and restarts
    except ValueError as error:  # SceneError and the expression errors: a message for the instructor
        return {"outcome": "error", "message": str(error)}
    except Exception:  # an engine bug: the parent logs it, the client gets a generic message
        return {"outcome": "internal", "trace": traceback.format_exc()}
    finally:
        if budget:
            signal.alarm(0)


def _derive(source: str, filename: str, budget_s: float | None = None) -> dict:
    import sympy

    import grader
    from grader.answers.question_tests import require_passing, run_question_tests
    from grader.answers.randomised import random_names
    from grader.answers.reference import ReferenceAnswer
    from grader.mechanics.lagrange import derive
    from grader.mechanics.references import parameter_specs
    from grader.mechanics.report import steps_json
    from grader.mechanics.scene import parse_scene
    from grader.simulate.motion import motion_of

    scene = parse_scene(source, source=filename)
    derivation = derive(scene, budget_s=budget_s)
    # The engine emits plain data; the checker's typed contract validates it before it is stored.
    references = [ReferenceAnswer.from_json(r) for r in derivation.references()]
    # The instructor's question tests, with the checker that will grade the students: a failing
    # one stops the registration (a ValueError: its message goes to the instructor).
    tests = require_passing(run_question_tests(references), filename)
    parameters = parameter_specs(scene)
    return {
        "slug": scene.id,
        "title": scene.title,
        "statement": scene.statement,
        # The stored derivation adds the step-by-step working for the instructor's review page, the
        # question tests' results, and the parameters a student's numbers are drawn from.
        "derivation": {**derivation.to_json(), "steps": steps_json(derivation.steps), "question_tests": tests,
                       "motion": motion_of(scene),
                       "parameters": parameters, "random_parameters": random_names(parameters)},
        "references": [r.to_json() for r in references],
        "engine_version": f"{grader.__version__}+sympy{sympy.__version__}",
    }


def load_problem_files(database, paths, **limits) -> list[tuple[str, str]]:
    """Store each scene file as a problem version when its source changed; returns (file, outcome) pairs.

    Unchanged files are recognised by their source hash without running the engine, so a restart
    costs nothing; a file that fails to derive is reported and skipped, not fatal.
    """
    outcomes = []
    for path in map(Path, paths):
        source = path.read_text(encoding="utf-8")
        digest = hashlib.sha256(source.encode()).hexdigest()
        newest = aliased(ProblemVersion)
        with database.read() as session:
            known = session.scalar(select(ProblemVersion.id).where(
                ProblemVersion.source_sha256 == digest,
                ProblemVersion.number == select(func.max(newest.number))
                .where(newest.problem_id == ProblemVersion.problem_id).scalar_subquery()).limit(1))
        if known is not None:
            outcomes.append((path.name, "unchanged"))
            continue
        try:
            read_scene_id(source, path.name)  # what an upload is refused for (a NUL) skips the file
            derived = derive_source(source, filename=path.name, **limits)
        except DerivationError as error:
            outcomes.append((path.name, f"skipped: {error}"))
            continue
        with database.write() as session:
            version, created = save_problem(session, derived)
            outcomes.append((path.name, f"version {version.number} of {derived.slug!r}" if created else "unchanged"))
    return outcomes


def close_shared_sandboxes() -> None:
    """Stop the shared children (after start-up: the derivation workers have their own)."""
    with _sandboxes_lock:
        for sandbox in _sandboxes.values():
            sandbox.close()
        _sandboxes.clear()
