"""Numeric answers: a number with (or without) a unit, against the engine's value at the student's numbers.

A ``kind = "numeric"`` answer's reference is still the engine's closed form (``g*m/3``); the request
carries the student's parameter values (`grader.answers.randomised`), and the checker evaluates the
closed form there, in SI units. The student's text is read with a small grammar of our own (never
``float()`` on arbitrary text, never ``eval``): a decimal or scientific number (``14.7``, ``1.47e1``,
``1.47×10^1``, ``1.47·10¹``, ``10^3``, a unicode minus; a name or ``≈`` before it, ``F = 14.7 N``), then a
unit read by :func:`grader.expressions.dimensions.read_unit` (the one unit table, with the students'
spellings: ``Nm``, ``m/s2``, ``newtons``). A decimal comma is refused with a message, since ``1,470``
could be either 1.47 or 1470.

Units of one dimension that are still not interchangeable are refused with what to type where the
scene's ``unit``, the declared ``dimension`` (``angular_velocity``, ``frequency``, ``torque``, ``angle``)
or the reference (a variable declared so, an inverse trigonometric function) says which is meant
(`_meaning`, `_unit_conflict`): Hz against rad/s (ω = 2πf), J for a torque, % for an angle. Where
nothing says which of rad/s and Hz, the answer is asked in s⁻¹. A bare number for a dimensionless answer is in the unit asked (``30``
when degrees are asked). Readings that are only a guess are refused, never judged, when they do not
give the answer's dimension: ``9.8 ms^-2`` (ms is the millisecond; m s^-2 was meant), ``14.7 Nm``.

The unit asked is decided in one place, :func:`asked_unit`: a request without one (``unit = ""``)
asks for the reference's dimension in any unit of it (a pure number only when the reference is
dimensionless), and a unit that contradicts the reference's dimension is a bad request, never a
verdict on the student.

Verdicts: a number outside the tolerance is ``not_equivalent``; a unit of the wrong dimension is
``not_equivalent`` with the dimension named in words; a missing unit (when the answer has one) or an
unreadable number is ``invalid`` with a message saying what to type. Messages never state the
reference value. A request that cannot be graded (no number for a name, numbers outside their
variables' domains, a unit of another dimension than the reference) raises
:class:`NumericRequestError`, which `grader.answers.checker.check` reports as ``invalid``.
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
from grader.answers.feedback import TWO_PI_MESSAGE, counts_cycles
from grader.answers.verdict import Verdict
from grader.expressions.implicit import Implicit, ImplicitError
from grader.expressions import (DimensionError, ExpressionError, Namespace, dimension_of, parse_dimension,
                                parse_expression)
from grader.expressions.dimensions import UnitReading, parse_unit, read_unit
from grader.expressions.unicode_input import MINUS_SIGNS, misleading_character

__all__ = ["DEFAULT_TOLERANCE", "NumericRequestError", "Quantity", "QuantityError", "asked_unit", "check_numeric",
           "parse_quantity", "reference_value", "within_tolerance"]

DEFAULT_TOLERANCE = {"relative": 0.01}
_MAX_TEXT = 200
_MINUSES = str.maketrans(dict.fromkeys(MINUS_SIGNS, "-"))  # − – — ‒ ‐ ‑ ﹣ －: the minuses formulas read
_SUPERSCRIPT_DIGITS = str.maketrans("⁺⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "+-0123456789")
_NUMBER = re.compile(r"""
    \s*(?P<sign>[-+])?\s*
    (?:
        (?P<ten>10)(?:\s*(?:\^|\*\*)\s*(?P<tp>[-+]?\d+|\(\s*[-+]?\d+\s*\))|(?P<ts>[⁺⁻]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+))
      | (?P<mantissa>\d+(?:\.\d*)?|\.\d+)
        (?:
            [eE](?P<e>[-+]?\d+)
          | \s*[×xX*·⋅∙]\s*10\s*(?:\^|\*\*)\s*(?P<p>[-+]?\d+|\(\s*[-+]?\d+\s*\))
          | \s*[×xX*·⋅∙]\s*10(?P<s>[⁺⁻]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+)
        )?
    )
    """, re.VERBOSE)
# "F = 14.7 N", "≈ 14.7 N", "~14.7 N": a name the student gives the quantity, or "about", before the number.
_LABEL = re.compile(r"\s*(?:[^\W\d]\w{0,19}(?:\s*\(\s*\w{0,8}\s*\))?\s*)?(?:=|≈|≃|~|∼)\s*")
_THOUSANDS = re.compile(r"[-+]?(\d{1,3})((?:,\d{3})+)(?![\d.,])")
_ANGLE_UNITS = frozenset({"rad", "deg", "°", "rev", "arcmin", "arcsec", "gon", "grad"})
_PER_TIME = parse_dimension("frequency")  # rad/s and Hz alike: the unit asked or the reference says which
_ENERGY = parse_dimension("energy")  # a torque's too (N·m), but not in joules
_UNIT_NAMES = {"s": "second", "N": "newton", "J": "joule", "W": "watt", "Pa": "pascal", "rad": "radian",
               "Hz": "hertz", "g": "gram", "m": "metre"}


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
    symbols: tuple = ()
    joined: tuple = ()

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


# What an equation editor or a LaTeX source puts around a number and its unit, read as the plain text
# the grammar below takes (14.06\,\mathrm{N}, 1.406\times10^{1}\ \text{N}, \SI{14.06}{N}, 30^\circ).
_LATEX_QUANTITY = (
    (re.compile(r"\\(?:SI|qty)\s*\{([^{}]*)\}\s*\{([^{}]*)\}"), r"\1 \2"),
    (re.compile(r"\\(?:num|si|unit|mathrm|text|textrm|mathit|mathsf|operatorname|rm)\s*\{([^{}]*)\}"), r"\1"),
    (re.compile(r"\\frac\s*\{([^{}]*)\}\s*\{([^{}]*)\}"), r"\1/(\2)"),
    (re.compile(r"\^\s*\{?\s*\\circ\s*\}?"), "°"),
    (re.compile(r"\^\s*\{([^{}]*)\}"), r"^\1"),
    (re.compile(r"\\[,;:> ]|~|\\q?quad(?![A-Za-z])|\\(?:thinspace|enspace|medspace|thickspace)(?![A-Za-z])"), " "),
    (re.compile(r"\\!"), ""),
    (re.compile(r"\\times(?![A-Za-z])\s*"), "×"),  # a space after a command is not typed, LaTeX's way
    (re.compile(r"\\c?dot(?![A-Za-z])\s*"), "·"),
    (re.compile(r"\\approx(?![A-Za-z])"), "≈"),
    (re.compile(r"\\(?:mu|micro)(?![A-Za-z])\s*"), "µ"),
    (re.compile(r"\\(?:degree|deg)(?![A-Za-z])"), "°"),
    (re.compile(r"\\%"), "%"),
    (re.compile(r"^\s*(?:\$\$?|\\[(\[])|(?:\$\$?|\\[)\]])\s*$|\$"), ""),
    (re.compile(r"_\{([^{}]*)\}"), r"_\1"),
)


def _plain_quantity(text: str) -> str:
    r"""``text`` with the LaTeX of a number and its unit written plainly (the text itself when it has none).

    >>> _plain_quantity(r"1.406\times10^{1}\,\mathrm{kg\cdot m/s^{2}}")
    '1.406×10^1 kg·m/s^2'
    >>> _plain_quantity(r"\SI{14.06}{N}"), _plain_quantity(r"$30^\circ$"), _plain_quantity(r"F_{N} = 14.06~\text{N}")
    ('14.06 N', '30°', 'F_N = 14.06 N')
    """
    if not re.search(r"[\\$~{]", text):
        return text
    for _ in range(3):  # \mathrm{\frac{m}{s^{2}}}: nested forms, from the inside out
        before = text
        for pattern, plain in _LATEX_QUANTITY:
            text = pattern.sub(plain, text)
        if text == before:
            break
    return re.sub(r"\s+", " ", text).strip()


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
    try:
        return _read_quantity(text)
    except QuantityError:
        better = _written_form(text) if isinstance(text, str) and len(text) <= _MAX_TEXT else None
        if better is None:
            raise
        raise QuantityError(better) from None


# Ways of writing a number that are not one decimal number; refused (never judged), each with what to
# type instead. Looked for only once the text has been refused: they cost the answers read nothing.
_DECIMAL = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)"
_PI_MULTIPLE = re.compile(rf"\s*(?:[^\W\d]\w{{0,19}}\s*(?:=|≈)\s*)?(?P<n>{_DECIMAL})?\s*[*·×⋅]?\s*"
                          r"(?:π|\\pi(?![A-Za-z])|(?<![A-Za-z])pi(?![A-Za-z]))\s*(?P<rest>[^*/^()π\d]*)$", re.IGNORECASE)
_PI = re.compile(r"π|\\pi(?![A-Za-z])|(?<![A-Za-z])pi(?![A-Za-z])", re.IGNORECASE)
_DMS = re.compile(r"\s*(?P<sign>[-+])?\s*(?P<d>\d+(?:\.\d+)?)\s*(?:°|deg\b|degrees?\b)\s*"
                  r"(?P<m>\d+(?:\.\d+)?)\s*(?:'|′|’|min\b|arcmin\b)\s*"
                  r"(?:(?P<s>\d+(?:\.\d+)?)\s*(?:\"|″|''|′′|’’|”|s\b|sec\b|arcsec\b))?\s*\.?\s*$")
_VULGAR = {"½": 1 / 2, "⅓": 1 / 3, "⅔": 2 / 3, "¼": 1 / 4, "¾": 3 / 4, "⅕": 1 / 5, "⅖": 2 / 5, "⅗": 3 / 5,
           "⅘": 4 / 5, "⅙": 1 / 6, "⅚": 5 / 6, "⅐": 1 / 7, "⅛": 1 / 8, "⅜": 3 / 8, "⅝": 5 / 8, "⅞": 7 / 8,
           "⅑": 1 / 9, "⅒": 1 / 10}
_VULGAR_NUMBER = re.compile("(?P<whole>\\d*)\\s*(?P<part>[" + "".join(_VULGAR) + "])")
_DECIMAL_POWER = re.compile(r"\d\s*(?:[eE]|[×xX*·⋅∙]?\s*10\s*(?:\^|\*\*)\s*\(?)\s*[-+]?\d*\.\d"
                            r"|^\s*[-+]?10\s*(?:\^|\*\*)\s*\(?\s*[-+]?\d*\.\d")
_PLUS_MINUS = re.compile(r"±|∓|\+\s*/\s*-|\+\s*-(?=\s*\d)|\\pm(?![A-Za-z])")
# A ± before the number (after a label, if any): two values, ±x, not x ± its uncertainty.
_LEADING_PLUS_MINUS = re.compile(r"\s*(?:[^\W\d][\w′'*{}]*\s*=\s*)?(?:±|∓|\+\s*/\s*-|\+\s*-(?=\s*\d)|\\pm(?![A-Za-z]))")
_NOTE = re.compile(r"(?<![A-Za-z])(?:s\.\s?f\.?|sf|s\.f|sig\.?\s*figs?|significant\s+(?:figures?|digits?)|"
                   r"d\.\s?p\.?|dp|decimal\s+places?)(?![A-Za-z])", re.IGNORECASE)


def _written_form(text: str) -> str | None:
    """What to type instead of a refused number written as a multiple of π, in degrees, minutes and
    seconds, with a vulgar fraction, with a power of ten that is not whole, with an uncertainty, with
    a note of its figures or after a formula (W = mg = 14.7 N); None for any other text.

    >>> _written_form("0.337π rad")
    'type the value as one decimal number, not in terms of π: 1.059 rad (0.337π rad)'
    >>> _written_form("60°39′36″")
    'type the angle as one number in decimal degrees: 60.66° (60°39′36″); degrees, minutes and seconds are not read'
    """
    plain = _plain_quantity(text.translate(_MINUSES)).strip()
    dms = _DMS.match(plain)
    if dms:
        value = float(dms["d"]) + float(dms["m"]) / 60 + float(dms["s"] or 0) / 3600
        sign = "-" if dms["sign"] == "-" else ""
        return (f"type the angle as one number in decimal degrees: {sign}{value:.6g}° ({text.strip()}); degrees, "
                f"minutes and seconds are not read")
    if _PI.search(plain):
        multiple = _PI_MULTIPLE.match(plain)
        if multiple and not _PI.search(multiple["rest"]):
            value = float(multiple["n"] or 1) * math.pi
            unit = multiple["rest"].strip()
            shown = f"{value:.4g} {unit}".strip()
            return f"type the value as one decimal number, not in terms of π: {shown} ({text.strip()})"
        return "type the value as one decimal number (such as 0.524), not in terms of π"
    vulgar = _VULGAR_NUMBER.search(plain)
    if vulgar:
        value = float(vulgar["whole"] or 0) + _VULGAR[vulgar["part"]]
        return (f"type the number as a decimal: {value:.6g}, not {vulgar['whole']}{vulgar['part']} "
                f"(fractions are not read)")
    if _DECIMAL_POWER.search(plain):
        return "a power of ten is a whole number (1.47e3, 1.47×10^3): type the value as one decimal number"
    if _LEADING_PLUS_MINUS.match(plain):
        # ±1.034 rad, θ = ±59.2°: both roots (the two equilibria), not an uncertainty
        return "type one value with one sign (the answer with + or the one with -): ± gives two answers"
    if _PLUS_MINUS.search(plain):
        return "type one value (such as 14.7 N), without its uncertainty (±)"
    if _NOTE.search(plain):
        return "type only the number and its unit, without a note of its figures (such as 3 s.f.)"
    if re.search(r"=|≈", plain):  # W = mg = 14.7 N, |F| = 14.7 N, 14.7 N = F: one name before '=' is read, no more
        return ("type only the number and its unit (such as 14.7 N), or one name then '=' before it (F = 14.7 N); "
                "a formula or a second '=' is not read")
    return None


def _read_quantity(text: str) -> Quantity:
    if not isinstance(text, str) or not text.strip():
        raise QuantityError("type a number, such as 14.7 or 1.47e1, with its unit")
    if len(text) > _MAX_TEXT:
        raise QuantityError(f"a number with its unit is at most {_MAX_TEXT} characters")
    text = _plain_quantity(text.translate(_MINUSES)).strip()
    label = _LABEL.match(text)
    if label:
        text = text[label.end():]  # "F = 14.7 N", "≈ 14.7 N"
    if re.match(r"\s*[-+]?\d+(?:[.,]\d+)*(?:,\d+[.]|[.]\d+,)", text):  # 1,000.5 or 1.000,5
        raise QuantityError("type one number with a decimal point and no thousands separators, such as 1000.5")
    thousands = _THOUSANDS.match(text)
    if thousands:
        whole, groups = thousands[1], thousands[2]
        raise QuantityError(f"type the number without commas: {whole}{groups.replace(',', '')} (or "
                            f"{whole}.{groups[1:].replace(',', '')} if the comma is a decimal point)")
    comma = re.search(r"(\d+),(\d+)", text)
    if comma:
        raise QuantityError(f"write a decimal point, not a comma: {comma[1]}.{comma[2]}, not {comma[1]},{comma[2]}")
    if "," in text:
        raise QuantityError("type one number with a decimal point (no commas)")
    match = _NUMBER.match(text)
    if not match:
        _refuse_misleading(text)
        if "π" in text or re.search(r"(?<![A-Za-z])pi(?![A-Za-z])", text, re.IGNORECASE):
            raise QuantityError("type the value as a decimal number (such as 0.524), not in terms of π")
        raise QuantityError("type a number first, such as 14.7 or 1.47e1, then its unit")
    if match["ten"]:  # 10^3: a power of ten alone
        mantissa = "1"
        exponent = (match["tp"] or "").strip("() ") or (match["ts"] or "").translate(_SUPERSCRIPT_DIGITS)
    else:
        mantissa = match["mantissa"]
        exponent = match["e"] or (match["p"] or "").strip("() ") or (match["s"] or "").translate(_SUPERSCRIPT_DIGITS)
    try:
        number = float(f"{match['sign'] or ''}{mantissa}e{exponent or 0}")
    except (ValueError, OverflowError):
        raise QuantityError("the number is not readable") from None
    underflow = number == 0 and mantissa.strip("0.") != ""
    if not math.isfinite(number) or underflow or (number != 0 and not 1e-300 < abs(number) < 1e300):
        raise QuantityError("the number is too large or too small")
    rest = text[match.end():].strip()
    rest = rest.rstrip(";").rstrip()  # "14.7 N;": a statement's closing ';', ignored as in a formula
    if rest.endswith(".") and not rest.endswith(".."):
        rest = rest[:-1].rstrip()  # "14.7 N." at the end of a sentence
    if re.match(r"·\d", rest) and "." not in mantissa:
        # 14·7: the raised decimal point of British print, or 14 times 7
        digits = re.match(r"·(\d+)", rest)[1]
        raise QuantityError(f"'{mantissa}·{digits}' reads as the decimal {mantissa}.{digits} or as a product: "
                            f"type {mantissa}.{digits}")
    if rest[:1] == "[" and rest[-1:] == "]" and not re.search(r"[][]", rest[1:-1]):
        rest = rest[1:-1].strip()  # "14.7 [N]": the unit in brackets, as tables and engineers write it
    if (rest[:1].isdigit() or rest[:1] == ".") and not re.match(r"1\s*/\s*[^\W\d]", rest):  # "5 1/s" is a unit
        raise QuantityError("type one number, without spaces inside it (1000, not 1 000)")
    if rest[:1] in "+-^" and rest or re.match(r"\(\s*[-+\d.]", rest):
        raise QuantityError("type one number (such as 14.7), not a calculation")
    if rest[:1] in "*/" and re.match(r"[*/]\s*[\d.(]", rest):
        raise QuantityError("type one number (such as 14.7), not a calculation")
    try:
        reading = read_unit(rest)
    except DimensionError as error:
        if re.search(r"(?:^|[\s×*·(])\d*\.?\d+(?![\d/])", rest):
            raise QuantityError("type one number (such as 14.7), not a calculation") from None
        _refuse_misleading(rest)
        raise QuantityError(f"the unit is not readable: {error}") from None
    digits = mantissa.replace(".", "").lstrip("0")
    return Quantity(number, rest, reading.size, reading.dimension, max(len(digits), 1), reading.symbols,
                    reading.joined)


def _refuse_misleading(text: str) -> None:
    """Raise for an invisible or look-alike character in a number's text, named (a Cyrillic Н or a
    trailing zero-width space would otherwise be shown as the N it looks like)."""
    bad = misleading_character(text)
    if bad is not None:
        raise QuantityError(f"{bad.message}; {bad.hint}")


def within_tolerance(value: float, reference: float, tolerance: Mapping[str, Any], size: float = 1.0) -> bool:
    """Whether ``value`` (SI) matches ``reference`` (SI) under the answer's tolerance.

    ``relative`` and ``absolute`` (SI units): within either is enough. ``sig_figs = n``: the value,
    rounded to n significant figures in the student's unit (of ``size``), is within half a unit of
    the n-th figure of the reference; with ``relative``/``absolute`` too, both must hold. A zero
    reference has no figures to match: there ``sig_figs = n`` takes a value below 10^-n in the
    student's unit (zero to n decimal places).

    Examples
    --------
    >>> within_tolerance(14.8, 14.715, {"relative": 0.01}), within_tolerance(15.0, 14.715, {"relative": 0.01})
    (True, False)
    >>> within_tolerance(14.7, 14.715, {"sig_figs": 3}), within_tolerance(14.6, 14.715, {"sig_figs": 3})
    (True, False)
    >>> within_tolerance(0.0, 0.0, {"sig_figs": 2}), within_tolerance(0.001, 0.0, {"sig_figs": 2})
    (True, True)
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
def _reference_dimension(text: str, variables_json: str) -> Any:
    """The reference's dimension from its variables' (None where it has none, such as ``m + l``, or every one, 0)."""
    expr, namespace = _reference_expr(text, variables_json)
    if expr == 0:
        return None  # zero has every dimension (m*a - m*a is a force as well as anything)
    try:
        return dimension_of(expr, namespace.dimensions())
    except DimensionError:
        return None  # the request's unit alone decides, as for any reference whose dimension is unknown


