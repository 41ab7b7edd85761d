"""The guards around scipy's event location (grader.simulate.events)."""

from __future__ import annotations

import time

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from grader.simulate.events import SimulationError, guard_start, within_budget


def falling_gap():
    def gap(t, y):
        return y[0]

    gap.terminal, gap.direction = True, -1.0
    return gap


def test_a_function_at_zero_at_the_start_does_not_fire_there_and_a_later_crossing_in_the_first_step_is_found():
    # A ball leaving the floor at 1 m/s lands after 2 v/g; one huge first step covers the whole hop.
    def rhs(t, y):
        return [y[1], -9.81]

    plain = solve_ivp(rhs, (0.0, 1.0), [0.0, 1.0], events=falling_gap(), first_step=0.5, rtol=1e-12)
    guarded = solve_ivp(rhs, (0.0, 1.0), [0.0, 1.0], events=guard_start(falling_gap(), 0.0, np.array([0.0, 1.0])),
                        first_step=0.5, rtol=1e-12)
    assert plain.t_events[0][0] == 0.0                                       # scipy alone stops at once
    assert guarded.t_events[0][0] == pytest.approx(2 / 9.81, rel=1e-12)     # the guard finds the landing


def test_a_function_already_on_its_safe_side_is_unchanged():
    guarded = guard_start(falling_gap(), 0.0, np.array([0.3]))
    assert guarded(0.0, np.array([0.3])) == 0.3
    assert (guarded.terminal, guarded.direction) == (True, -1.0)


def test_a_right_hand_side_past_its_deadline_stops_the_integration():
    limited = within_budget(lambda t, y: [1.0], time.monotonic() - 1.0)
    with pytest.raises(SimulationError, match="time budget"):
        solve_ivp(limited, (0.0, 1e9), [0.0], max_step=1.0)
