"""Equations of motion: the reference times a nonzero factor free of the state, and systems that span it."""

import pytest

from grader.answers import check

PENDULUM_EOM = "thetaddot = -g/l*sin(theta)"


@pytest.mark.parametrize("answer", [
    "thetaddot + (g/l) sin(theta) = 0",
    "l thetaddot = -g sin theta",
    "m l^2 thetaddot + m g l sin(theta) = 0",   # multiplied by m l^2, free of the state
    "g*sin(theta) = -l*thetaddot",
])
def test_pendulum_equation_in_any_scaled_form_is_right(pendulum, answer):
    v = check(PENDULUM_EOM, answer, pendulum, kind="equation")
    assert v.verdict == "equivalent", v.reason


@pytest.mark.parametrize("answer, why", [
    ("thetaddot*cos(theta) = -g/l*sin(theta)*cos(theta)", "factor cos(theta) vanishes on (-pi, pi)"),
    ("thetaddot*thetadot = -g/l*sin(theta)*thetadot", "factor thetadot vanishes"),
    ("thetaddot = -g/l*theta", "the small-angle equation is another equation"),
    ("thetaddot = -g/l*sin(theta)*(1 + 10^-9)", "off by 1e-9"),
])
def test_state_dependent_factors_and_near_misses_are_wrong(pendulum, answer, why):
    v = check(PENDULUM_EOM, answer, pendulum, kind="equation")
    assert v.verdict == "not_equivalent", why
    assert v.certainty == "proved" and v.counterexample is not None


def test_state_is_inferred_from_dot_names_or_given_explicitly(pendulum):
    # without kinds, theta/thetadot/thetaddot are the state because their names say so
    v = check(PENDULUM_EOM, "thetaddot*cos(theta) = -g/l*sin(theta)*cos(theta)", pendulum, kind="equation")
    assert v.verdict == "not_equivalent"
    # declaring only thetaddot as state makes a cos(theta) factor acceptable
    v = check(PENDULUM_EOM, "thetaddot*cos(theta) = -g/l*sin(theta)*cos(theta)", pendulum, kind="equation",
              state=["thetaddot"])
    assert v.verdict == "equivalent"


ATWOOD_SYSTEM = {
    "m1": {"dimension": "mass", "domain": "positive"},
    "m2": {"dimension": "mass", "domain": "positive"},
    "g": {"dimension": "acceleration", "domain": "positive"},
    "xddot": {"dimension": "acceleration", "kind": "acceleration"},
    "yddot": {"dimension": "acceleration", "kind": "acceleration"},
    "T": {"dimension": "force", "kind": "force"},
}
SYSTEM = "m1*xddot = -T; m2*yddot = m2*g - T; xddot + yddot = 0"


@pytest.mark.parametrize("answer, expected", [
    ("xddot = -yddot; m2*yddot = m2*g - T; m1*xddot + T = 0", "equivalent"),       # reordered
    ("m1*xddot - m2*yddot = -m2*g; m2*yddot = m2*g - T; xddot + yddot = 0", "equivalent"),  # combined
    ("m1*xddot = T; m2*yddot = m2*g - T; xddot + yddot = 0", "not_equivalent"),    # a sign
    ("m1*xddot = -T; m2*yddot = m2*g - T", "not_equivalent"),                      # one missing
    ("m1*xddot = -T; m2*yddot = m2*g - T; m1*xddot - m2*yddot = -m2*g", "not_equivalent"),  # dependent
])
def test_half_atwood_systems_must_span_the_same_equations(answer, expected):
    assert check(SYSTEM, answer, ATWOOD_SYSTEM, kind="equation").verdict == expected


def test_an_expression_alone_is_read_as_equal_to_zero(pendulum):
    v = check(PENDULUM_EOM, "thetaddot + g/l*sin(theta)", pendulum, kind="equation")
    assert v.verdict == "equivalent" and any("= 0" in n for n in v.parsed["notes"])


