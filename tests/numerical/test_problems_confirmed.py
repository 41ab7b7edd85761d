"""Every answer of every scene in ``problems/`` (and the textbook scenes) confirmed by a numerical experiment.

For each scene file the engine derives its closed-form answers (``derive(scene).answers``). The
motion from the scene's ``[initial]`` state is then integrated numerically
(:mod:`grader.simulate`), which never sees the engine's results: it differentiates the scene's
own T, V and f numerically and solves the KKT system for q̈ and λ at every instant. Along that
motion each answer's *defining* expression (``expr = "lambda_surface"``, ``"-Q_roll_s"``, ...) is
evaluated with the numerical multipliers, forces and accelerations, and must equal the engine's
closed form evaluated at the same state, to 1e-6 relative. Values near zero (a normal force at the
moment of release, θ̈ at the bottom of a swing) are compared against the largest value of that
answer along the run instead of their own size.

Answers with ``where = "..."`` are special values: the condition is located as an event along the
motion (first crossing), and the answer's expression is evaluated there.

A scene that starts at rest in an equilibrium (the top of the sphere) is given a push of 1e-7 in
its first named velocity (see ``SceneModel.initial_state``). The energy this adds is checked to be
below 1e-12 of the energy exchanged during the run, so energy-based closed forms are disturbed
far below the tolerance.

New files in ``problems/`` are picked up automatically. If there are none, or the engine cannot be
imported, these tests fail: they never pass without having confirmed something.
"""

from __future__ import annotations

import functools
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest
import sympy

from grader.simulate.constrained import Event, Snapshot, multiplier_zero, simulate
from grader.simulate.scene_numeric import SceneModel

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"
# The textbook scenes the engine was not written for (bead on a rotating hoop, ladder, wedge,
# Atwood with a massive pulley, double pendulum) are confirmed the same way.
TEXTBOOK = Path(__file__).resolve().parents[1] / "mechanics" / "scenes"
SCENE_FILES = sorted(PROBLEMS.glob("*.toml")) + sorted(TEXTBOOK.glob("*.toml"))

RTOL = 1e-6
PUSH = 1e-7            # rad/s or m/s: leaves an unstable equilibrium, adds ~push² energy
CHUNK = 2.0            # s of motion per integration run
SAMPLES_PER_CHUNK = 9
T_MAX = 30.0           # s: give up looking for a `where` condition after this


