"""What the red-team scene tests share: a scene's own numbers, agreement with a hand derivation at
parameter points, and Newton's laws integrated with scipy (written again, never the engine's equations)."""

from __future__ import annotations

import functools

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import load_scene
from tests.mechanics.conftest import SCENES
from tests.mechanics.test_red_team_scenes_7 import at


@functools.lru_cache(maxsize=None)
def derived(name: str):
    """The scene ``name`` of tests/mechanics/scenes derived once, under `grader derive`'s budget."""
    return derive(load_scene(SCENES / f"{name}.toml"), budget_s=60)


def engine_value(name: str, answer: str, point: dict[str, float]) -> float:
    """The engine's ``answer`` of the scene ``name`` at ``point``."""
    derivation = derived(name)
    return at(derivation, derivation.answers[answer], point)


def hand_cases(tables: dict) -> list[tuple]:
    """(scene, answer, expected, points) for each answer of ``{scene: ({answer: expected}, points)}``."""
    return [(scene, answer, expected, points)
            for scene, (table, points) in tables.items() for answer, expected in table.items()]


def unchecked_answers(tables: dict, elsewhere: set = frozenset()) -> dict[str, set]:
    """Per scene, the answers in its file or its table but not both (``elsewhere``: (scene, answer) pairs
    checked by other tests count as in the table)."""
    unchecked = {}
    for scene, (table, _) in tables.items():
        names = {a.name for a in load_scene(SCENES / f"{scene}.toml").answers}
        left = names ^ (set(table) | {a for s, a in elsewhere if s == scene})
        if left:
            unchecked[scene] = left
    return unchecked


def scene_values(name: str) -> dict[str, float]:
    """The scene's parameter values (the numbers the engine chose its closed forms at)."""
    return {p.name: float(p.value) for p in load_scene(SCENES / f"{name}.toml").parameters.values()}


def agrees_by_hand(derivation, answer: str, expected: str, points: list[dict[str, float]]) -> None:
    """The engine's answer equals the hand-derived ``expected`` at every point, to 1e-10."""
    for point in points:
        got, want = at(derivation, derivation.answers[answer], point), at(derivation, expected, point)
        assert got == pytest.approx(want, rel=1e-10, abs=1e-12), f"{answer} at {point}"


def integrate(rhs, start, t_end, events=None):
    return solve_ivp(rhs, (0.0, t_end), start, method="DOP853", rtol=1e-11, atol=1e-13, dense_output=True,
                     events=events)


def period(solution, velocity_index: int, t_end: float) -> float:
    """The time between the first and the third sign change of a velocity (one full swing)."""
    ts = np.linspace(0.0, t_end, 20001)
    v = solution.sol(ts)[velocity_index]
    crossings = [ts[i] - v[i] * (ts[i + 1] - ts[i]) / (v[i + 1] - v[i])
                 for i in range(1, len(ts) - 1) if v[i] * v[i + 1] < 0]
    return crossings[2] - crossings[0]