def test_an_equation_whose_sides_differ_in_dimension_is_rejected_in_words(pendulum):
    v = check(PENDULUM_EOM, "thetaddot = -g*sin(theta)", pendulum, kind="equation")
    assert v.verdict == "not_equivalent" and v.feedback[0]["code"] == "dimension"
    assert "acceleration" in v.reason


# -- equations by the right rule: a factor nonzero on the whole declared domain ---------------------
POLAR = {
    "g": {"dimension": "acceleration", "domain": "positive"},
    "r": {"dimension": "length", "domain": "positive", "kind": "coordinate"},
    "rdot": {"dimension": "velocity", "kind": "velocity"},
    "rddot": {"dimension": "acceleration", "kind": "acceleration"},
    "thetadot": {"dimension": "angular_velocity", "kind": "velocity"},
    "x": {"dimension": "dimensionless", "kind": "coordinate"},
}
RADIAL = "rddot = r thetadot^2 - g"


@pytest.mark.parametrize("answer", [
    "r^2 rddot = r^3 thetadot^2 - g r^2",          # r**2 with r > 0
    "(rddot - r thetadot^2 + g)/r = 0",            # 1/r: a length that stays positive
    "(1 + x^2)(rddot - r thetadot^2 + g) = 0",     # 1 + x**2 never vanishes
])
def test_a_state_dependent_factor_nonzero_on_the_whole_domain_is_right(answer):
    v = check(RADIAL, answer, POLAR, kind="equation")
    assert v.verdict == "equivalent" and v.certainty == "proved", v.reason


@pytest.mark.parametrize("answer", [
    "x (rddot - r thetadot^2 + g) = 0",            # x is real: zero at x = 0
    "thetadot (rddot - r thetadot^2 + g) = 0",
])
def test_a_state_dependent_factor_that_can_vanish_is_refused_with_the_reason(answer):
    v = check(RADIAL, answer, POLAR, kind="equation")
    assert v.verdict == "not_equivalent" and "zero somewhere in the declared domain" in v.reason
    assert v.counterexample is not None


@pytest.mark.parametrize("domain, expected", [([-1.5, 1.5], "equivalent"), ([-3.1416, 3.1416], "not_equivalent")])
def test_cos_theta_is_a_right_factor_only_where_it_cannot_vanish(pendulum, domain, expected):
    variables = {**pendulum, "theta": {"dimension": "angle", "domain": domain}}
    v = check(PENDULUM_EOM, "thetaddot*cos(theta) = -g/l*sin(theta)*cos(theta)", variables, kind="equation")
    assert v.verdict == expected


@pytest.mark.parametrize("answer, expected", [
    ("x - 1 = 0", "equivalent"),                   # x**2 - 1 = (x - 1)(x + 1), and x + 1 > 0 for x > 0
    ("(x - 1)(x + 1) = 0", "equivalent"),
    ("x^2 - x = 0", "equivalent"),                 # x (x - 1): x > 0 adds no root
    ("x - 2 = 0", "not_equivalent"),
])
def test_a_factored_polynomial_with_the_same_roots_on_the_domain_is_right(answer, expected):
    variables = {"x": {"dimension": "dimensionless", "domain": "positive", "kind": "coordinate"}}
    v = check("x^2 = 1", answer, variables, kind="equation")
    assert v.verdict == expected, v.reason


@pytest.mark.parametrize("answer, expected", [
    ("(1 + theta^2)^400 (l thetaddot + g sin theta) = 0", "equivalent"),   # a high power of a nonzero factor
    ("theta^400 (l thetaddot + g sin theta) = 0", "not_equivalent"),       # vanishes at theta = 0
])
def test_high_powers_of_a_factor_are_decided_without_expanding_them(pendulum, answer, expected):
    import time

    started = time.monotonic()
    v = check(PENDULUM_EOM, answer, pendulum, kind="equation")
    assert v.verdict == expected and time.monotonic() - started < 2.0
