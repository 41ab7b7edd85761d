"""The sandbox: a runaway check is killed (SIGKILL), the child restarted, and the caller told why."""

import os
import time

import pytest

from grader.answers.sandbox import Sandbox

RUNAWAY = "grader.answers.sandbox:_test_runaway"


@pytest.fixture
def box():
    with Sandbox(budget_s=0.5, memory_mb=512, handler=RUNAWAY) as sandbox:
        yield sandbox


@pytest.mark.parametrize("request_", [{"sleep": 30}, {"spin": True}], ids=["sleep", "busy-loop"])
def test_a_runaway_is_killed_at_the_budget_and_the_child_replaced(box, request_):
    first = box.run({})["pid"]
    started = time.monotonic()
    reply = box.run(request_)
    assert time.monotonic() - started < 2.0
    assert reply["verdict"] == "invalid" and reply["budget_exceeded"] is True
    assert "budget exceeded" in reply["reason"]
    with pytest.raises(ProcessLookupError):
        os.kill(first, 0)
    assert box.run({})["pid"] != first and box.restarts == 1


def test_memory_cap_cannot_be_escaped(box):
    reply = box.run({"allocate_mb": 2048})
    assert reply["verdict"] == "invalid" and "memory" in reply["reason"]
    assert box.run({})["verdict"] == "equivalent"  # and the next request is served


def test_the_real_checker_runs_in_the_sandbox():
    with Sandbox(budget_s=2.0) as sandbox:
        reply = sandbox.run({"reference": "m*g/3", "answer": "mg/3",
                             "variables": {"m": {"dimension": "mass", "domain": "positive"},
                                           "g": {"dimension": "acceleration", "domain": "positive"}}})
        assert reply["verdict"] == "equivalent"
        assert sandbox.run("not a request")["verdict"] == "invalid"