def asked_unit(unit: Any, reference: Any = None, dimension: str | None = None) -> UnitReading:
    """The unit a numeric answer is asked in: ``unit`` read, or without one the reference's dimension in SI.

    The one place that decides what ``unit = ""`` means (the request's default, and the stored
    reference's, `grader.answers.reference.ReferenceAnswer`): the answer is of the reference's
    dimension, in any unit of it, and a pure number only where the reference is dimensionless.

    Parameters
    ----------
    unit : str
        The unit asked (``"N"``), or ``""`` for none.
    reference : Dimension or None
        The reference's dimension, from its variables; None where it cannot be found.
    dimension : str, optional
        The answer's dimension as the request declares it (``"force"``, ``"kg*m*s^-2"``).

    Raises
    ------
    NumericRequestError
        When the unit or the declared dimension does not read, or when the unit, the declared
        dimension and the reference's disagree: such a request would grade every student against
        another quantity than the reference.

    Examples
    --------
    >>> force = parse_dimension("force")
    >>> asked_unit("kN", force).size, asked_unit("", force).dimension.describe()
    (1000.0, 'a force (kg·m/s²)')
    >>> asked_unit("m", force)
    Traceback (most recent call last):
    ...
    grader.answers.numeric.NumericRequestError: the unit 'm' is a length (m), but the reference is a force (kg·m/s²)
    """
    if not isinstance(unit, str):
        raise NumericRequestError("'unit' must be a string")
    try:
        reading = read_unit(unit)
    except DimensionError as error:
        raise NumericRequestError(f"bad unit {unit!r}: {error}") from None
    try:
        declared = parse_dimension(dimension) if dimension else None
    except DimensionError as error:
        raise NumericRequestError(f"bad dimension {dimension!r}: {error}") from None
    if not unit.strip():
        if declared is not None and reference is not None and declared != reference:
            raise NumericRequestError(f"the dimension {dimension!r} is {declared.describe()}, but the reference is "
                                      f"{reference.describe()}")
        wanted = declared or reference
        return reading if wanted is None else UnitReading(1.0, wanted)
    if declared is not None and declared != reading.dimension:
        raise NumericRequestError(f"the unit {unit!r} is not {declared.describe()}")
    if reference is not None and reference != reading.dimension:
        raise NumericRequestError(f"the unit {unit!r} is {reading.dimension.describe()}, but the reference is "
                                  f"{reference.describe()}")
    return reading