# Special values that define a state or a parameter rather than a moment of the motion from
# [initial] (a steady orbit, small oscillations, a threshold launch speed, a configuration this
# launch does not reach): each has its own experiment in test_special_values_confirmed.py.
CONFIRMED_ELSEWHERE = {
    ("table_hole_orbit", "steady_angular_velocity"),
    ("bead_hoop_equilibrium", "small_oscillation_frequency"),
    ("cylinder_in_cylinder", "small_oscillation_frequency"),
    ("loop_inside_track", "top_normal_force"),
    ("loop_inside_track", "least_launch_speed"),
    ("cylinder_in_cylinder", "largest_normal_force"),
    ("ladder_wall", "largest_wall_force"),
    ("pendulum_sliding_support", "small_oscillation_frequency"),
    ("conical_pendulum", "small_oscillation_frequency"),
    ("bead_rotating_parabola", "small_oscillation_frequency"),
    ("bead_rotating_parabola", "critical_angular_velocity"),
    ("turntable_slot_spring", "small_oscillation_frequency"),
    ("turntable_slot_spring", "critical_angular_velocity"),
    ("double_atwood", "balancing_mass"),
    ("spool_pulled_at_angle", "critical_cos"),
    ("watt_governor", "small_oscillation_frequency"),
    ("watt_governor", "least_angular_velocity"),
    ("watt_governor", "equilibrium_cos"),
    # Extremes over the driven motion: test_special_values_confirmed.py, over two periods.
    ("cylinder_on_oscillating_plank", "largest_friction"),
    ("cylinder_on_oscillating_plank", "least_velocity"),
    ("cylinder_on_oscillating_plank", "largest_spin"),
    # The red-team scenes: tests/numerical/test_red_team_confirmed.py.
    ("bead_hoop_turning_about_rim", "small_oscillation_frequency"),
    ("bead_on_cycloid", "small_oscillation_frequency"),
    ("bead_spinning_hoop_cartesian", "small_oscillation_frequency"),
    ("particle_in_paraboloid", "orbit_angular_velocity"),
    ("particle_in_paraboloid", "small_oscillation_frequency"),
    ("pulley_spring_block", "lowest_depth"),
    ("pulley_spring_block", "small_oscillation_frequency"),
    ("rocking_half_cylinder", "small_oscillation_frequency"),
    ("rotating_frame_spring_orbit", "small_oscillation_frequency"),
    ("rotating_frame_spring_orbit", "steady_relative_angular_velocity"),
    # The second red team's: the same file.
    ("bead_inclined_rotating_wire", "equilibrium_distance"),
    ("particle_rotating_inclined_plane", "equilibrium_distance"),
    ("particle_rotating_inclined_plane", "equilibrium_normal_force"),
    ("pendulum_accelerating_car", "small_oscillation_frequency"),
    ("trammel_spring", "small_oscillation_frequency"),
    ("yoyo_counterweight", "balancing_mass"),
    ("block_on_accelerated_incline", "least_acceleration"),
    # The third red team's: the same file.
    ("cart_cylinder", "small_oscillation_frequency"),
    ("offcentre_wheel", "small_oscillation_frequency"),
    ("rod_ends_on_circle", "small_oscillation_frequency"),
    ("hoop_bead_incline", "relative_equilibrium_tan"),
    ("hoop_bead_incline", "relative_equilibrium_acceleration"),
    ("dumbbell_in_circle", "small_oscillation_frequency"),
    # The fifth red team's: the same file (the height of the climb, and a launch speed other than [initial]'s).
    ("cart_quarter_circle", "max_height"),
    ("cart_quarter_circle", "rim_angular_speed_squared"),
    ("cart_quarter_circle", "least_launch_speed"),
    # Extremes of a swing through the pole of θ: test_special_values_confirmed.py, over a whole swing.
    ("spherical_pendulum_through_the_pole", "thetadot_max"),
    ("spherical_pendulum_through_the_pole", "rise_rate_max"),
    ("spherical_pendulum_through_the_pole", "rise_rate_min"),
    ("sphere_in_bowl", "least_friction_coefficient"),
    ("sphere_in_bowl", "small_oscillation_frequency"),
    # The eleventh engine red team's: test_special_values_confirmed.py (extremes over the integrated
    # bounce; the frequency from a nudged orbit's crossings).
    ("elastic_pendulum_hanging", "r_max"),
    ("elastic_pendulum_hanging", "tension_min"),
    ("cone_orbit_inverse_attraction", "small_oscillation_frequency"),
    # Red team 12's: test_red_team_confirmed.py (the swing about the normal to the incline).
    ("pendulum_on_block_on_incline", "small_oscillation_frequency"),
    # Red team 16's: test_red_team_confirmed.py (frequencies from nudged swings, the equilibrium located
    # numerically, the balancing mass by a release, the least floor force over the integrated fall).
    ("pendulum_winding_on_cylinder", "small_oscillation_frequency"),
    ("bead_on_free_hoop", "small_oscillation_frequency"),
    ("rod_in_bowl_on_rim", "equilibrium_cos"),
    ("rod_in_bowl_on_rim", "small_oscillation_frequency"),
    ("cylinder_in_free_cylinder", "small_oscillation_frequency"),
    ("compound_atwood_massive_pulleys", "balancing_mass"),
    ("hinged_rods_on_floor", "least_floor_force"),
    # Red team 18's: tests/mechanics/test_red_team_scenes_12.py (extremes over the integrated swing, the
    # frequency from its period, the hovering acceleration by Newton's laws at and beside it).
    ("bead_vertical_ellipse_cartesian", "largest_speed_squared"),
    ("bead_vertical_ellipse_cartesian", "frequency"),
    ("disk_incline_spring_axle", "frequency"),
    ("disk_incline_spring_axle", "least_friction_coefficient"),
    ("disk_incline_spring_axle", "largest_speed"),
    ("incline_peg_spring_hanging", "frequency"),
    ("incline_peg_spring_hanging", "largest_stretch"),
    ("incline_peg_spring_hanging", "least_tension"),
    ("incline_peg_spring_hanging", "largest_tension"),
    ("yoyo_pulled_up_accelerating", "hovering_acceleration"),
    # Red team 21's: tests/mechanics/test_red_team_scenes_13.py (extremes and frequencies against the
    # integrated swings; the stick's falling rate holds until it lands, where the integration here goes on).
    ("stick_falling_on_ice", "fall_rate"),
    ("swing_seat_parallel_ropes", "largest_right_tension"),
    ("swing_seat_parallel_ropes", "least_left_tension"),
    ("swing_seat_parallel_ropes", "small_oscillation_frequency"),
    ("two_beads_rigid_rod_cartesian", "largest_inner_side_force"),
    ("two_beads_rigid_rod_cartesian", "small_oscillation_frequency"),
    ("cylinder_in_accelerating_drum", "small_oscillation_frequency"),
    ("atwood_hung_from_spring", "largest_tension"),
    # Red team 24's: tests/mechanics/test_red_team_scenes_14.py (steady circles launched at the engine's rate,
    # the turning radius and the frequencies against integrated orbits and swings).
    ("gravity_well_funnel", "orbit_angular_velocity"),
    ("gravity_well_funnel", "innermost_radius"),
    ("gravity_well_funnel", "small_oscillation_frequency"),
    ("magnetic_spherical_pendulum", "steady_orbit_rate"),
    ("particle_on_torus", "steady_orbit_rate"),
    ("bead_rotating_ellipse_cartesian", "small_oscillation_frequency"),
    # ẍ = 0 names the equilibrium at rest (ẍ has a ẋ² term in Cartesian x), not a moment of the swing.
    ("bead_rotating_ellipse_cartesian", "equilibrium_height"),
    ("bead_rotating_ellipse_cartesian", "passing_normal_force"),
}


