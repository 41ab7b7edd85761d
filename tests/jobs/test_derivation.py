"""Deriving uploaded scenes in a limited child process, and loading problems/ at start."""

import json
import signal
from pathlib import Path

import pytest
from sqlalchemy import select

from grader.jobs.derivation import (DerivationError, SandboxUnavailable, derive_source, load_problem_files,
                                    read_scene_id)
from grader.sandbox import Outcome
from grader.store.models import ProblemVersion

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"
TEXTBOOK = Path(__file__).resolve().parents[1] / "mechanics" / "scenes"


def test_a_scene_is_derived_into_references_the_checker_takes():
    derived = derive_source((PROBLEMS / "yoyo.toml").read_text(), filename="yoyo.toml")
    references = {r["name"]: r for r in derived.references}
    assert derived.slug == "yoyo" and derived.title.startswith("Yo-yo")
    # The yo-yo falls with a = 2g/3 and the string pulls with T = mg/3.
    assert references["acceleration"]["reference"] == "2*g/3"
    assert references["tension"]["reference"] == "g*m/3"
    assert set(references["tension"]) >= {"prompt", "kind", "variables", "dimension", "latex", "feedback"}


@pytest.mark.parametrize("source, message", [
    ("id = \"x\"\n[energy\n", "upload.toml"),
    ("id = \"x\"\n[coordinates]\nq = { dimension = \"length\" }\n[energy]\nkinetic = \"qdot^2 + tehta\"\n", "tehta"),
])
def test_an_invalid_scene_is_refused_with_its_error(source, message):
    with pytest.raises(DerivationError, match=message):
        derive_source(source)


def test_a_derivation_over_its_time_limit_is_stopped_and_the_next_one_works():
    # A four-link chain takes far more than 0.2 s to derive (and no earlier derivation in the child
    # can have cached it). The engine's own budget (0.18 s) names the step it stopped in; should a
    # step not return to Python in time, the parent's kill at 0.2 s stops it instead. Which one comes
    # first depends on the machine's load.
    from grader.bench.isolation import pathological_scene

    with pytest.raises(DerivationError, match=r"ran out of its 0.18 s budget while|longer than 0.2 s"):
        derive_source(pathological_scene(4), timeout_s=0.2)
    assert derive_source((PROBLEMS / "yoyo.toml").read_text()).slug == "yoyo"


def test_loading_problem_files_adds_versions_only_for_changed_sources(database, tmp_path):
    scene = tmp_path / "yoyo.toml"
    scene.write_text((PROBLEMS / "yoyo.toml").read_text())
    assert load_problem_files(database, [scene]) == [("yoyo.toml", "version 1 of 'yoyo'")]
    assert load_problem_files(database, [scene]) == [("yoyo.toml", "unchanged")]
    scene.write_text(scene.read_text() + "\n# clarified\n")
    assert load_problem_files(database, [scene]) == [("yoyo.toml", "version 2 of 'yoyo'")]
    with database.read() as session:
        assert session.scalars(select(ProblemVersion.number)).all() == [1, 2]


@pytest.mark.parametrize("source, words", [
    ("not toml [", "not valid TOML"),
    ('id = "x"\ntitle = "\\u0000Pendulum"\n', "title holds a NUL character"),  # no column takes it
])
def test_a_broken_problem_file_is_skipped_not_fatal(database, tmp_path, source, words):
    (tmp_path / "bad.toml").write_text(source)
    [(name, outcome)] = load_problem_files(database, [tmp_path / "bad.toml"])
    assert name == "bad.toml" and outcome.startswith("skipped: bad.toml: ") and words in outcome


class _Ended:
    """A sandbox whose every run ends in the given outcome (the real ones are tested in tests/test_sandbox.py)."""

    def __init__(self, outcome):
        self.outcome = outcome

    def run(self, request, budget_s=None):
        return self.outcome


# How each way a derivation child's run can end reads to the instructor who uploaded the scene.
@pytest.mark.parametrize("outcome, error, words", [
    (Outcome("timeout"), DerivationError, "longer than 20 s"),
    (Outcome("out_of_memory"), DerivationError, "more than 2048 MB"),
    (Outcome("crashed", detail="the child exited (signal SIGSEGV)"), DerivationError, "the engine failed"),
    (Outcome("ok", reply={"outcome": "error", "message": "x.toml: energy: unknown name"}), DerivationError,
     "unknown name"),
    (Outcome("crashed", detail="did not start", during_start=True), SandboxUnavailable, "unavailable"),
], ids=["timeout", "out-of-memory", "crash", "scene-error", "no-child"])
def test_every_sandbox_outcome_becomes_a_scene_error_or_a_retry(outcome, error, words):
    with pytest.raises(error, match=words):
        derive_source("id = 'x'", timeout_s=20, memory_mb=2048, sandbox=_Ended(outcome))


