"""Numeric answers: a number with (or without) a unit, against the engine's value at the student's numbers.

A ``kind = "numeric"`` answer's reference is still the engine's closed form (``g*m/3``); the request
carries the student's parameter values (`grader.answers.randomised`), and the checker evaluates the
closed form there, in SI units. The student's text is read with a small grammar of our own (never
``float()`` on arbitrary text, never ``eval``): a decimal or scientific number (``14.7``, ``1.47e1``,
``1.47×10^1``, ``1.47·10¹``, a unicode minus), then a unit read by
:func:`grader.expressions.dimensions.parse_unit` (the one unit table). A decimal comma is refused with
a message, since ``1,470`` could be either 1.47 or 1470.

Verdicts: a number outside the tolerance is ``not_equivalent``; a unit of the wrong dimension is
``not_equivalent`` with the dimension named in words; a missing unit (when the answer has one) or an
unreadable number is ``invalid`` with a message saying what to type. Messages never state the
reference value.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Mapping, Sequence

import sympy

from grader.answers.evaluate import SCALE, FloatBackend, Unsupported, compile_expr
from grader.answers.verdict import Verdict
from grader.expressions.implicit import Implicit, ImplicitError
from grader.expressions import DimensionError, ExpressionError, Namespace, parse_dimension, parse_expression
from grader.expressions.dimensions import parse_unit

__all__ = ["DEFAULT_TOLERANCE", "NumericRequestError", "Quantity", "QuantityError", "check_numeric",
           "parse_quantity", "reference_value", "within_tolerance"]

DEFAULT_TOLERANCE = {"relative": 0.01}
_MAX_TEXT = 200
_MINUSES = str.maketrans({"\u2212": "-", "\u2012": "-", "\u2013": "-", "\ufe63": "-", "\uff0d": "-"})
_SUPERSCRIPT_DIGITS = str.maketrans("⁺⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "+-0123456789")
_NUMBER = re.compile(r"""
    \s*(?P<sign>[-+])?\s*
    (?P<mantissa>\d+(?:\.\d*)?|\.\d+)
    (?:
        [eE](?P<e>[-+]?\d+)
      | \s*[×x*·]\s*10\s*(?:\^|\*\*)\s*(?P<p>[-+]?\d+|\(\s*[-+]?\d+\s*\))
      | \s*[×x*·]\s*10(?P<s>[⁺⁻]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+)
    )?
    """, re.VERBOSE)


class QuantityError(ValueError):
    """Text that is not a number with a unit; the message says what to type instead."""


class NumericRequestError(ValueError):
    """The request (not the student's text) is wrong: no value for a parameter, a bad tolerance."""


@dataclass(frozen=True)
class Quantity:
    """A student's number and unit, read.

    Attributes
    ----------
    number : float
        The number as typed (in the student's unit).
    unit : str
        The unit as typed (stripped; ``""`` for none).
    size : float
        The unit's size in SI units (``km/h`` is 1/3.6).
    dimension : Dimension
    sig_figs : int
        Significant figures of the number as typed (``14.70`` has 4, ``0.0147`` has 3).
    """

    number: float
    unit: str
    size: float
    dimension: Any
    sig_figs: int

    @property
    def si(self) -> float:
        """The value in SI units."""
        return self.number * self.size

    @property
    def latex(self) -> str:
        """The quantity typeset (``14.7\\,\\mathrm{N}``)."""
        number = f"{self.number:g}"
        if "e" in number:
            mantissa, exponent = number.split("e")
            number = rf"{mantissa} \times 10^{{{int(exponent)}}}"
        if not self.unit:
            return number
        unit = self.unit.replace("*", r"\cdot ").replace("·", r"\cdot ").replace("°", r"^\circ")
        return rf"{number}\,\mathrm{{{unit}}}"


def parse_quantity(text: str) -> Quantity:
    """Read ``"14.7 N"``, ``"1.47e1 kg*m/s^2"``, ``"−3.2×10^-2 m"``; raises :class:`QuantityError`.

    Examples
    --------
    >>> q = parse_quantity("1.47×10^1 kN")
    >>> q.number, q.si, q.sig_figs, q.dimension.describe()
    (14.7, 14700.0, 3, 'a force (kg·m/s²)')
    >>> parse_quantity("14,7 N")
    Traceback (most recent call last):
    ...
    grader.answers.numeric.QuantityError: write a decimal point, not a comma: 14.7, not 14,7
    """
    if not isinstance(text, str) or not text.strip():
        raise QuantityError("type a number, such as 14.7 or 1.47e1, with its unit")
    if len(text) > _MAX_TEXT:
        raise QuantityError(f"a number with its unit is at most {_MAX_TEXT} characters")
    text = text.translate(_MINUSES).strip()
    comma = re.search(r"(\d+),(\d+)", text)
    if comma:
        raise QuantityError(f"write a decimal point, not a comma: {comma[1]}.{comma[2]}, not {comma[1]},{comma[2]}")
    if "," in text:
        raise QuantityError("type one number with a decimal point (no commas)")
    match = _NUMBER.match(text)
    if not match:
        raise QuantityError("type a number first, such as 14.7 or 1.47e1, then its unit")
    mantissa = match["mantissa"]
    exponent = match["e"] or (match["p"] or "").strip("() ") or (match["s"] or "").translate(_SUPERSCRIPT_DIGITS)
    try:
        number = float(f"{match['sign'] or ''}{mantissa}e{exponent or 0}")
    except (ValueError, OverflowError):
        raise QuantityError("the number is not readable") from None
    if not math.isfinite(number) or (number != 0 and not 1e-300 < abs(number) < 1e300):
        raise QuantityError("the number is too large or too small")
    rest = text[match.end():].strip()
    if rest[:1].isdigit() or rest[:1] == ".":
        raise QuantityError("type one number, without spaces inside it (1000, not 1 000)")
    if rest[:1] in "+-^(" and rest:
        raise QuantityError("type one number (such as 14.7), not a calculation")
    if rest[:1] in "*/" and re.match(r"[*/]\s*[\d.(]", rest):
        raise QuantityError("type one number (such as 14.7), not a calculation")
    try:
        size, dimension = parse_unit(rest)
    except DimensionError as error:
        raise QuantityError(f"the unit is not readable: {error}") from None
    digits = mantissa.replace(".", "").lstrip("0")
    return Quantity(number, rest, size, dimension, max(len(digits), 1))


def within_tolerance(value: float, reference: float, tolerance: Mapping[str, Any], size: float = 1.0) -> bool:
    """Whether ``value`` (SI) matches ``reference`` (SI) under the answer's tolerance.

    ``relative`` and ``absolute`` (SI units): within either is enough. ``sig_figs = n``: the value,
    rounded to n significant figures in the student's unit (of ``size``), is within half a unit of
    the n-th figure of the reference; with ``relative``/``absolute`` too, both must hold.

    Examples
    --------
    >>> within_tolerance(14.8, 14.715, {"relative": 0.01}), within_tolerance(15.0, 14.715, {"relative": 0.01})
    (True, False)
    >>> within_tolerance(14.7, 14.715, {"sig_figs": 3}), within_tolerance(14.6, 14.715, {"sig_figs": 3})
    (True, False)
    """
    band = [tolerance[k] for k in ("relative", "absolute") if tolerance.get(k) is not None]
    ok = True
    if band or "sig_figs" not in tolerance:
        relative = float(tolerance.get("relative") or 0.0)
        absolute = float(tolerance.get("absolute") or 0.0)
        if not band:
            relative = DEFAULT_TOLERANCE["relative"]
        slack = max(absolute, relative * abs(reference)) + 1e-12 * abs(reference)
        ok = abs(value - reference) <= slack
    figures = tolerance.get("sig_figs")
    if figures is not None and ok:
        n = int(figures)
        mine, theirs = value / size, reference / size  # compare in the student's unit
        if theirs == 0:
            return abs(mine) < 10.0 ** (-n)
        place = math.floor(math.log10(abs(theirs))) - n + 1  # the n-th figure's decimal place
        rounded = _round_figures(mine, n)
        ok = abs(rounded - theirs) <= 0.5 * 10.0 ** place * (1 + 1e-9)
    return ok


def _round_figures(x: float, n: int) -> float:
    if x == 0:
        return 0.0
    return round(x, n - 1 - math.floor(math.log10(abs(x))))


@lru_cache(maxsize=256)
def _reference_expr(text: str, variables_json: str) -> tuple[sympy.Expr, Namespace]:
    namespace = Namespace.from_spec(json.loads(variables_json))
    return parse_expression(text, namespace, printed=False).expr, namespace


@lru_cache(maxsize=256)
def _root(implicit_json: str, variables_json: str, numbers: tuple) -> float:
    """The unknown of an implicit reference (`grader.expressions.implicit`) at the student's numbers."""
    try:
        rule = Implicit.from_json(json.loads(implicit_json))
    except ImplicitError as error:
        raise NumericRequestError(str(error)) from None
    condition, namespace = _reference_expr(rule.condition, variables_json)
    try:
        x = namespace.symbol(rule.unknown)
    except KeyError:
        raise NumericRequestError(f"implicit.unknown {rule.unknown!r} is not one of the variables") from None
    values = dict(numbers)
    subs = {}
    for symbol in condition.free_symbols - {x}:
        value = values.get(symbol.name)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise NumericRequestError(f"no number for {symbol.name!r}: a numeric answer needs a value for every "
                                      f"name in its reference")
        subs[symbol] = sympy.Float(value)
    try:
        compiled = compile_expr(condition.xreplace(subs), FloatBackend())
    except Unsupported as error:
        raise NumericRequestError(f"the checker cannot evaluate the condition: {error}") from None
    root = rule.solve(lambda v: compiled({x: v, SCALE: 0.0}))
    if root is None:
        raise NumericRequestError(f"the reference has no value at these numbers: its condition has fewer than "
                                  f"{rule.root + 1} roots for {rule.unknown} in [{rule.lo:g}, {rule.hi:g}]")
    return root


def _with_root(implicit: Mapping[str, Any] | None, variables_json: str, values: Mapping[str, Any]) -> dict:
    """``values``, with the implicit reference's unknown at its root (unchanged without one)."""
    if implicit is None:
        return dict(values)
    numbers = tuple(sorted((k, v) for k, v in values.items()
                           if isinstance(k, str) and isinstance(v, (int, float)) and not isinstance(v, bool)))
    try:
        implicit_json = json.dumps(implicit, sort_keys=True)
    except (TypeError, ValueError):
        raise NumericRequestError("'implicit' must be JSON data") from None
    name = implicit.get("unknown") if isinstance(implicit, Mapping) else None
    return {**values, name: _root(implicit_json, variables_json, numbers)}


def _value(text: str, variables_json: str, values: Mapping[str, Any]) -> float:
    """A closed form (engine output or an instructor's feedback expression) at the student's numbers."""
    expr, namespace = _reference_expr(text, variables_json)
    subs = {}
    for symbol in expr.free_symbols:
        value = values.get(symbol.name)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise NumericRequestError(f"no number for {symbol.name!r}: a numeric answer needs a value for every "
                                      f"name in its reference")
        subs[symbol] = sympy.Float(value)
    result = complex(sympy.N(expr.xreplace(subs), 17)) if subs else complex(sympy.N(expr, 17))
    if abs(result.imag) > 1e-12 * max(1.0, abs(result.real)) or not math.isfinite(result.real):
        raise NumericRequestError("the reference is not a real number at these values")
    return result.real


def reference_value(reference: str, variables: Mapping[str, Mapping], values: Mapping[str, Any],
                    implicit: Mapping[str, Any] | None = None) -> float:
    """The reference's value (SI units) at ``values``: for instructors (question tests), never for students.

    ``implicit``: the root the reference's unknown is at, for a reference without a closed form
    (`grader.expressions.implicit.Implicit` as JSON).

    Examples
    --------
    >>> reference_value("m*g/3", {"m": {"dimension": "mass", "domain": "positive"},
    ...                           "g": {"dimension": "acceleration", "domain": "positive"}}, {"m": 0.3, "g": 9.81})
    0.981
    """
    variables_json = json.dumps(variables, sort_keys=True)
    return _value(reference, variables_json, _with_root(implicit, variables_json, values))


def _tolerance(raw: Any) -> dict[str, Any]:
    if raw is None:
        return dict(DEFAULT_TOLERANCE)
    if not isinstance(raw, Mapping) or set(raw) - {"relative", "absolute", "sig_figs"}:
        raise NumericRequestError("'tolerance' must be an object {relative?, absolute?, sig_figs?}")
    for key in ("relative", "absolute"):
        v = raw.get(key)
        if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float)) or not 0 <= v < math.inf):
            raise NumericRequestError(f"tolerance.{key} must be a number >= 0")
    figures = raw.get("sig_figs")
    if figures is not None and (isinstance(figures, bool) or not isinstance(figures, int) or not 1 <= figures <= 15):
        raise NumericRequestError("tolerance.sig_figs must be a whole number from 1 to 15")
    return dict(raw)