def _answer_ids() -> list[tuple[Path, str]]:
    # Read names with tomllib, not the scene loader, so that collection works even when the
    # loader or a file is broken (the test itself then fails with the loader's message).
    cases = []
    for path in SCENE_FILES:
        try:
            answers = tomllib.loads(path.read_text(encoding="utf-8")).get("answers", [])
        except (tomllib.TOMLDecodeError, UnicodeDecodeError):
            answers = [{"name": "<unreadable>"}]
        cases += [(path, a.get("name", f"answers[{i}]")) for i, a in enumerate(answers)
                  if (path.stem, a.get("name")) not in CONFIRMED_ELSEWHERE]
    return cases


def reasonable_value(parameter) -> float:
    """A number for a parameter the scene leaves without ``value``."""
    if parameter.name == "g":
        return 9.81
    domain = parameter.domain
    if domain.kind == "interval":
        return domain.lo + 0.37 * (domain.hi - domain.lo)
    return 1.3


@dataclass
class Experiment:
    """One scene's numerical run: states along the motion, and where its conditions hold."""

    model: SceneModel
    closed_forms: dict
    samples: list[dict[str, float]] = field(default_factory=list)  # quantities by name
    where: dict[str, dict[str, float] | None] = field(default_factory=dict)  # condition -> quantities
    push_energy_ratio: float = 0.0


def _condition_key(model: SceneModel, spec) -> str:
    lhs, rhs = spec.where
    return str(model.definition(lhs - rhs))


def _where_events(model: SceneModel) -> list[Event]:
    """One event per distinct ``where`` condition: lhs - rhs crossing zero."""
    conditions = {}
    for spec in model.scene.answers:
        if spec.where is not None and (model.scene.id, spec.name) not in CONFIRMED_ELSEWHERE:
            lhs, rhs = spec.where
            conditions[_condition_key(model, spec)] = model.definition(lhs - rhs)
    return [Event(key, lambda s, e=expr: model.evaluate(e, model.quantities(s)), terminal=False)
            for key, expr in conditions.items()]