def _check_domains(namespace: Namespace, variables: Mapping[str, Any], values: Mapping[str, Any]) -> None:
    """Raise for a number outside its variable's declared domain (or not below the variable it is
    declared ``below``): the reference holds only there, so its value elsewhere grades nothing."""
    numbers = {k: v for k, v in values.items()
               if isinstance(k, str) and isinstance(v, (int, float)) and not isinstance(v, bool)}
    for variable in namespace.variables:
        value = numbers.get(variable.name)
        if value is None:
            continue  # no number: _value says so where the reference needs one
        if not variable.domain.contains(value):
            raise NumericRequestError(f"the value {value:g} of {variable.name!r} is outside its domain "
                                      f"({variable.domain})")
        spec = variables.get(variable.name)
        other = spec.get("below") if isinstance(spec, Mapping) else None
        if isinstance(other, str) and other in numbers and not value < numbers[other]:
            raise NumericRequestError(f"the value {value:g} of {variable.name!r} is not below that of {other!r} "
                                      f"({numbers[other]:g}), as its domain says")


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
    try:
        variables_json = json.dumps(variables, sort_keys=True)
        _, namespace = _reference_expr(reference, variables_json)
        expected = asked_unit(unit, _reference_dimension(reference, variables_json), dimension)
        expected_dim = expected.dimension
        values = dict(values or {})
        _check_domains(namespace, variables, values)
        values = _with_root(implicit, variables_json, values)
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
    meaning = _meaning(expected.symbols, dimension, _reference_expr(reference, variables_json)[0], variables)
    angle = expected_dim.is_dimensionless and meaning == "angle"
    if quantity.unit == "" and expected_dim.is_dimensionless and expected.size != 1.0:
        # A bare number for an angle or a ratio is in the unit asked (30 when degrees are asked, 50 when %).
        quantity = Quantity(quantity.number, "", expected.size, quantity.dimension, quantity.sig_figs)
        parsed["notes"].append(f"read in {unit}, the unit asked")
    if quantity.unit == "" and not expected_dim.is_dimensionless:
        example = f", for example in {unit}" if unit.strip() else ""
        reason = f"give a unit: the answer is {expected_dim.describe()}{example}"
        return Verdict("invalid", "none", reason, parsed=parsed,
                       feedback=[{"code": "missing_unit", "message": f"Give a unit: the answer is "
                                                                     f"{expected_dim.describe()}."}])
    if quantity.dimension != expected_dim:
        try:
            metre = read_unit(quantity.unit, milli_as_metre=True)
        except DimensionError:
            metre = None
        if metre is not None and metre.split and metre.dimension == expected_dim:
            milli = metre.split[0]
            unit_name = _UNIT_NAMES.get(milli[1:], milli[1:])
            message = (f"{milli} is the milli{unit_name}; if you meant metres times {unit_name}s, put a space "
                       f"between them: m {milli[1:]}.")
            return Verdict("invalid", "none", _reason(message), parsed=parsed,
                           feedback=[{"code": "unit", "message": message}])
        mine = "a pure number" if quantity.dimension.is_dimensionless else quantity.dimension.describe()
        wanted = "a pure number" if expected_dim.is_dimensionless else expected_dim.describe()
        if quantity.joined:  # Nm read as N m was a guess: refuse rather than judge it
            name, read_as = quantity.joined[0]
            message = (f"{quantity.unit} was read as {quantity.unit.replace(name, read_as, 1)} ({name} as units "
                       f"written together), {mine}; the answer is {wanted}. Type the units apart, with spaces or *.")
            return Verdict("invalid", "none", _reason(message), parsed=parsed,
                           feedback=[{"code": "unit", "message": message}])
        message = f"Your unit {quantity.unit} is {mine}; the answer is {wanted}."
        return Verdict("not_equivalent", "proved", f"wrong unit: {quantity.unit} is {mine}, the answer is {wanted}",
                       parsed=parsed, feedback=[{"code": "dimension", "message": message}],
                       evidence={"method": "units"})
    conflict = _unit_conflict(meaning, quantity.symbols, expected_dim)
    if conflict:
        return Verdict("invalid", "none", _reason(conflict), parsed=parsed,
                       feedback=[{"code": "unit", "message": conflict}])
    if quantity.unit and quantity.size != 1.0:
        parsed["notes"].append(f"converted from {quantity.unit} to SI units")
    figures = tol.get("sig_figs")
    # Zero has no significant figures: a zero answer, or any answer to a zero reference, is judged by
    # its value alone (within_tolerance's rule for a zero reference), never told to give more figures.
    # Too few figures is the slip only where the figures given are right (7 m, -2.5 m and 25 m for 2.5 m
    # were all told to give more figures); otherwise the value is what is wrong.
    if (figures is not None and quantity.sig_figs < figures and quantity.number != 0 and target != 0
            and within_tolerance(quantity.si, target, {**tol, "sig_figs": quantity.sig_figs}, quantity.size)):
        return Verdict("not_equivalent", "proved", f"give at least {figures} significant figures",
                       parsed=parsed, evidence={"method": "numeric_value"},
                       feedback=[{"code": "sig_figs", "message": f"Give your answer to {figures} significant figures."}])
    # A zero reference is matched to n decimal places in the unit asked, not the student's: 0.0009 Mm
    # (900 m) passed for 0 m to 3 places.
    if within_tolerance(quantity.si, target, tol, quantity.size if target != 0 else expected.size):
        return Verdict("equivalent", "numeric", "within the tolerance of the expected value", parsed=parsed,
                       evidence={"method": "numeric_value", "tolerance": tol})
    items = _numeric_feedback(quantity.si, target, tol, feedback or (), variables_json, values,
                              counts_cycles(expected_dim))
    if not items and quantity.unit == "" and (angle or expected.size != 1.0):
        other = math.pi / 180 if expected.size == 1.0 else 1.0  # the other of rad and degrees (or % and 1)
        if within_tolerance(quantity.number * other, target, tol, other):
            asked = "rad" if expected.size == 1.0 else unit
            meant = ("°" if expected.size == 1.0 else "rad") if angle else None
            items = [{"code": "angle_unit" if angle else "unit",
                      "message": f"A number without a unit is read in {asked}, the unit asked"
                                 + (f"; type {meant} after it if you meant that unit." if meant else ".")}]
    verdict = Verdict("not_equivalent", "numeric", "outside the tolerance of the expected value", parsed=parsed,
                      feedback=items, evidence={"method": "numeric_value", "tolerance": tol})
    scores = [item["score"] for item in items if "score" in item]
    if scores:
        verdict.score = max(scores)
    return verdict


