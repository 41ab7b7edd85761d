"""The checker in its sandbox: every way a run ends becomes a verdict, and only the checker's own
failures are marked as such (so the queue retries them rather than grading the student on them)."""

from pathlib import Path

import pytest

from grader.answers.sandbox import SandboxedChecker, verdict_of
from grader.answers.verdict import Verdict
from grader.sandbox import Outcome

MG = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"}}
HANDLERS = str(Path(__file__).parents[1])  # tests/sandbox_handlers.py


@pytest.mark.parametrize("outcome, reason, budget_exceeded, checker_failure", [
    (Outcome("timeout", detail="stopped after 2 s"), "budget exceeded", True, False),
    (Outcome("out_of_memory"), "memory limit", False, False),
    (Outcome("crashed", detail="the child exited (signal SIGSEGV)"), "crashed on this answer", False, False),
    (Outcome("crashed", detail="the sandbox child died while starting", during_start=True),
     "checker unavailable", False, True),
    (Outcome("ok", reply={"verdict": "maybe"}), "not a verdict", False, True),
    (Outcome("ok", reply=None), "not a verdict", False, True),
], ids=["timeout", "out-of-memory", "crash-on-the-answer", "crash-at-start", "odd-verdict", "no-reply"])
def test_every_outcome_but_a_verdict_is_an_invalid_verdict(outcome, reason, budget_exceeded, checker_failure):
    v = verdict_of(outcome, "x^x")
    assert v["verdict"] == "invalid" and reason in v["reason"] and v["parsed"]["text"] == "x^x"
    assert v["budget_exceeded"] is budget_exceeded
    assert v.get("checker_failure", False) is checker_failure


def test_a_checker_verdict_passes_through_unchanged():
    reply = Verdict("equivalent", "proved", "symbolically identical").to_json()
    assert verdict_of(Outcome("ok", reply=reply)) == reply


def test_the_real_checker_runs_in_the_sandbox():
    with SandboxedChecker(budget_s=2.0) as checker:
        assert checker.run({"reference": "m*g/3", "answer": "mg/3", "variables": MG})["verdict"] == "equivalent"
        assert checker.run("not a request")["verdict"] == "invalid"
        surrogate = checker.run({"reference": "m*g", "answer": "m g\ud800", "variables": MG})
        assert surrogate["verdict"] == "invalid" and "U+D800" in surrogate["reason"]


def test_a_checker_that_cannot_start_is_a_checker_failure_not_an_exception(monkeypatch):
    monkeypatch.setenv("PYTHONPATH", HANDLERS)
    with SandboxedChecker(budget_s=1.0, handler="sandbox_handlers:no_such_handler") as checker:
        v = checker.run({"reference": "m*g", "answer": "m g", "variables": MG})
    assert v["verdict"] == "invalid" and v["checker_failure"] is True


def test_a_runaway_answer_is_stopped_at_its_budget(monkeypatch):
    monkeypatch.setenv("PYTHONPATH", HANDLERS)
    with SandboxedChecker(budget_s=0.3, handler="sandbox_handlers:runaway") as checker:
        v = checker.run({"answer": "x", "spin": True})
    assert v["verdict"] == "invalid" and v["budget_exceeded"] is True and "checker_failure" not in v