def _follow_motion(model: SceneModel, start, conditions: list[Event]):
    """Integrate chunk by chunk until every condition has occurred (or T_MAX).

    Returns the sampled states up to the first release of a unilateral contact, that time, and
    the first state where each condition holds.
    """
    # A unilateral contact holds while its multiplier keeps its starting sign.
    releases = [multiplier_zero(k.name, terminal=False) for k in model.scene.constraints
                if k.kind == "unilateral"]
    t, q, qdot = start.t, start.q, start.qdot
    states: list[Snapshot] = []
    released_at = math.inf
    found: dict[str, Snapshot] = {}
    while True:
        motion = simulate(model.numeric, q, qdot, t + CHUNK, t0=t, events=conditions + releases,
                          sample_times=np.linspace(t, t + CHUNK, SAMPLES_PER_CHUNK))
        hits = [motion.first(r.name) for r in releases if motion.first(r.name) is not None]
        release = min(hits, key=lambda s: s.t, default=None)
        if release is not None and release.t < released_at:
            # Sample the stretch up to the release as densely as a whole chunk: a contact
            # may let go long before the chunk ends.
            # (a contact whose force starts at zero lets go at once: nothing to sample before it)
            dense = (simulate(model.numeric, q, qdot, release.t, t0=t,
                              sample_times=np.linspace(t, release.t, SAMPLES_PER_CHUNK)).samples
                     if release.t > t else [])
            states += list(dense) + [release]
            released_at = release.t
        elif released_at == math.inf:
            states += motion.samples
        for event in conditions:
            # A condition that holds at the start (θ̇ = 0 of a swing released at rest) is not reached
            # there: the motion leaves it, as the engine reads it (the integration's first microsecond
            # may cross it back and forth by rounding).
            hits = [s for s in motion.events.get(event.name, []) if s.t > start.t + 1e-6]
            if event.name not in found and hits:
                found[event.name] = hits[0]
        t, q, qdot = motion.end.t, motion.end.q, motion.end.qdot
        if len(found) == len(conditions) or t >= T_MAX:
            return [s for s in states if s.t <= released_at], found


def _push_energy_ratio(model: SceneModel, start, end: Snapshot) -> float:
    """Energy the push added (at rest, all of its kinetic energy) over the energy exchanged."""
    if not start.pushed:
        return 0.0
    added = float(model.numeric.kinetic(list(start.q), list(start.qdot), start.t))
    exchanged = abs(float(model.numeric.potential(list(end.q), end.t))
                    - float(model.numeric.potential(list(start.q), start.t)))
    return added / exchanged if exchanged else math.inf


@functools.lru_cache(maxsize=None)
def run_experiment(path: Path) -> Experiment:
    # Imported here so that a missing engine fails these tests instead of their collection.
    from grader.mechanics.lagrange import derive
    from grader.mechanics.scene import load_scene

    scene = load_scene(path)
    derivation = derive(scene)
    closed_forms = dict(derivation.answers)
    # A numeric answer without a closed form: the value the checker finds at the scene's numbers.
    references = {r["name"]: r for r in derivation.references()}
    for name in derivation.implicit:
        closed_forms[name] = sympy.Float(_implicit_value(references[name]), 30)
    fallback = {n: reasonable_value(p) for n, p in scene.parameters.items() if p.value is None}
    model = SceneModel(scene, fallback)

    start = model.initial_state(push=PUSH)
    conditions = _where_events(model)
    # where t = 0: the first sample, the start itself, which no crossing reports; not looked for along the
    # motion (which then ran on to T_MAX: 30 s of a stick falling through the ice after it landed, 37 s of CI)
    at_start = [e for e in conditions if e.name in (str(scene.time), str(-scene.time))]
    states, found = _follow_motion(model, start, [e for e in conditions if e not in at_start])
    for event in at_start:
        found[event.name] = min(states, key=lambda s: s.t)
    # Quantities in time order, so that parametrization angles follow the motion continuously.
    # A fresh model does it: the events above already walked the other one's parametrization
    # guess far along the motion (four turns down a helix), where Gauss–Newton would have to
    # come back from.
    states.sort(key=lambda s: s.t)
    # The states where conditions hold are taken in the same time order, for the same reason.
    model = SceneModel(scene, fallback)
    quantities = {}
    for state in sorted(states + list(found.values()), key=lambda s: s.t):
        quantities[id(state)] = model.quantities(state)
    return Experiment(
        model=model,
        closed_forms=closed_forms,
        samples=[quantities[id(s)] for s in states],
        where={e.name: (quantities[id(found[e.name])] if e.name in found else None) for e in conditions},
        push_energy_ratio=_push_energy_ratio(model, start, states[-1]),
    )