@pytest.mark.slow
def test_an_orphaned_derivation_child_stops_by_itself(tmp_path):
    """If the server dies mid-derivation (kill -9), its child must not derive on for minutes: the
    engine's budget stops it and says where (an alarm that kills the child backs that up)."""
    import subprocess
    import sys
    import time

    from grader.bench.isolation import pathological_scene

    request = json.dumps({"source": pathological_scene(4), "filename": "chain4.toml", "budget_s": 0.5})
    child = subprocess.Popen([sys.executable, "-m", "grader.sandbox", "--handler",
                              "grader.jobs.derivation_child:derive_request"],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    try:
        assert json.loads(child.stdout.readline()) == {"ready": True}
        child.stdin.write((request + "\n").encode())
        child.stdin.flush()  # nobody will kill it: this parent "died" and only waits
        started = time.monotonic()
        reply = child.stdout.readline()
        assert time.monotonic() - started < 1 + 5 + 5  # its budget rounded up, the margin, start-up slack
        if reply:  # the engine's budget stopped the derivation and named the step
            assert "ran out of its 0.45 s budget while" in json.loads(reply)["reply"]["message"]
        else:  # the backstop: the alarm ended the child
            child.wait(timeout=5)
            assert child.returncode == -signal.SIGALRM
    finally:
        child.kill()
        child.wait()


def test_a_derivation_child_runs_at_a_lowered_cpu_priority_and_the_server_does_not():
    import os

    from grader.jobs.derivation import derivation_sandbox
    from grader.jobs.derivation_child import DERIVE_NICENESS

    own = os.getpriority(os.PRIO_PROCESS, 0)
    sandbox = derivation_sandbox(timeout_s=30)
    try:
        with pytest.raises(DerivationError, match="not valid TOML"):
            derive_source('id = "x"\n[energy\n', sandbox=sandbox)
        assert os.getpriority(os.PRIO_PROCESS, sandbox.pid) == min(own + DERIVE_NICENESS, 19)
    finally:
        sandbox.close()
    assert os.getpriority(os.PRIO_PROCESS, 0) == own


@pytest.mark.slow
@pytest.mark.parametrize("path", sorted(PROBLEMS.glob("*.toml")) + sorted(TEXTBOOK.glob("*.toml")), ids=lambda p: p.name)
def test_every_shipped_and_textbook_scene_registers(path):
    # What an instructor's upload goes through (the derivation child's handler, in this process):
    # every kind of answer the engine computes must fit the checker's reference contract.
    from grader.jobs.derivation import derive_request

    reply = derive_request({"source": path.read_text(), "filename": path.name})
    assert reply["outcome"] == "ok", reply.get("message") or reply.get("trace")
    assert {r["kind"] for r in reply["problem"]["references"]} <= {"expression", "equation", "numeric"}


# TOML's "\u0000" escape is a NUL character in any string or key; no column takes it, so the scene
# is refused before a derivation is queued, naming where the NUL is.
@pytest.mark.parametrize("source, where", [
    ('id = "x"\ntitle = "\\u0000Simple pendulum"\n', "title"),
    ('id = "x"\nstatement = """A string\\u0000"""\n', "statement"),
    ('id = "x\\u0000"\n', "id"),
    ('id = "x"\n[[answers]]\nname = "T"\nprompt = "ok"\n[[answers]]\nname = "a"\nprompt = "The\\u0000a"\n',
     "answers[1].prompt"),
    ('id = "x"\n[[answers]]\nname = "T"\nfeedback = [{ when = "m*g", say = "\\u0000" }]\n',
     "answers[0].feedback[0].say"),
    ('id = "x"\n[variables]\n"m\\u0000" = { dimension = "mass" }\n', 'variables."m\\u0000"'),
    ('id = "x"\n[parameters]\ng = { value = 9.81, unit = "m/s^2\\u0000" }\n', "parameters.g.unit"),
])
def test_a_scene_holding_a_nul_character_is_refused_naming_where(source, where):
    with pytest.raises(DerivationError) as refused:
        read_scene_id(source, "pendulum.toml")
    assert str(refused.value) == (f"pendulum.toml: {where} holds a NUL character (\\u0000), which is not text; "
                                  "remove it")