def _reason(message: str) -> str:
    """A feedback sentence as a verdict's reason: without its full stop, and lower-case where it starts
    with an ordinary word (never a unit symbol: ``Hz counts cycles``, not ``hz``; ``Nm was read``, not
    the nanometre's ``nm``)."""
    text = message[:-1] if message.endswith(".") else message
    first = text.split(" ", 1)[0]
    try:
        read_unit(first)
    except DimensionError:
        return text[:1].lower() + text[1:]
    return text


# Declared dimensions (`parse_dimension`'s names) that say which unit of a shared dimension is meant.
_ANGULAR_NAMES = frozenset({"angular_velocity", "angular_frequency"})
_CYCLE_NAMES = frozenset({"frequency"})
_INVERSE_TRIG = (sympy.asin, sympy.acos, sympy.atan, sympy.acot, sympy.asec, sympy.acsc, sympy.atan2)


def _named(expr: sympy.Expr, names: frozenset) -> bool:
    """Whether ``expr`` is a quantity of one of the named kinds: a variable declared so, an inverse
    trigonometric function for an angle (and π), or a sum of such or a number times one."""
    if expr.is_Symbol:
        return expr.name in names
    if expr is sympy.pi or isinstance(expr, _INVERSE_TRIG):
        return "angle" in names
    if expr.is_Add:
        return all(_named(term, names) for term in expr.args)
    if expr.is_Mul:
        coefficient, rest = expr.as_coeff_Mul()
        return coefficient.is_Rational and rest is not expr and _named(rest, names)
    return False