def _implicit_value(reference: dict) -> float:
    """What the checker takes as the value of a numeric answer without a closed form, at the
    scene's own numbers (its unknown at the root grader.expressions.implicit finds)."""
    from grader.answers.numeric import reference_value

    values = {name: spec["value"] for name, spec in reference["parameters"].items() if "value" in spec}
    return reference_value(reference["reference"], reference["variables"], values, reference["implicit"])


def test_there_are_problems_to_confirm():
    assert SCENE_FILES, f"no scene files in {PROBLEMS}: nothing would be confirmed"


@pytest.mark.parametrize("path", SCENE_FILES, ids=lambda p: p.stem)
def test_motion_is_long_enough_to_confirm_the_answers(path):
    experiment = run_experiment(path)
    assert len(experiment.samples) >= 5, "too little motion before a contact released to confirm anything"
    assert experiment.samples[-1]["t"] > experiment.samples[0]["t"]


@pytest.mark.parametrize("path", SCENE_FILES, ids=lambda p: p.stem)
def test_starting_push_is_negligible(path):
    assert run_experiment(path).push_energy_ratio < 1e-12


@pytest.mark.parametrize("path, answer", _answer_ids(), ids=lambda v: v.stem if isinstance(v, Path) else v)
def test_answer_agrees_with_the_numerical_experiment(path, answer):
    experiment = run_experiment(path)
    model = experiment.model
    spec = model.scene.answer(answer)
    closed_form = experiment.closed_forms[answer]

    if spec.where is not None:
        state = experiment.where[_condition_key(model, spec)]
        lhs, rhs = spec.where
        assert state is not None, f"the motion never reaches {lhs} = {rhs} within {T_MAX} s"
        numeric, exact = model.evaluate(spec.expr, state), model.evaluate(closed_form, state)
        assert abs(numeric - exact) <= RTOL * max(abs(exact), 1e-12), (
            f"{answer} where {lhs} = {rhs}: numerical {numeric!r}, engine {closed_form} = {exact!r}")
        return

    pairs = [(model.evaluate(spec.expr, s), model.evaluate(closed_form, s), s) for s in experiment.samples]
    scale = max(max(abs(exact) for _, exact, _ in pairs), 1e-12)
    for numeric, exact, state in pairs:
        assert abs(numeric - exact) <= RTOL * max(abs(exact), scale), (
            f"{answer} at t = {state['t']:.6g}: numerical {numeric!r}, engine {closed_form} = {exact!r}")


def test_a_contact_whose_force_starts_at_zero_lets_go_at_the_start():
    """Launched over the top of a sphere with v² = gR the normal force starts at zero: the harness
    records the release at t = 0 instead of integrating an empty stretch before it (which raised)."""
    from grader.mechanics.scene import parse_scene

    text = (PROBLEMS / "sphere.toml").read_text(encoding="utf-8")
    text = text.replace("theta = 0\nthetadot = 0", "theta = 0\nthetadot = 3.5")  # R θ̇² = 9.8 ≈ g
    scene = parse_scene(text.replace('value = 9.81', 'value = 9.8'), "sphere.toml")
    model = SceneModel(scene, {})
    start = model.initial_state(push=0.0)
    states, _ = _follow_motion(model, start, [])
    assert states and max(s.t for s in states) <= start.t + 1e-6
