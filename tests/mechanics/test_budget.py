"""Budgets: a derivation that runs out of time says which step and which answer ran out."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from grader.cli.derive import derive as derive_command
from grader.mechanics.budget import BudgetExceeded, attempt, overall_budget, step
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import load_scene

SCENES = Path(__file__).resolve().parent / "scenes"


def spin(seconds: float) -> str:
    """Busy work: CPU time, which is what an attempt's budget counts."""
    end = time.process_time() + seconds
    while time.process_time() < end:
        pass
    return "done"


def test_attempt_falls_back_when_the_step_runs_out_of_cpu_time():
    assert attempt(lambda: spin(5), 0.05, fallback=lambda: "fallback") == "fallback"
    assert attempt(lambda: spin(0.01), 2.0, fallback=lambda: "fallback") == "done"


def test_an_attempt_inside_an_overall_budget_leaves_it_in_force():
    with pytest.raises(BudgetExceeded, match="while outer work"):
        with overall_budget(0.6), step("outer work"):
            assert attempt(lambda: spin(5), 0.05, fallback=lambda: "fallback") == "fallback"
            time.sleep(3)  # the overall (wall-clock) budget still fires


def test_a_derivation_out_of_budget_names_the_step():
    scene = load_scene(SCENES / "double_pendulum.toml")
    with pytest.raises(BudgetExceeded) as caught:
        derive(scene, budget_s=0.01)
    assert caught.value.step  # e.g. "solving the equations of motion"
    assert "0.01 s budget while" in str(caught.value)


def test_an_answer_out_of_budget_is_named_wherever_in_it_the_time_runs_out(monkeypatch):
    # a step that names no answer of its own (an extreme's search, a tidying) said only "while deriving"
    from grader.mechanics import answers

    def slow(evaluator, spec):
        time.sleep(5)

    monkeypatch.setattr("grader.mechanics.extremes.extreme_value", slow)
    scene = load_scene(SCENES / "cylinder_in_cylinder.toml")
    largest = next(a.name for a in scene.answers if a.kind == "maximum")
    with pytest.raises(BudgetExceeded) as caught:
        derive(scene, budget_s=3)
    assert f"for the answer '{largest}'" in str(caught.value), str(caught.value)
    assert answers  # (the module whose loop names the answer)


def test_grader_derive_has_a_budget_and_says_where_it_ran_out():
    result = CliRunner().invoke(derive_command, [str(SCENES / "double_pendulum.toml"), "--budget", "0.1"])
    assert result.exit_code == 3
    assert "double_pendulum.toml: the derivation ran out of its 0.1 s budget while" in result.output


def test_grader_derive_within_budget_prints_the_derivation():
    result = CliRunner().invoke(derive_command, [str(SCENES / "atwood_massless_pulley.toml"), "--budget", "60"])
    assert result.exit_code == 0, result.output
    assert "tension_left = -lambda_left = 2*g*m1*m2/(m1 + m2)" in result.output


def test_a_budget_never_raises_inside_a_garbage_collection_but_right_after_it(monkeypatch):
    # An exception from a gc callback is lost (reported as unraisable) and the step would run on
    # unbounded: the alarm waits for the collection to end, then interrupts.
    import threading
    import time

    from grader.mechanics import budget

    monkeypatch.setattr(budget, "_collecting", [True])
    threading.Timer(0.3, lambda: budget._collecting.__setitem__(0, False)).start()

    def spin():
        while True:
            pass

    start = time.perf_counter()
    assert budget.attempt(spin, 0.05, fallback=lambda: "fallback") == "fallback"
    assert time.perf_counter() - start >= 0.25


def test_a_budget_never_raises_inside_another_libraries_collection_callback(monkeypatch):
    # hypothesis times collections with a callback that runs before ours at the start: an alarm
    # landing in it was lost (unraisable) and failed an unrelated test in CI.
    import gc
    import sys

    lost = []
    monkeypatch.setattr(sys, "unraisablehook", lost.append)

    def slow_callback(phase, info):
        if phase == "start":
            spin(0.2)

    def collect_then_spin():
        gc.collect()
        spin(5)

    gc.callbacks.insert(0, slow_callback)
    try:
        assert attempt(collect_then_spin, 0.05, fallback=lambda: "fallback") == "fallback"
    finally:
        gc.callbacks.remove(slow_callback)
    assert lost == []


def test_a_budget_never_raises_inside_a_finaliser(monkeypatch):
    # an exception from __del__ is lost too (unraisable); the alarm waits for the finaliser to end
    import sys

    lost = []
    monkeypatch.setattr(sys, "unraisablehook", lost.append)

    class SlowToFinalise:
        def __del__(self):
            spin(0.2)

    def drop_then_spin():
        SlowToFinalise()  # finalised at once: its reference count drops to zero
        spin(5)

    assert attempt(drop_then_spin, 0.05, fallback=lambda: "fallback") == "fallback"
    assert lost == []