def _meaning(asked: Sequence[str], dimension: str | None, reference: sympy.Expr, variables: Mapping) -> str | None:
    """Which of the units a dimension shares the answer is in: ``"angle"`` (rad, °, not %),
    ``"angular"`` (rad/s), ``"cycles"`` (Hz), ``"torque"`` (N·m, not J), or None where neither the unit
    asked, the declared dimension nor the reference (a variable declared so, an inverse trigonometric
    function) says."""
    asked = set(asked)
    if asked & _ANGLE_UNITS:
        return "angular" if asked & {"s", "min", "h", "Hz"} else "angle"
    if "Hz" in asked:
        return "cycles"
    if {"N", "m"} <= asked and "J" not in asked:
        return "torque"
    name = str(dimension or "").strip().lower()
    for names, meaning in ((frozenset({"angle"}), "angle"), (_ANGULAR_NAMES, "angular"), (_CYCLE_NAMES, "cycles"),
                           (frozenset({"torque"}), "torque")):
        if name in names:
            return meaning
    for meaning, names in (("angle", {"angle"}), ("angular", _ANGULAR_NAMES), ("cycles", _CYCLE_NAMES)):
        declared = frozenset(n for n, spec in variables.items() if isinstance(spec, Mapping)
                             and str(spec.get("dimension", "")).strip().lower() in names) | (names & {"angle"})
        if _named(reference, declared):
            return meaning
    return None


