"""How typed names resolve to the namespace's variables."""

import pytest
import sympy

from grader.expressions import ExpressionError, Namespace, Variable
from grader.expressions.names import derivative_name, resolve_name


@pytest.mark.parametrize("typed, order, canonical", [
    ("theta", 0, "theta"),
    ("theta_dot", 0, "thetadot"),
    ("theta_ddot", 0, "thetaddot"),
    ("m_1", 0, "m1"),
    ("theta", 1, "thetadot"),
    ("theta", 2, "thetaddot"),
    ("thetadot", 1, "thetaddot"),
    ("lambda_surface", 0, "lambda_surface"),
])
def test_spellings_resolve_to_the_canonical_variable(ns, typed, order, canonical):
    resolved = resolve_name(typed, ns, order=order)
    assert resolved.kind == "symbol" and resolved.value == ns.symbol(canonical)


@pytest.mark.parametrize("base, order, name", [("x", 1, "xdot"), ("x", 2, "xddot"), ("xdot", 1, "xddot")])
def test_derivative_names(base, order, name):
    assert derivative_name(base, order) == name


@pytest.mark.parametrize("typed, parts", [
    ("mg", ["m", "g"]),
    ("mgl", ["m", "g", "l"]),
    ("m1g", ["m1", "g"]),
    ("mthetadot", ["m", "thetadot"]),
    ("mgcos", ["m", "g", "cos"]),
    ("sin2x", ["sin", "2", "x"]),
    ("pir", ["pi", "r"]),
])
def test_glued_names_split_into_known_names(ns, typed, parts):
    resolved = resolve_name(typed, ns)
    assert resolved.kind == "split" and resolved.value == parts
    assert resolved.notes and resolved.notes[0].startswith(f"read '{typed}' as")


@pytest.mark.parametrize("typed", ["E", "e", "pi"])
def test_constants(ns, typed):
    assert resolve_name(typed, ns).value in (sympy.E, sympy.pi)


def test_functions_are_recognised_in_any_case(ns):
    assert resolve_name("Sin", ns).value == "sin" and resolve_name("Abs", ns).value == "abs"


@pytest.mark.parametrize("typed, called, code", [
    ("thetta", False, "unknown_name"),
    ("factorial", True, "unsupported_function"),
    ("__class__", False, "unsupported_function"),
    ("import", False, "unsupported_function"),
    ("zdot", False, "unknown_name"),
])
def test_refusals(ns, typed, called, code):
    with pytest.raises(ExpressionError) as err:
        resolve_name(typed, ns, called=called)
    assert err.value.code == code


def test_missing_derivative_says_which_variable_is_missing():
    ns = Namespace([Variable("x", "length")])
    with pytest.raises(ExpressionError, match="no variable xdot"):
        resolve_name("x", ns, order=1, typed="x'")


def test_unknown_long_name_is_shortened_in_the_message(ns):
    with pytest.raises(ExpressionError) as err:
        resolve_name("q" * 500, ns)
    assert len(err.value.message) < 100
