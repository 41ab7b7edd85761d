"""Red team 2 of the simulation's effects, on scenes in tests/simulate/scenes/ written for it: each
effect happens where its textbook closed form puts it, each regime keeps what it must keep, and an
effect the scene does not declare never happens (the same geometry with a bilateral constraint).

Closed forms (each derived by hand in the test that uses it):
- impacts on bodies that rest against others: the blow is passed on contact by contact (Newton's
  cradle: the last ball leaves at v; a small ball on a big one dropped on the floor leaves at
  v (3M − m)/(M + m)), and a contact that could only be kept by pulling lets go (the string of an
  Atwood machine whose mass is struck upwards goes slack);
- block on a platform on a spring: it leaves where the spring has its natural length;
- particle on a cylinder accelerating sideways at a: it leaves where cos ψ = (2/3) g/√(g² + a²),
  ψ from the effective upward direction (a, g);
- bob on a string in polar coordinates: slack where cos θ = (2gl − v₀²)/(3gl), a parabola inside
  the circle, then the jerk keeps the tangential velocity only;
- yo-yo struck upwards: taut again after 2v/g, then ẏ = v m b²/(m b² + I).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from grader.mechanics.scene import load_scene, parse_scene
from grader.simulate.trajectory import simulate_scene

SCENES = Path(__file__).resolve().parent / "scenes"
G = 9.81


def scene(name: str, kind: str | None = None):
    """A scene of tests/simulate/scenes, with its unilateral constraints made ``kind``."""
    text = (SCENES / f"{name}.toml").read_text()
    if kind is not None:
        text = text.replace('kind = "unilateral"', f'kind = "{kind}"')
    return parse_scene(text, source=f"{name}.toml")


def effects(motion) -> list[tuple[str, str]]:
    return [(e.effect, e.constraint) for e in motion.events]


def between(motion, start: float, stop: float) -> np.ndarray:
    return (motion.t > start) & (motion.t < stop)


# -- impacts on bodies resting against others ------------------------------------------------------

@pytest.mark.parametrize("mb, e", [(1.0, 1.0), (1.0, 0.0), (0.5, 0.5)])
def test_a_struck_atwood_mass_lets_its_string_go_slack_and_the_string_jerks_taut_later(mb, e):
    # Before: the impact was solved with the string held rigid, so the string pushed mass 2 down
    # (ẏ₂ = +2.6 m/s for e = 1) and the ball bounced off both masses at once.
    m, L, h, d, u = 1.0, 3.0, 1.5, 0.5, 5.0
    motion = simulate_scene(load_scene(SCENES / "atwood_struck_from_below.toml"), {"mb": mb, "e": e},
                            t_end=0.6, samples=601)
    t_hit = (u - math.sqrt(u * u - 2 * G * d)) / G
    u_hit = math.sqrt(u * u - 2 * G * d)
    w = (1 + e) * mb * u_hit / (mb + m)           # mass 1 alone takes the blow: the string is slack
    ball = (mb - e * m) * u_hit / (mb + m)
    expected = ([("contact", "hit")] if e == 0 else [("bounce", "hit")]) + [("release", "string"),
                                                                            ("contact", "string")]
    if e == 0:
        expected.append(("release", "hit"))  # the jerk pulls mass 1 up off the ball
    assert effects(motion) == expected
    hit, slack, taut = motion.events[:3]
    assert hit.t == slack.t == pytest.approx(t_hit, abs=1e-12)
    assert (hit.state["y1dot"], hit.state["y2dot"], hit.state["ybdot"]) == pytest.approx((-w, 0.0, -ball), abs=1e-9)
    # Slack: both masses fall freely, L − y1 − y2 = w τ − g τ², taut again at τ = w/g, when mass 1
    # is at rest and mass 2 falls at w; the inelastic jerk leaves ∓w/2 (equal masses).
    assert taut.t == pytest.approx(t_hit + w / G, abs=1e-10)
    assert (taut.state["y1dot"], taut.state["y2dot"]) == pytest.approx((-w / 2, w / 2), abs=1e-9)
    flight = between(motion, slack.t, taut.t)
    tau = motion.t[flight] - t_hit
    np.testing.assert_allclose(motion.q[flight, 1], L - h + G * tau ** 2 / 2, atol=1e-10)
    assert not motion.active[flight, 0].any()
    energy = (m / 2 * (motion.qdot[:, 0] ** 2 + motion.qdot[:, 1] ** 2) + mb / 2 * motion.qdot[:, 2] ** 2
              - G * (m * motion.q[:, 0] + m * motion.q[:, 1] + mb * motion.q[:, 2]))
    assert np.ptp(energy[flight]) < 1e-9
    after = motion.t > taut.t
    assert energy[flight][0] - energy[after][0] == pytest.approx(m * w * w / 4, rel=1e-8)
    assert np.all(motion.multipliers[motion.active[:, 0], 0] >= 0)


@pytest.mark.parametrize("e, m3, final", [
    (1.0, 0.2, (0.0, 0.0, 1.0)),            # the blow passes through: the last ball leaves at v
    (1.0, 0.4, (-1 / 3, 0.0, 2 / 3)),       # ball 2 bounces back off the heavy ball 3 and hits ball 1
    (0.0, 0.2, (1 / 3, 1 / 3, 1 / 3)),      # inelastic: all three together
    (0.0, 0.4, (1 / 4, 1 / 4, 1 / 4)),
])
def test_newtons_cradle_passes_the_blow_on_contact_by_contact(e, m3, final):
    # Before: the resting contact between balls 2 and 3 was held rigid whatever its restitution,
    # so with e = 1 ball 1 bounced back at −v/3 off a pair moving at 2v/3.
    v, m = 1.2, 0.2
    motion = simulate_scene(load_scene(SCENES / "newtons_cradle.toml"), {"e": e, "m3": m3}, t_end=0.5, samples=51)
    hit = motion.events[0]
    assert hit.t == pytest.approx((0.3 - 0.05) / v, abs=1e-12)
    assert {x.t for x in motion.events} == {hit.t}
    assert [hit.state[k] for k in ("x1dot", "x2dot", "x3dot")] == pytest.approx([v * x for x in final], abs=1e-9)
    after = motion.qdot[motion.t > hit.t]
    assert m * (after[:, 0] + after[:, 1]) + m3 * after[:, 2] == pytest.approx(m * v, rel=1e-12)
    kinetic = m / 2 * (after[:, 0] ** 2 + after[:, 1] ** 2) + m3 / 2 * after[:, 2] ** 2
    if e == 1.0:
        np.testing.assert_allclose(kinetic, m / 2 * v * v, rtol=1e-9)
    gaps = np.diff(motion.q, axis=1) - 0.05
    assert gaps.min() > -1e-12


@pytest.mark.parametrize("M", [0.15, 0.5, 0.05])
def test_a_small_ball_dropped_on_a_big_one_leaves_at_v_times_3M_minus_m_over_M_plus_m(M):
    # Before: the small ball resting on the big one was held to it at the floor's impact, and both
    # rebounded at v together (the small ball rose to h, not to 4h for M = 3m).
    m, h = 0.05, 1.0
    motion = simulate_scene(load_scene(SCENES / "stacked_balls_drop.toml"), {"M": M}, t_end=0.8, samples=801)
    v = math.sqrt(2 * G * h)
    bounce = motion.events[0]
    assert bounce.t == pytest.approx(math.sqrt(2 * h / G), abs=1e-10)
    big, small = v * (M - 3 * m) / (M + m), v * (3 * M - m) / (M + m)
    if big < 0:  # equal masses: the big ball goes back into the floor and rebounds at v again
        big = -big
    assert (bounce.state["y1dot"], bounce.state["y2dot"]) == pytest.approx((big, small), abs=1e-9)
    energy = M / 2 * motion.qdot[:, 0] ** 2 + m / 2 * motion.qdot[:, 1] ** 2 + G * (M * motion.q[:, 0] + m * motion.q[:, 1])
    assert np.ptp(energy) < 1e-8 * M * G * h
    assert motion.q[:, 0].min() > -1e-12 and (motion.q[:, 1] - motion.q[:, 0]).min() > 0.24 - 1e-12
