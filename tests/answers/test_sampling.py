"""Sample points lie in the declared domains and are reproducible."""

import math

import pytest
import sympy

from grader.answers.sampling import STRESS_EVERY, Sampler, seed_for
from grader.expressions import parse_domain


def test_points_stay_inside_interval_domains():
    alpha = sympy.Symbol("alpha", nonnegative=True)
    s = Sampler({alpha: parse_domain([0, "pi/2"])}, seed=seed_for("g*sin(alpha)"))
    assert all(0 <= s.point(i)[alpha] <= math.pi / 2 for i in range(50))


def test_positive_unbounded_variables_get_extreme_scales_on_stress_points():
    m1 = sympy.Symbol("m1", positive=True)
    s = Sampler({m1: parse_domain("positive")}, seed=1)
    stressed = [s.point(i)[m1] for i in range(STRESS_EVERY - 1, 40, STRESS_EVERY)]
    assert min(stressed) < 1e-2 or max(stressed) > 1e2
    assert all(v > 0 for v in stressed)


def test_the_same_reference_is_probed_at_the_same_points():
    m = sympy.Symbol("m", positive=True)
    a = Sampler({m: parse_domain("positive")}, seed_for("m*g/3", "expression"))
    b = Sampler({m: parse_domain("positive")}, seed_for("m*g/3", "expression"))
    assert [a.point(i) for i in range(8)] == [b.point(i) for i in range(8)]


def test_wide_points_span_the_whole_scale_of_a_real_domain():
    x = sympy.Symbol("x", real=True)
    s = Sampler({x: parse_domain("real")}, seed=4)
    values = [s.wide_point(i)[x] for i in range(60)]
    assert max(values) > 1e3 and min(values) < -1e3 and min(abs(v) for v in values) < 1e-1


def test_wide_points_do_not_change_the_ordinary_points():
    x = sympy.Symbol("x", real=True)
    a, b = Sampler({x: parse_domain("real")}, seed=4), Sampler({x: parse_domain("real")}, seed=4)
    b.wide_point(10)
    assert [a.point(i) for i in range(8)] == [b.point(i) for i in range(8)]


def test_real_variables_get_both_signs_and_every_scale_on_stress_points():
    x = sympy.Symbol("x", real=True)
    s = Sampler({x: parse_domain("real")}, seed=7)
    stressed = [s.point(i)[x] for i in range(STRESS_EVERY - 1, 200, STRESS_EVERY)]
    assert max(stressed) > 1e3 and min(stressed) < -1e3


def test_stress_on_real_variables_leaves_the_other_points_as_they_were():
    x, m = sympy.Symbol("x", real=True), sympy.Symbol("m", positive=True)
    with_x = Sampler({x: parse_domain("real"), m: parse_domain("positive")}, seed=3)
    without = Sampler({x: parse_domain("real"), m: parse_domain("positive")}, seed=3, stress=False)
    ordinary = [i for i in range(12) if i % STRESS_EVERY != STRESS_EVERY - 1]
    assert [with_x.point(i) for i in ordinary] == [without.point(i) for i in ordinary]


def test_a_variable_declared_below_another_stays_below_it_at_every_point():
    """{a: R}: a hoop's off-centre mass inside its radius; the ordinary, stress and wide points all
    keep a < R, and a sampler without both symbols ignores the pair."""
    positive = parse_domain("positive")
    a, R, m = sympy.symbols("a R m", positive=True)
    sampler = Sampler({a: positive, R: positive, m: positive}, seed=7, below={a: R})
    points = [sampler.point(i) for i in range(4 * STRESS_EVERY * 5)] + [sampler.wide_point(i) for i in range(20)]
    assert all(p[a] < p[R] for p in points)
    unordered = Sampler({a: positive, R: positive}, seed=7)
    assert any(unordered.point(i)[a] > unordered.point(i)[R] for i in range(20))  # the order is not by chance
    assert Sampler({a: positive, m: positive}, seed=7, below={a: R}).below == {}


def test_the_ordinary_points_of_an_interval_take_each_of_its_parts_once_per_block():
    # eight independent draws all miss |θ| > π/2 on [-π, π] once in 256 checks; the parts do not
    theta = sympy.Symbol("theta", real=True)
    s = Sampler({theta: parse_domain([-4, 2])}, seed=seed_for("theta"))
    for block in range(5):
        ordinary = [s.point(8 * block + j)[theta] for j in range(8) if j % STRESS_EVERY != STRESS_EVERY - 1]
        assert sorted(math.floor(v) for v in ordinary) == [-4, -3, -2, -1, 0, 1]


@pytest.mark.parametrize("domain, band", [
    ([-1, 10], (-1, 0)),          # the side of zero ordinary draws hardly reach
    ([-0.2, 3.1416], (-0.2, 0)),
    ([0, 3.3], (3.135, 3.3)),      # the outer end, beyond pi, where acos(cos θ) is no longer θ
    ([-3.1416, 3.1416], (-0.29, 0.29)),
])
def test_stress_points_of_an_interval_reach_the_bands_ordinary_points_avoid(domain, band):
    x = sympy.Symbol("x", real=True)
    s = Sampler({x: parse_domain(domain)}, seed=seed_for("x", str(domain)))
    stressed = [s.point(i)[x] for i in range(STRESS_EVERY - 1, 16 * STRESS_EVERY, STRESS_EVERY)]
    assert any(band[0] < v < band[1] for v in stressed)
    assert all(domain[0] < v < domain[1] for v in stressed)
