"""The motion a problem page shows: a short simulation of the scene, drawn once when it is registered.

The scene's optional ``[simulation]`` table says how long to simulate (``t_end``, default 3 s) and
whether students see the pictures too (``show_students``, default false: instructors always do).
The result is plain JSON (SVG text and the events), stored with the derivation, so no page ever
integrates anything. A scene that cannot be simulated (a parameter without a ``value``, an initial
state off its constraints) gets a reason instead of pictures: that is information for the
instructor, not an error of the registration.

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> motion = motion_of(load_scene("problems/vertical_circle.toml"))
>>> sorted(motion)
['animation', 'events', 'plot', 'show_students', 't_end']
>>> motion["plot"].startswith("<svg") and [e["effect"] for e in motion["events"]][:1]
['release']
"""

from __future__ import annotations

from typing import Any

__all__ = ["DEFAULT_T_END_S", "motion_of"]

DEFAULT_T_END_S = 3.0
SAMPLES = 241
BUDGET_S = 8.0


def motion_of(scene, *, budget_s: float = BUDGET_S) -> dict[str, Any]:
    """``{"plot", "animation" (None without [geometry]), "events", "t_end", "show_students"}``, or
    ``{"unavailable": reason, "show_students"}`` when the scene cannot be simulated."""
    from grader.simulate.compiled import SingularDynamics, parameter_values
    from grader.simulate.events import SimulationError
    from grader.simulate.initial import InitialStateError
    from grader.simulate.plot import animation_of, plot_of
    from grader.simulate.trajectory import simulate_scene

    settings = getattr(scene, "simulation", None) or {}
    show_students = bool(settings.get("show_students", False))
    t_end = float(settings.get("t_end", DEFAULT_T_END_S))
    try:
        values = parameter_values(scene, None)
        trajectory = simulate_scene(scene, t_end=t_end, samples=SAMPLES, budget_s=budget_s)
    except (KeyError, ValueError, SingularDynamics, SimulationError, InitialStateError, ArithmeticError) as error:
        reason = error.args[0] if isinstance(error, KeyError) and error.args else str(error)
        return {"unavailable": f"no simulation: {reason}", "show_students": show_students}
    animation = animation_of(scene, trajectory, values) if getattr(scene, "geometry", None) else None
    return {"plot": plot_of(trajectory, title=f"{scene.title}: the first {t_end:g} s"),
            "animation": animation, "events": trajectory.to_json()["events"], "t_end": t_end,
            "show_students": show_students}
