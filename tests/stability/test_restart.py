"""A restart at an event, from the state the event reports, continues the same motion and does
not report the event again: the mode is decided from the state (a zero contact force counts by
the sign of its derivative), not from the history."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from grader.mechanics.scene import load_scene
from grader.simulate.compiled import CompiledScene, parameter_values
from grader.simulate.effects import declared_effects
from grader.simulate.initial import initial_state
from grader.simulate.trajectory import Simulation

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


@pytest.mark.parametrize("scene_file, overrides, t_end", [
    ("vertical_circle.toml", {}, 2.0),          # string slack, then taut again
    ("incline_slipping.toml", {"alpha": 0.2}, 2.0),  # stick after slipping (launched without spin)
])
def test_restart_at_each_event_continues_without_firing_it_again(scene_file, overrides, t_end):
    scene = load_scene(PROBLEMS / scene_file)
    compiled = CompiledScene(scene, parameter_values(scene, overrides))
    simulation = Simulation(compiled, declared_effects(scene, compiled.values))
    q0, qdot0 = initial_state(scene, compiled)
    if scene.id == "incline_slipping":
        qdot0 = np.array([2.0, 0.0, 0.0])
    times = np.linspace(0.0, t_end, 41)
    whole = simulation.run(0.0, q0, qdot0, t_end, times)
    assert whole.events, "the scene must have events to restart at"
    for k, event in enumerate(whole.events):
        q = [event.state[name] for name in compiled.coordinates]
        qdot = [event.state[f"{name}dot"] for name in compiled.coordinates]
        later = times[times > event.t]
        restart = simulation.run(event.t, q, qdot, t_end, later)
        assert [(e.effect, e.constraint) for e in restart.events] == [
            (e.effect, e.constraint) for e in whole.events[k + 1:]]
        np.testing.assert_allclose(restart.q, whole.q[times > event.t], rtol=1e-8, atol=1e-10)