def check_numeric(reference: str, answer: str, variables: Mapping[str, Mapping], values: Mapping[str, Any] | None,
                  unit: str = "", tolerance: Mapping[str, Any] | None = None, dimension: str | None = None,
                  feedback: Sequence[Mapping] | None = None, implicit: Mapping[str, Any] | None = None) -> Verdict:
    """A student's number (with unit) against ``reference`` evaluated at ``values``.

    ``implicit``: for a reference without a closed form, the root of a condition its unknown is at,
    found numerically at ``values`` (`grader.expressions.implicit`).

    Raises :class:`NumericRequestError` when the request itself is wrong (the caller, `check`, turns
    it into an ``invalid`` verdict).

    Examples
    --------
    >>> variables = {"m": {"dimension": "mass", "domain": "positive"},
    ...              "g": {"dimension": "acceleration", "domain": "positive"}}
    >>> values = {"m": 1.5, "g": 9.81}
    >>> check_numeric("m*g", "14.7 N", variables, values, unit="N").verdict
    'equivalent'
    >>> v = check_numeric("m*g", "14.7 m/s", variables, values, unit="N")
    >>> v.verdict, v.feedback[0]["message"]
    ('not_equivalent', 'Your unit m/s is a velocity (m/s); the answer is a force (kg·m/s²).')
    >>> check_numeric("m*g", "14.7", variables, values, unit="N").reason
    'give a unit: the answer is a force (kg·m/s²), for example in N'
    """
    tol = _tolerance(tolerance)
    if not isinstance(unit, str):
        raise NumericRequestError("'unit' must be a string")
    try:
        _, expected_dim = parse_unit(unit)
        if dimension:
            declared = parse_dimension(dimension)
            if declared != expected_dim:
                raise NumericRequestError(f"the unit {unit!r} is not {declared.describe()}")
    except DimensionError as error:
        raise NumericRequestError(f"bad unit {unit!r}: {error}") from None
    try:
        variables_json = json.dumps(variables, sort_keys=True)
        values = _with_root(implicit, variables_json, dict(values or {}))
        target = _value(reference, variables_json, values)
    except ExpressionError as error:
        raise NumericRequestError(f"the reference does not parse: {error}") from None
    except (TypeError, ValueError, KeyError) as error:
        if isinstance(error, NumericRequestError):
            raise
        raise NumericRequestError(f"bad variables: {error}") from None

    text = answer if isinstance(answer, str) else ""
    try:
        quantity = parse_quantity(text)
    except QuantityError as error:
        return Verdict.invalid(str(error), text, feedback=[{"code": "number", "message": f"{str(error)[:1].upper()}"
                                                                                           f"{str(error)[1:]}."}])
    parsed = {"text": text.strip(), "latex": quantity.latex, "notes": []}
    if quantity.unit == "" and not expected_dim.is_dimensionless:
        reason = f"give a unit: the answer is {expected_dim.describe()}, for example in {unit}"
        return Verdict("invalid", "none", reason, parsed=parsed,
                       feedback=[{"code": "missing_unit", "message": f"Give a unit: the answer is "
                                                                     f"{expected_dim.describe()}."}])
    if quantity.dimension != expected_dim:
        mine = "a pure number" if quantity.dimension.is_dimensionless else quantity.dimension.describe()
        wanted = "a pure number" if expected_dim.is_dimensionless else expected_dim.describe()
        message = f"Your unit {quantity.unit} is {mine}; the answer is {wanted}."
        return Verdict("not_equivalent", "proved", f"wrong unit: {quantity.unit} is {mine}, the answer is {wanted}",
                       parsed=parsed, feedback=[{"code": "dimension", "message": message}],
                       evidence={"method": "units"})
    if quantity.unit and quantity.size != 1.0:
        parsed["notes"].append(f"converted from {quantity.unit} to SI units")
    figures = tol.get("sig_figs")
    if figures is not None and quantity.sig_figs < figures:
        return Verdict("not_equivalent", "proved", f"give at least {figures} significant figures",
                       parsed=parsed, evidence={"method": "numeric_value"},
                       feedback=[{"code": "sig_figs", "message": f"Give your answer to {figures} significant figures."}])
    if within_tolerance(quantity.si, target, tol, quantity.size):
        return Verdict("equivalent", "numeric", "within the tolerance of the expected value", parsed=parsed,
                       evidence={"method": "numeric_value", "tolerance": tol})
    items = _numeric_feedback(quantity.si, target, tol, feedback or (), variables_json, values)
    verdict = Verdict("not_equivalent", "numeric", "outside the tolerance of the expected value", parsed=parsed,
                      feedback=items, evidence={"method": "numeric_value", "tolerance": tol})
    scores = [item["score"] for item in items if "score" in item]
    if scores:
        verdict.score = max(scores)
    return verdict


def _numeric_feedback(value: float, target: float, tol: Mapping[str, Any], feedback, variables_json: str,
                      values: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The instructor's message for a known wrong value, else a slip we can name (never the value)."""
    band = {k: tol[k] for k in ("relative", "absolute") if tol.get(k) is not None} or DEFAULT_TOLERANCE
    for entry in feedback:
        try:
            wrong = _value(entry["expr"], variables_json, values)
        except (ExpressionError, NumericRequestError, KeyError, TypeError, ValueError):
            continue  # an entry that does not evaluate here cannot match
        if within_tolerance(value, wrong, band):
            item = {"code": "instructor", "message": str(entry["message"])}
            if isinstance(entry.get("score"), (int, float)) and not isinstance(entry.get("score"), bool):
                item["score"] = float(entry["score"])
            return [item]
    if target != 0 and within_tolerance(-value, target, band):
        return [{"code": "sign", "message": "Check the sign of your answer."}]
    if target != 0 and value != 0:
        ratio = math.log10(abs(value / target))
        if abs(ratio - round(ratio)) < 0.005 and round(ratio) != 0:
            return [{"code": "power_of_ten", "message": "Your value is off by a power of ten: check unit prefixes "
                                                        "and conversions."}]
    return []