def _unit_conflict(meaning: str | None, typed: Sequence[str], dimension: Any) -> str | None:
    """Why a unit of the right dimension is still not the one meant; None if it is.

    Units the dimensions cannot tell apart: an angular frequency in rad/s is not one in Hz (cycles
    per second, ω = 2πf), a torque is in N·m and not in joules (an energy), an angle is not a
    percentage. Where the request does not say which of rad/s and Hz (``unit = ""`` or ``1/s``), a
    student who names one is asked for s⁻¹: 3.13 Hz was accepted for ω = 3.13 rad/s. The message
    says what to type; it never says which number is right.
    """
    typed = set(typed)
    if meaning == "angle" and "%" in typed:
        return "Give the angle in rad or ° (not in %)."
    if meaning == "angular" and "Hz" in typed:
        return ("Hz counts cycles per second (f = ω/2π); give this angular frequency in rad/s "
                "(or s⁻¹).")
    if meaning == "cycles" and typed & _ANGLE_UNITS:
        return ("Give this frequency in Hz (cycles per second, or s⁻¹); rad/s measures an angular "
                "frequency (ω = 2πf).")
    if meaning is None and dimension == _PER_TIME and (typed & _ANGLE_UNITS or "Hz" in typed):
        return ("Give this answer in s⁻¹ (type 1/s): the question does not say whether it counts radians "
                "(rad/s) or cycles (Hz, f = ω/2π).")
    if meaning == "torque" and dimension == _ENERGY and "J" in typed and "rad" not in typed:  # J/rad is fine
        return "A torque is given in N·m (the joule is for energy): type N*m."
    return None


def _numeric_feedback(value: float, target: float, tol: Mapping[str, Any], feedback, variables_json: str,
                      values: Mapping[str, Any], cycles: bool = True) -> list[dict[str, Any]]:
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
    if cycles and target != 0 and any(within_tolerance(value, target * f, band) for f in (2 * math.pi, 1 / (2 * math.pi))):
        return [{"code": "two_pi", "message": TWO_PI_MESSAGE}]
    if target != 0 and value != 0:
        ratio = math.log10(abs(value / target))
        if abs(ratio - round(ratio)) < 0.005 and round(ratio) != 0:
            if value * target < 0:  # a prefix fixed, the sign is still wrong
                return [{"code": "power_of_ten", "message": "Your value is off by a power of ten and has the wrong "
                                                            "sign: check unit prefixes, conversions and the sign."}]
            return [{"code": "power_of_ten", "message": "Your value is off by a power of ten: check unit prefixes "
                                                        "and conversions."}]
    return []
