"""Domains, variables, LaTeX names and the namespace."""

import math
import random

import numpy as np
import pytest
import sympy

from grader.expressions import Domain, Namespace, Variable, parse_domain
from grader.expressions.names import latex_name


@pytest.mark.parametrize("spec, assumptions", [
    ("positive", {"positive": True}),
    ("nonnegative", {"nonnegative": True}),
    ("real", {"real": True}),
    ([0.1, 2], {"positive": True}),         # an interval inside (0, inf) is positive
    ([0, 1], {"nonnegative": True}),
    ([-1, 1], {"real": True}),
    ([-2, -1], {"negative": True}),
    (["-pi/2", "pi/2"], {"real": True}),
])
def test_domain_assumptions(spec, assumptions):
    assert parse_domain(spec).assumptions == assumptions


@pytest.mark.parametrize("spec, inside, outside", [
    ("positive", [1e-9, 5.0], [0.0, -1.0, math.inf, math.nan]),
    ("nonnegative", [0.0, 3.0], [-1e-9]),
    ("real", [-7.0, 0.0], [math.inf, "abc", 1j]),
    ([0, "pi"], [0.0, 3.14], [3.15, -0.01]),
])
def test_domain_contains(spec, inside, outside):
    domain = parse_domain(spec)
    assert all(domain.contains(v) for v in inside)
    assert not any(domain.contains(v) for v in outside)


@pytest.mark.parametrize("spec", ["positive", "nonnegative", "real", [0, 1], [-1, 1], [2, 3], [-5, -4]])
@pytest.mark.parametrize("rng", [random.Random(7), np.random.default_rng(7)], ids=["random", "numpy"])
def test_samples_stay_inside_away_from_ends_and_zero(spec, rng):
    domain = parse_domain(spec)
    for _ in range(200):
        value = domain.sample(rng)
        assert isinstance(value, float) and domain.contains(value)
        assert abs(value) >= 0.05                      # tiny magnitudes hide wrong answers
        if domain.kind == "interval":
            width = domain.hi - domain.lo
            assert domain.lo + 0.04 * width < value < domain.hi - 0.04 * width


def test_real_samples_take_both_signs():
    rng = random.Random(3)
    values = [parse_domain("real").sample(rng) for _ in range(100)]
    assert min(values) < 0 < max(values)


@pytest.mark.parametrize("spec", ["complex", [1, 0], [1], [True, 2], ["x", 1]])
def test_bad_domains_are_refused(spec):
    with pytest.raises(ValueError):
        parse_domain(spec)


@pytest.mark.parametrize("name, latex", [
    ("theta", r"\theta"), ("thetadot", r"\dot{\theta}"), ("thetaddot", r"\ddot{\theta}"),
    ("m1", "m_{1}"), ("lambda_surface", r"\lambda_{\mathrm{surface}}"),
    ("Q_roll_s", r"Q_{\mathrm{roll},s}"), ("Omega", r"\Omega"), ("omega", r"\omega"),
    ("x", "x"), ("rdot", r"\dot{r}"), ("phi2dot", r"\dot{\phi}_{2}"), ("m_A", "m_{A}"),
])
def test_latex_names(name, latex):
    assert latex_name(name) == latex
    assert Variable(name, "length").latex == latex


def test_variable_symbol_uses_domain_assumptions():
    v = Variable("l", "length", "positive", "parameter")
    assert v.symbol == sympy.Symbol("l", positive=True)
    assert v.symbol != sympy.Symbol("l")
    assert v.dimension.describe() == "a length (m)"


@pytest.mark.parametrize("kwargs", [
    {"name": "2x", "dimension": "length"},
    {"name": "_x", "dimension": "length"},
    {"name": "x", "dimension": "furlong"},
    {"name": "x", "dimension": "length", "kind": "wizard"},
])
def test_bad_variables_are_refused(kwargs):
    with pytest.raises(ValueError):
        Variable(**kwargs)


def test_namespace_lookups(ns):
    theta = ns.symbol("theta")
    assert ns.dimensions()[theta].is_dimensionless
    assert ns.latex_names()[ns.symbol("thetadot")] == r"\dot{\theta}"
    assert "m" in ns and ns["m"].kind == "parameter"
    assert [v.name for v in ns.variables][:3] == ["m", "m1", "g"]
    with pytest.raises(KeyError, match="thetaa"):
        ns.symbol("thetaa")


@pytest.mark.parametrize("variables", [
    [Variable("x", "length"), Variable("x", "mass")],
    [Variable("sin", "length")],
])
def test_namespace_refuses_duplicates_and_function_names(variables):
    with pytest.raises(ValueError):
        Namespace(variables)


def test_namespace_from_answer_checker_spec():
    ns = Namespace.from_spec({"m": {"dimension": "mass", "domain": "positive"},
                              "theta": {"dimension": "angle", "domain": [0, 1], "kind": "coordinate"}})
    assert ns.symbol("m").is_positive and ns["theta"].kind == "coordinate"


def test_namespace_tables_are_handed_out_as_copies(ns):
    # They are built once per namespace; a caller changing its copy must not change the namespace.
    ns.dimensions().clear()
    ns.latex_names()[ns.symbol("m")] = "M"
    assert ns.dimensions()[ns.symbol("m")].describe() == "a mass (kg)"
    assert ns.latex_names()[ns.symbol("m")] == "m"


@pytest.mark.parametrize("spec", [["0", "pi/2"], ["-pi", "pi"], ["pi/6", "5*pi/6"], ["-pi/2", "pi/3"]])
def test_an_end_written_with_pi_is_held_by_the_interval(spec):
    # float("pi/2") is 6e-17 below π/2: rounded outward, the interval holds its true ends, so that cos θ is
    # not proved nonzero on [0, "pi/2"]
    import sympy

    domain = parse_domain(spec)
    lo, hi = (sympy.sympify(s) for s in spec)  # the test's own text
    assert sympy.Float(domain.lo, 40) <= lo.evalf(40) and hi.evalf(40) <= sympy.Float(domain.hi, 40)
    assert parse_domain([0, 1.5]).hi == 1.5 and parse_domain(["0", "1/2"]).hi == 0.5  # exact ends stay
