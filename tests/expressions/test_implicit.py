"""The implicit-value rule: the k-th real root of f(x) = 0 in an interval, shared by engine and checker."""

from __future__ import annotations

import math

import pytest

from grader.expressions.implicit import Implicit, ImplicitError, real_roots


@pytest.mark.parametrize("f, lo, hi, expected", [
    # buckling of an upright pendulum held by a torsion spring: θ = 0 and the tilted equilibrium
    (lambda x: 9.81 * math.sin(x) - 5 * x, 0.0, math.pi, [0.0, 1.8730555106317808]),
    # every root of a cubic, in increasing order
    (lambda x: (x + 1.5) * (x - 0.25) * (x - 2), -3.0, 3.0, [-1.5, 0.25, 2.0]),
    # Kepler's equation E − e sin E = M, one root
    (lambda x: x - 0.7 * math.sin(x) - 1.2, 0.0, 2 * math.pi, [1.8690879651369636]),
    # an exact zero at an end of the interval counts
    (lambda x: x * x - 1, 0.0, 1.0, [1.0]),
])
def test_roots_are_found_in_increasing_order_to_float_precision(f, lo, hi, expected):
    roots = real_roots(f, lo, hi)
    assert len(roots) == len(expected)
    for got, want in zip(roots, expected):
        assert got == pytest.approx(want, rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("f, lo, hi", [
    (lambda x: 1 / x, -1.0, 1.0),                    # a sign change across a pole
    (lambda x: math.tan(x) - 100, 1.0, 2.0),         # tan's pole at π/2 after its root at 1.5608 ...
])
def test_a_sign_change_across_a_pole_is_not_a_root(f, lo, hi):
    for r in real_roots(f, lo, hi):
        assert abs(f(r)) < 1e-6


def test_a_function_undefined_on_part_of_the_interval_has_its_roots_where_it_is_defined():
    roots = real_roots(lambda x: math.sqrt(x - 1) - 0.5, 0.0, 3.0)  # ValueError below x = 1
    assert roots == [pytest.approx(1.25, rel=1e-12)]


def test_no_root_is_an_empty_list():
    assert real_roots(lambda x: x * x + 1, -5.0, 5.0) == []


def test_roots_are_searched_in_a_bounded_interval_only():
    with pytest.raises(ValueError, match="bounded"):
        real_roots(lambda x: x, 0.0, math.inf)


def test_the_rule_picks_its_root_and_says_when_there_are_fewer():
    rule = Implicit("g*sin(theta) - k*theta", "theta", 0.0, math.pi, 1)
    assert rule.solve(lambda x: 9.81 * math.sin(x) - 5 * x) == pytest.approx(1.8730555106317808)
    assert rule.solve(lambda x: 9.81 * math.sin(x) - 12 * x) is None  # only θ = 0: no tilted equilibrium


@pytest.mark.parametrize("data, message", [
    ("theta", "must be an object"),
    ({"condition": "", "unknown": "theta", "interval": [0, 1], "root": 0}, "condition"),
    ({"condition": "x", "unknown": "theta", "interval": [1, 0], "root": 0}, "interval"),
    ({"condition": "x", "unknown": "theta", "interval": [0, float("inf")], "root": 0}, "interval"),
    ({"condition": "x", "unknown": "theta", "interval": [0, 1], "root": -1}, "root"),
    ({"condition": "x", "unknown": "theta", "interval": [0, 1], "root": True}, "root"),
])
def test_malformed_rules_are_refused_with_their_key(data, message):
    with pytest.raises(ImplicitError, match=message):
        Implicit.from_json(data)
