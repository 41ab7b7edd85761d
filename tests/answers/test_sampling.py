"""Sample points lie in the declared domains and are reproducible."""

import math

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
