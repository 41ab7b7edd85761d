"""The sandbox: every run ends in one neutral outcome, a runaway is killed and its child replaced."""

import os
import time
from pathlib import Path

import pytest

from grader.sandbox import OUTCOMES, Outcome, Sandbox

HANDLERS = str(Path(__file__).parent)  # tests/sandbox_handlers.py, imported by the child


@pytest.fixture
def box(monkeypatch):
    monkeypatch.setenv("PYTHONPATH", HANDLERS)
    with Sandbox("sandbox_handlers:runaway", budget_s=0.5, memory_mb=512) as sandbox:
        yield sandbox


def test_a_reply_comes_back_as_ok(box):
    outcome = box.run({"echo": "x\ud800y"})  # a lone surrogate travels as its JSON escape
    assert outcome.status == "ok" and outcome.reply["echo"] == "x\ud800y"


@pytest.mark.parametrize("request_", [{"sleep": 30}, {"spin": True}], ids=["sleep", "busy-loop"])
def test_a_runaway_is_killed_at_the_budget_and_the_child_replaced(box, request_):
    first = box.run({}).reply["pid"]
    started = time.monotonic()
    outcome = box.run(request_)
    assert time.monotonic() - started < 2.0
    assert outcome.status == "timeout" and not outcome.during_start
    with pytest.raises(ProcessLookupError):
        os.kill(first, 0)
    assert box.run({}).reply["pid"] != first and box.restarts == 1


@pytest.mark.parametrize("request_, status", [
    ({"allocate_mb": 2048}, "out_of_memory"),  # over the 512 MiB cap
    ({"exit": 9}, "crashed"),                  # the child dies mid-request
    ({"raise": True}, "crashed"),              # the handler raises
])
def test_a_failing_request_has_its_outcome_and_the_next_one_is_served(box, request_, status):
    outcome = box.run(request_)
    assert outcome.status == status and outcome.reply is None and not outcome.during_start
    assert box.run({"echo": 1}).reply["echo"] == 1


def test_a_child_that_dies_on_start_up_is_an_outcome_not_an_exception(monkeypatch):
    monkeypatch.setenv("PYTHONPATH", HANDLERS)
    with Sandbox("sandbox_handlers:no_such_handler", budget_s=1.0) as box:
        outcome = box.run({})
    assert outcome.status == "crashed" and outcome.during_start


def test_an_outcome_is_one_of_four():
    assert OUTCOMES == ("ok", "timeout", "crashed", "out_of_memory")
    with pytest.raises(ValueError):
        Outcome("killed")
