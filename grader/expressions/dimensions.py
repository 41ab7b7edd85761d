"""Physical dimensions over (mass, length, time) and the dimension of a sympy expression.

Angles are dimensionless (radians are a ratio of lengths), so ``sin(theta)`` is
fine and ``thetadot`` has dimension 1/s.  Exponents are ``Fraction`` because
``sqrt(l/g)`` is legitimate physics and gives halves along the way.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from typing import Mapping

import sympy
from sympy.core.function import AppliedUndef

from .errors import DimensionError
from .unicode_input import MINUS_SIGNS
from .functions import BY_SYMPY

__all__ = ["Dimension", "parse_dimension", "parse_unit", "read_unit", "UnitReading", "dimension_of", "NAMED_DIMENSIONS",
           "UNITS", "PREFIXES"]

_SUPERSCRIPTS = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def _as_fraction(value) -> Fraction:
    if isinstance(value, Fraction):
        return value
    if isinstance(value, sympy.Rational):
        return Fraction(int(value.p), int(value.q))
    if isinstance(value, int):
        return Fraction(value)
    raise TypeError(f"dimension exponents must be rational, got {value!r}")


def _whole(value: Fraction) -> "int | Fraction":
    return value.numerator if value.denominator == 1 else value


@dataclass(frozen=True)
class Dimension:
    """Exponents of mass, length and time; immutable and hashable.

    Examples
    --------
    >>> force = Dimension(1, 1, -2)
    >>> force.describe()
    'a force (kg·m/s²)'
    >>> (force * Dimension(0, 1, 0)).describe()
    'an energy or torque (kg·m²/s²)'
    >>> (Dimension(0, 1, 0) ** Fraction(1, 2)).unit()
    'm^(1/2)'
    """

    mass: Fraction = Fraction(0)
    length: Fraction = Fraction(0)
    time: Fraction = Fraction(0)

    def __post_init__(self) -> None:
        for field in ("mass", "length", "time"):
            object.__setattr__(self, field, _as_fraction(getattr(self, field)))
        # The same exponents as plain ints where whole (not a dataclass field: no part of ==, hash or
        # repr): dimension_of adds and compares these, which costs a fraction of Fraction arithmetic.
        object.__setattr__(self, "_exponents", (_whole(self.mass), _whole(self.length), _whole(self.time)))

    # -- arithmetic -------------------------------------------------------
    def __mul__(self, other: "Dimension") -> "Dimension":
        return Dimension(self.mass + other.mass, self.length + other.length, self.time + other.time)

    def __truediv__(self, other: "Dimension") -> "Dimension":
        return Dimension(self.mass - other.mass, self.length - other.length, self.time - other.time)

    def __pow__(self, exponent) -> "Dimension":
        e = _as_fraction(exponent)
        return Dimension(self.mass * e, self.length * e, self.time * e)

    @property
    def is_dimensionless(self) -> bool:
        return self.mass == 0 and self.length == 0 and self.time == 0

    # -- words ------------------------------------------------------------
    def unit(self) -> str:
        """SI unit text such as ``'kg·m/s²'``; ``'1'`` when dimensionless."""
        num, den = [], []
        for symbol, exp in (("kg", self.mass), ("m", self.length), ("s", self.time)):
            if exp == 0:
                continue
            (num if exp > 0 else den).append(_unit_power(symbol, abs(exp)))
        top = "·".join(num) or "1"
        if len(den) > 1:  # kg/(m·s): kg/m·s is read kg·s/m, as a quantity's unit is (_UnitParser.product)
            return f"{top}/({'·'.join(den)})"
        return top if not den else f"{top}/{den[0]}"

    def describe(self) -> str:
        """The dimension in words with its SI unit, e.g. ``'a length (m)'``."""
        if self.is_dimensionless:
            return "dimensionless"
        words = _WORDS.get(self)
        if words:
            return f"{words} ({self.unit()})"
        return f"a quantity in {self.unit()}"

    def __str__(self) -> str:
        return self.unit()


def _unit_power(symbol: str, exp: Fraction) -> str:
    if exp == 1:
        return symbol
    if exp.denominator == 1:
        return symbol + str(exp.numerator).translate(_SUPERSCRIPTS)
    return f"{symbol}^({exp})"


DIMENSIONLESS = Dimension()
_M, _L, _T = Dimension(1, 0, 0), Dimension(0, 1, 0), Dimension(0, 0, 1)

#: The named dimensions scene files may use (``dimension = "force"``).
# Words a student adds for a direction ("9.8 m/s^2 down"), which the sign of the number says instead.
_DIRECTION_WORDS = frozenset({"down", "downward", "downwards", "upward", "upwards", "left", "right", "north", "south",
                              "east", "west", "negative", "positive", "inward", "inwards", "outward", "outwards",
                              "forward", "forwards", "backward", "backwards", "clockwise", "anticlockwise",
                              "counterclockwise", "horizontal", "vertical", "along", "towards", "away"})
NAMED_DIMENSIONS: dict[str, Dimension] = {
    "dimensionless": DIMENSIONLESS,
    "angle": DIMENSIONLESS,
    "mass": _M,
    "length": _L,
    "time": _T,
    "velocity": _L / _T,
    "acceleration": _L / _T ** 2,
    "force": _M * _L / _T ** 2,
    "energy": _M * _L ** 2 / _T ** 2,
    "momentum": _M * _L / _T,
    "angular_velocity": DIMENSIONLESS / _T,
    "angular_acceleration": DIMENSIONLESS / _T ** 2,
    "frequency": DIMENSIONLESS / _T,
    "moment_of_inertia": _M * _L ** 2,
    "torque": _M * _L ** 2 / _T ** 2,
    "power": _M * _L ** 2 / _T ** 3,
    "area": _L ** 2,
    "volume": _L ** 3,
    "stiffness": _M / _T ** 2,
    "density": _M / _L ** 3,
    "angular_momentum": _M * _L ** 2 / _T,
}

# Words for describe(); where two named dimensions coincide (energy and torque,
# frequency and angular velocity) the phrase says both, since either may be meant.
_WORDS: dict[Dimension, str] = {
    _M: "a mass",
    _L: "a length",
    _T: "a time",
    _L / _T: "a velocity",
    _L / _T ** 2: "an acceleration",
    _M * _L / _T ** 2: "a force",
    _M * _L ** 2 / _T ** 2: "an energy or torque",
    _M * _L / _T: "a momentum",
    DIMENSIONLESS / _T: "an angular velocity or frequency",
    DIMENSIONLESS / _T ** 2: "an angular acceleration",
    _M * _L ** 2: "a moment of inertia",
    _M * _L ** 2 / _T ** 3: "a power",
    _L ** 2: "an area",
    _L ** 3: "a volume",
    _M / _T ** 2: "a stiffness",
    _M / _L ** 3: "a density",
    _M * _L ** 2 / _T: "an angular momentum",
}

# The one unit table: symbol -> (size in SI units, dimension, takes an SI prefix). Dimensions
# (`parse_dimension`) read the SI-sized units only; quantities (`parse_unit`, a numeric answer's
# "14.7 kN") read all of them, with prefixes, and scale.
UNITS: dict[str, tuple[float, Dimension, bool]] = {
    "kg": (1.0, _M, False), "g": (1e-3, _M, True), "m": (1.0, _L, True), "s": (1.0, _T, True),
    "min": (60.0, _T, False), "h": (3600.0, _T, False),
    "N": (1.0, _M * _L / _T ** 2, True), "J": (1.0, _M * _L ** 2 / _T ** 2, True),
    "W": (1.0, _M * _L ** 2 / _T ** 3, True), "Pa": (1.0, _M / _L / _T ** 2, True),
    "rad": (1.0, DIMENSIONLESS, True), "Hz": (1.0, DIMENSIONLESS / _T, True),
    "deg": (math.pi / 180, DIMENSIONLESS, False), "°": (math.pi / 180, DIMENSIONLESS, False),
    "%": (0.01, DIMENSIONLESS, False),
    # angles in turns and their parts, and forces outside SI that textbooks still print
    "rev": (2 * math.pi, DIMENSIONLESS, False), "arcmin": (math.pi / 10800, DIMENSIONLESS, False),
    "arcsec": (math.pi / 648000, DIMENSIONLESS, False), "gon": (math.pi / 200, DIMENSIONLESS, False),
    "grad": (math.pi / 200, DIMENSIONLESS, False),
    "dyn": (1e-5, _M * _L / _T ** 2, False), "kgf": (9.80665, _M * _L / _T ** 2, False),
    "lbf": (4.4482216152605, _M * _L / _T ** 2, False),
    "t": (1000.0, _M, False),  # the tonne, accepted for use with SI (unprefixed: kt is also the knot)
}
# Every SI prefix from yocto to yotta (a nucleus is a few fm across, a laser pulse some fs or as long)
PREFIXES: dict[str, float] = {"Y": 1e24, "Z": 1e21, "E": 1e18, "P": 1e15, "T": 1e12, "G": 1e9, "M": 1e6, "k": 1e3,
                              "h": 1e2, "da": 1e1, "d": 1e-1, "c": 1e-2, "m": 1e-3, "µ": 1e-6, "μ": 1e-6, "u": 1e-6,
                              "n": 1e-9, "p": 1e-12, "f": 1e-15, "a": 1e-18, "z": 1e-21, "y": 1e-24}
_SI_UNITS: dict[str, Dimension] = {name: dim for name, (size, dim, _) in UNITS.items()
                                   if size == 1.0 and name != "g"}

_DIM_TOKEN = re.compile(r"\s*(?:(\d+(?:/\d+)?)|([A-Za-z_µμ°]+|%)|(\*\*|[*/^()·.\-+]))")
# A quantity's unit as students type it: the unit's names in words, any case, singular or plural
# ("newtons", "Metres", "secs"), with prefixes in words ("kilometres"); "per", "squared", "cubed".
_UNIT_WORDS: dict[str, str] = {
    "second": "s", "sec": "s", "metre": "m", "meter": "m", "gram": "g", "gramme": "g", "newton": "N",
    "joule": "J", "watt": "W", "pascal": "Pa", "radian": "rad", "rad": "rad", "degree": "deg", "deg": "deg",
    "hertz": "Hz", "minute": "min", "min": "min", "hour": "h", "hr": "h", "percent": "%", "kg": "kg", "kilo": "kg",
    "revolution": "rev", "rev": "rev", "turn": "rev", "arcminute": "arcmin", "arcsecond": "arcsec",
    "gradian": "grad", "dyne": "dyn", "tonne": "t",
}
_PREFIX_WORDS: dict[str, str] = {"yotta": "Y", "zetta": "Z", "exa": "E", "peta": "P", "tera": "T", "giga": "G",
                                 "mega": "M", "kilo": "k", "hecto": "h", "deca": "da", "deka": "da", "deci": "d",
                                 "centi": "c", "milli": "m", "micro": "µ", "nano": "n", "pico": "p", "femto": "f",
                                 "atto": "a", "zepto": "z", "yocto": "y"}
_PURE_WORDS = ("dimensionless", "unitless")
# Look-alikes of the degree sign and of the multiplication dot.
_UNIT_LOOKALIKES = str.maketrans({"º": "°", "˚": "°", "⋅": "·", "∙": "·", "•": "·", "×": "*",
                                  **dict.fromkeys(MINUS_SIGNS, "-")})
_SUPERSCRIPT_RUN = re.compile("[⁺⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+")
_FROM_SUPERSCRIPTS = str.maketrans("⁺⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "+-0123456789")


def _unit_size(name: str) -> tuple[float, Dimension] | None:
    """(size in SI, dimension) of a unit symbol such as ``kN`` or ``min``; None if it is not one."""
    found = _unit_parts(name)
    return None if found is None else found[:2]


def _unit_parts(name: str) -> tuple[float, Dimension, str] | None:
    """(size in SI, dimension, the unit without its prefix) of a unit symbol such as ``kN``."""
    if name in UNITS:
        size, dim, _ = UNITS[name]
        return size, dim, name
    for prefix, factor in PREFIXES.items():
        if name.startswith(prefix) and name[len(prefix):] in UNITS:
            size, dim, prefixable = UNITS[name[len(prefix):]]
            if prefixable:
                return factor * size, dim, name[len(prefix):]
    return None


def _unit_word(word: str) -> str | None:
    """The symbol of a unit written in words (``newtons``, ``Kilometres``, ``msec``); None if none."""
    lower = word.lower()
    for stem in (lower, lower[:-1] if lower.endswith("s") and len(lower) > 2 else None):
        if stem is None:
            continue
        if stem in _UNIT_WORDS:
            return _UNIT_WORDS[stem]
        for prefix_word, prefix in _PREFIX_WORDS.items():
            rest = stem[len(prefix_word):]
            if stem.startswith(prefix_word) and _UNIT_WORDS.get(rest) and _unit_size(prefix + _UNIT_WORDS[rest]):
                return prefix + _UNIT_WORDS[rest]
    if word[:1] in PREFIXES and word[1:].lower() in ("sec", "secs"):
        return word[:1] + "s"  # msec, µsec
    return None


def _unit_splits(name: str, depth: int = 0) -> list[list[str]]:
    """Every way to read ``name`` as unit symbols written together (``Nm``: N m; ``kgm``: kg m)."""
    if not name:
        return [[]]
    if depth > 6:
        return []
    splits = []
    for end in range(1, len(name) + 1):
        head = name[:end]
        if _unit_size(head) is not None:
            splits.extend([head, *tail] for tail in _unit_splits(name[end:], depth + 1))
    return splits


def _case_hint(name: str) -> str:
    """`` (did you mean kN?)`` for a unit typed in the wrong case; ``""`` if none is meant."""
    lower = name.lower()
    candidates = sorted({symbol for symbol in UNITS if symbol.lower() == lower}
                        | {prefix + symbol for symbol, (_, _, prefixable) in UNITS.items() if prefixable
                           for prefix in PREFIXES if prefix not in "μu" and (prefix + symbol).lower() == lower})
    if not candidates:
        return ""
    return f" (unit symbols are case-sensitive: did you mean {' or '.join(candidates)}?)"


def parse_unit(text: str) -> tuple[float, Dimension]:
    """Read a unit as a student writes it after a number: (size in SI units, dimension).

    Units are ``kg g m s min h N J W Pa rad Hz deg ° %`` with SI prefixes (``kN``, ``cm``, ``ms``,
    ``µs``, ``daN``, ``fm``, ``PJ``: every prefix from yocto to yotta), the tonne (``t``, unprefixed), the turn
    and parts of a degree (``rev arcmin arcsec grad gon``) and forces outside SI (``dyn kgf lbf``), combined with ``* / ^ **``, ``·``, a space (``kg m/s^2``), parentheses and
    superscripts (``m/s²``); an empty text is a pure number. Also as students type them: symbols
    written together (``Nm``, ``kgm/s^2``; refused where two readings differ, ``Nms``), an exponent
    right after its unit (``m/s2``, ``m s-2``), a hyphen between units (``N-m``), a unit in words
    (``newtons``, ``Metres``, ``kilometres``, ``secs``, ``msec``, ``per``, ``squared``), a capital
    first letter where that is no other unit (``Kg``, ``Rad``; ``Nm`` stays N m, ``Ms`` the
    megasecond). Symbols are otherwise case-sensitive (``mN``, ``MN``); a wrong case gets a hint.

    Examples
    --------
    >>> parse_unit("km/h")[0], parse_unit("km/h")[1].describe()
    (0.2777777777777778, 'a velocity (m/s)')
    >>> parse_unit("kg m/s²") == parse_unit("N")
    True
    >>> parse_unit("Nm") == parse_unit("N m") == parse_unit("newton-metres") == parse_unit("N*m")
    True
    >>> parse_unit("m s-2") == parse_unit("m/s2") == parse_unit("metres per second squared") == parse_unit("m/s^2")
    True
    >>> parse_unit("Nms")
    Traceback (most recent call last):
    ...
    grader.expressions.errors.DimensionError: 'Nms' could be N*ms or N*m*s: write the units apart, with spaces or '*'
    >>> parse_unit("kn")
    Traceback (most recent call last):
    ...
    grader.expressions.errors.DimensionError: unknown unit 'kn' in 'kn' (unit symbols are case-sensitive: did you mean kN?)
    """
    reading = read_unit(text)
    return reading.size, reading.dimension


@dataclass(frozen=True)
class UnitReading:
    """A quantity's unit, read (:func:`read_unit`).

    Attributes
    ----------
    size : float
        The unit's size in SI units.
    dimension : Dimension
    symbols : tuple of str
        The units it is made of, without prefixes (``kN*m`` has ``("N", "m")``): which of
        the units of one dimension was meant (``J`` or ``N*m``, ``Hz`` or ``rad/s``).
    split : tuple of str
        With ``milli_as_metre``, the milli-prefixed units read as metre products.
    joined : tuple of str
        ``(name, reading)`` of names read as unit symbols written together (``("Nm", "N m")``): a
        guess at what was meant.
    """

    size: float
    dimension: Dimension
    symbols: tuple = ()
    split: tuple = ()
    joined: tuple = ()


def read_unit(text: str, milli_as_metre: bool = False) -> UnitReading:
    """Read a unit as a student writes it after a number (:func:`parse_unit`), with the units it names.

    ``milli_as_metre``: read a milli-prefixed unit (``ms``, ``mN``) as the metre times that unit
    instead (``m s``, ``m N``): what a student who typed ``9.8 ms^-2`` may have meant; for a
    message, never to accept.

    Examples
    --------
    >>> reading = read_unit("kNm")
    >>> reading.size, reading.symbols, reading.dimension.describe()
    (1000.0, ('N', 'm'), 'an energy or torque (kg·m²/s²)')
    >>> read_unit("ms^-2").dimension.describe(), read_unit("ms^-2", milli_as_metre=True).dimension.describe()
    ('an angular acceleration (1/s²)', 'an acceleration (m/s²)')
    """
    if not isinstance(text, str) or len(text) > 200:
        raise DimensionError("a unit is short text such as 'N' or 'kg*m/s^2'")
    text = _SUPERSCRIPT_RUN.sub(lambda m: "^" + m.group().translate(_FROM_SUPERSCRIPTS),
                                text.translate(_UNIT_LOOKALIKES).strip())
    if not text:
        return UnitReading(1.0, DIMENSIONLESS)
    if text.startswith("/"):
        text = "1" + text  # "5 /s"
    parser = _UnitParser(text, scaled=True, milli_as_metre=milli_as_metre)
    size, dim = parser.parse_scaled()
    return UnitReading(size, dim, tuple(parser.symbols), tuple(parser.split), tuple(parser.joined))


def parse_dimension(text: "str | Dimension") -> Dimension:
    """Read a dimension: a name from :data:`NAMED_DIMENSIONS` or SI units.

    SI units are ``kg m s N J W rad Hz`` combined with ``* / ^ **`` (``·`` too)
    and parentheses; exponents are integers or fractions, possibly negative.

    Examples
    --------
    >>> parse_dimension("force") == parse_dimension("kg*m/s^2") == parse_dimension("N")
    True
    >>> parse_dimension("s^-1").describe()
    'an angular velocity or frequency (1/s)'
    >>> parse_dimension("N*m").describe()
    'an energy or torque (kg·m²/s²)'
    """
    if isinstance(text, Dimension):
        return text
    if not isinstance(text, str):
        raise DimensionError(f"a dimension must be text such as 'force' or 'kg*m/s^2', got {text!r}")
    key = text.strip().lower().replace(" ", "_").replace("-", "_")
    if key in NAMED_DIMENSIONS:
        return NAMED_DIMENSIONS[key]
    if len(text) > 200:
        raise DimensionError("dimension text is too long")
    return _UnitParser(text).parse()


class _UnitParser:
    """Recursive descent over ``product := power (('*'|'/') power)*``.

    It works on (size in SI, dimension) pairs: dimensions ignore the size; with ``scaled`` (a
    quantity's unit, :func:`parse_unit`) prefixed and non-SI units are read too, a space multiplies,
    and named dimensions are refused (``14 force`` is no quantity).
    """

    def __init__(self, text: str, scaled: bool = False, milli_as_metre: bool = False) -> None:
        self.text = text
        self.scaled = scaled
        self.milli_as_metre = milli_as_metre
        self.symbols: list[str] = []  # the units read, without prefixes (scaled)
        self.split: list[str] = []    # milli-prefixed units read as metre products (milli_as_metre)
        self.joined: list[str] = []   # names read as symbols written together (Nm)
        self.tokens: list[tuple[str, str]] = []
        attached: list[bool] = []  # no space before the token
        pos = 0
        stripped = text.rstrip()
        while pos < len(stripped):
            match = _DIM_TOKEN.match(stripped, pos)
            if not match:
                what = "unit" if scaled else "dimension"
                raise DimensionError(f"cannot read {what} {text!r} at character {pos + 1}")
            number, name, op = match.groups()
            self.tokens.append(("num", number) if number else ("name", name) if name else ("op", op))
            attached.append(match.start(match.lastindex) == pos)
            pos = match.end()
        if scaled:
            self.tokens = self._as_typed(self.tokens, attached)
        self.i = 0

    def _as_typed(self, raw: list[tuple[str, str]], attached: list[bool]) -> list:
        """A quantity's tokens with the students' habits read: every name becomes ("unit", symbols)
        (``Nm``: N, m), an exponent right after its unit gets its ``^`` (``s2``, ``s-2``), a hyphen
        between two units multiplies (``N-m``), ``per`` divides, ``squared``/``cubed`` raise."""
        tokens: list = []
        for k, (kind, value) in enumerate(raw):
            after = raw[k + 1] if k + 1 < len(raw) else None
            glued = k + 1 < len(raw) and attached[k + 1]
            if kind == "op" and value in "-+" and tokens and tokens[-1][0] == "unit" and attached[k]:
                if after is not None and after[0] == "num" and glued:
                    tokens.append(("op", "^"))  # s-2
                elif value == "-" and after is not None and after[0] == "name" and glued:
                    tokens.append(("op", "*"))  # N-m
                    continue
            if kind == "num" and tokens and tokens[-1][0] == "unit" and attached[k]:
                tokens.append(("op", "^"))  # s2
            if kind != "name":
                tokens.append((kind, value))
                continue
            exponent_next = after in (("op", "^"), ("op", "**"))
            lower = value.lower()
            if lower == "per":
                tokens.extend([("op", "/")] if tokens else [("num", "1"), ("op", "/")])  # "5 per second"
            elif lower in ("squared", "cubed") and tokens:
                tokens.extend([("op", "^"), ("num", "2" if lower == "squared" else "3")])
            elif lower in _PURE_WORDS:
                tokens.append(("num", "1"))
            else:
                tokens.append(("unit", self._symbols(value, exponent_next)))
        return tokens

    def _symbols(self, name: str, exponent_next: bool) -> tuple[str, ...]:
        """The unit symbols a name stands for (``kN``: kN; ``Nm``: N, m; ``newtons``: N)."""
        word = _unit_word(name)
        splits = [split for split in _unit_splits(name) if len(split) > 1] if len(name) <= 12 else []
        if _unit_size(name) is not None:
            symbols = (name,)
        elif word is not None and not (exponent_next and splits):
            symbols = (word,)  # "rads" is radians, but "rads^-1" is rad s^-1
        elif splits:
            readings = {tuple(split): self._group_size(split) for split in splits}
            if len(set(readings.values())) > 1:
                ways = " or ".join("*".join(split) for split in sorted(readings, key=len)[:2])
                raise DimensionError(f"{name!r} could be {ways}: write the units apart, with spaces or '*'")
            symbols = min(readings, key=len)
            self.joined.append((name, " ".join(symbols)))
        elif name[:1].isupper() and name[1:].islower() and _unit_size(name.lower()) is not None:
            symbols = (name.lower(),)  # Kg, Rad (a capital only where it is no other unit: Ms, Nm)
        elif len(name) >= 4 and name.isalpha() and not _case_hint(name):
            direction = " (a direction is the sign)" if name.lower() in _DIRECTION_WORDS else ""
            raise DimensionError(f"{name!r} is not a unit: type only the number and its unit{direction}, in SI "
                                 f"units such as kg g m s min h N J W Pa rad Hz deg")
        else:
            raise DimensionError(f"unknown unit {name!r} in {self.text!r}"
                                 + (_case_hint(name) or "; use SI units such as kg g m s min h N J W Pa rad Hz deg, "
                                                        "with prefixes (kN, cm, ms)"))
        if self.milli_as_metre:
            spread = []
            for symbol in symbols:
                rest = symbol[1:]
                if symbol.startswith("m") and rest in UNITS and UNITS[rest][2] and symbol not in UNITS:
                    spread.extend(["m", rest])
                    self.split.append(symbol)
                else:
                    spread.append(symbol)
            symbols = tuple(spread)
        return symbols

    @staticmethod
    def _group_size(symbols) -> tuple[float, Dimension]:
        size, dim = 1.0, DIMENSIONLESS
        for symbol in symbols:
            s, d = _unit_size(symbol)
            size, dim = size * s, dim * d
        return round(size, 12), dim

    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> tuple[str, str]:
        tok = self.peek()
        if tok is None:
            raise DimensionError(f"dimension {self.text!r} ends too early")
        self.i += 1
        return tok

    def parse(self) -> Dimension:
        return self.parse_scaled()[1]

    def parse_scaled(self) -> tuple[float, Dimension]:
        if not self.tokens:
            raise DimensionError("empty dimension")
        size, dim = self.product(0)
        if self.peek() is not None:
            what = "unit" if self.scaled else "dimension"
            token = self.peek()
            shown = "".join(token[1]) if token[0] == "unit" else token[1]
            raise DimensionError(f"cannot read {what} {self.text!r}: unexpected {shown!r}")
        return size, dim

    def product(self, depth: int) -> tuple[float, Dimension]:
        if depth > 20:
            raise DimensionError("dimension is nested too deeply")
        size, dim = self.power(depth)
        while True:
            token = self.peek()
            if token in (("op", "*"), ("op", "/"), ("op", "·"), ("op", ".")):
                op = self.take()[1]
            elif self.scaled and token is not None and (token[0] == "unit" or token == ("op", "(")):
                op = "*"  # "kg m/s^2": a space between units multiplies
            else:
                return size, dim
            right_size, right = self.power(depth)
            if op == "/" and self.scaled and self._multiplies_next():
                # m/s·s, kg/m s: (m/s)·s by precedence, but m/(s·s) as many write it (and as "J/kg K" means)
                raise DimensionError(self._after_solidus())
            if op == "/":
                size, dim = size / right_size, dim / right
            else:
                size, dim = size * right_size, dim * right

    def _multiplies_next(self) -> bool:
        """Whether the next token multiplies what comes before it (``*``, ``·``, ``.``, or a unit after a space)."""
        token = self.peek()
        return token in (("op", "*"), ("op", "·"), ("op", ".")) or (
            token is not None and (token[0] == "unit" or token == ("op", "(")))

    def _after_solidus(self) -> str:
        """The refusal of a product after a '/' (``m/s·s``), saying both readings."""
        return (f"{self.text.strip()!r} could have every unit after the '/' below it, or only the first: put the units "
                f"below the '/' in brackets, as in m/(s·s), or write their powers, as in m·s^-2")

    def power(self, depth: int) -> tuple[float, Dimension]:
        kind, value = self.take()
        head_size, head_dim = 1.0, DIMENSIONLESS  # units written together before the last (kgm^2: kg)
        if (kind, value) == ("op", "("):
            size, dim = self.product(depth + 1)
            if self.take() != ("op", ")"):
                raise DimensionError(f"unbalanced parenthesis in dimension {self.text!r}")
        elif kind == "num" and value == "1":
            size, dim = 1.0, DIMENSIONLESS
        elif self.scaled:
            if kind != "unit":
                raise DimensionError(f"cannot read unit {self.text!r}: unexpected {value!r}")
            for symbol in value[:-1]:
                found = _unit_parts(symbol)
                head_size, head_dim = head_size * found[0], head_dim * found[1]
                self.symbols.append(found[2])
            size, dim, base = _unit_parts(value[-1])
            self.symbols.append(base)
        elif kind == "name" and value in _SI_UNITS:
            size, dim = 1.0, _SI_UNITS[value]
        elif kind == "name" and value.lower() in NAMED_DIMENSIONS:
            size, dim = 1.0, NAMED_DIMENSIONS[value.lower()]
        else:
            known = ", ".join(sorted(NAMED_DIMENSIONS))
            raise DimensionError(f"unknown dimension or unit {value!r} in {self.text!r}; "
                                 f"use SI units (kg m s N J W rad Hz) or one of: {known}")
        if self.peek() in (("op", "^"), ("op", "**")):
            self.take()
            exponent = self.exponent()
            if abs(exponent) > 12 or exponent.denominator > 12:
                raise DimensionError(f"a unit exponent of {exponent} is not plausible in {self.text!r}")
            size, dim = size ** float(exponent), dim ** exponent
        return head_size * size, head_dim * dim

    def exponent(self) -> Fraction:
        sign = 1
        if self.peek() in (("op", "-"), ("op", "+")):
            sign = -1 if self.take()[1] == "-" else 1
        kind, value = self.take()
        if kind == "op" and value == "(":
            exp = self.exponent()
            closing = self.peek()
            if closing is None:
                raise DimensionError(f"unbalanced parenthesis in dimension {self.text!r}")
            if self.take() != ("op", ")"):
                # kg^(10^400), kg^(1e999): an exponent is one number, not an expression
                raise DimensionError(f"a unit exponent is a whole number or a fraction such as 2, -1 or (1/2), "
                                     f"got {''.join(closing[1])!r} after it in {self.text!r}")
            return sign * exp
        if kind != "num":
            raise DimensionError(f"a unit exponent must be a number, got {value!r} in {self.text!r}")
        return sign * self._fraction(value)

    def _fraction(self, written: str) -> Fraction:
        """The exponent a number token writes (``2``, ``1/2``), refusing a zero denominator, which
        :class:`~fractions.Fraction` would raise as ZeroDivisionError, no DimensionError."""
        if int(written.partition("/")[2] or 1) == 0:
            raise DimensionError(f"a unit exponent of {written} divides by zero in {self.text!r}")
        return Fraction(written)


# -- dimension of an expression --------------------------------------------

# sympy functions outside the registry that an engine derivation can still produce.
_OTHER_DIMENSIONLESS = (sympy.acot, sympy.asec, sympy.acsc)


def _phrase(dim: Dimension) -> str:
    return "a dimensionless number" if dim.is_dimensionless else dim.describe()


# The walker works on (mass, length, time) exponent tuples, ints where whole, and builds a
# Dimension only for the result and for messages: its Fraction arithmetic dominated the walk.
_Exponents = tuple
_NONE: _Exponents = (0, 0, 0)


@lru_cache(maxsize=256)
def _dim(exponents: _Exponents) -> Dimension:
    # Dimensions are immutable, and answers keep having the same few: build each one once.
    return Dimension(*exponents)


@lru_cache(maxsize=256)
def _words(exponents: _Exponents) -> str:
    return _phrase(_dim(exponents))


def dimension_of(expr, dims: Mapping) -> Dimension:
    """The dimension of a sympy expression whose symbols have the given dimensions.

    Parameters
    ----------
    expr : sympy.Basic
        An expression, or an ``Eq`` (both sides must agree).
    dims : mapping
        ``{Symbol: Dimension}`` (e.g. ``Namespace.dimensions()``); keys may also be
        names, and symbols are matched by name when the assumptions differ.
        Applied functions ``theta(t)`` are looked up by their name.

    Raises
    ------
    DimensionError
        Terms of different dimensions added or equated, a function of a
        dimensional argument, a dimensional base raised to a symbolic power,
        or a symbol with no known dimension.

    Examples
    --------
    >>> import sympy
    >>> m, g, l, theta = sympy.symbols("m g l theta")
    >>> dims = {m: parse_dimension("mass"), g: parse_dimension("acceleration"),
    ...         l: parse_dimension("length"), theta: parse_dimension("angle")}
    >>> dimension_of(m*g*l*sympy.cos(theta), dims).describe()
    'an energy or torque (kg·m²/s²)'
    >>> dimension_of(m*g + l, dims)
    Traceback (most recent call last):
    ...
    grader.expressions.errors.DimensionError: adds a force (kg·m/s²) to a length (m): g*m + l
    """
    by_name = {}
    for key, value in dims.items():
        name = key if isinstance(key, str) else getattr(key, "name", None)
        if name is not None:
            by_name[name] = parse_dimension(value)
    if isinstance(expr, (int, Fraction)) and not isinstance(expr, bool):
        expr = sympy.Rational(expr)
    if not isinstance(expr, sympy.Basic):
        # Text must go through parse_expression first; nothing here reads strings.
        raise TypeError(f"dimension_of takes a sympy expression, got {type(expr).__name__}")
    walker = _DimensionWalker(dims, by_name)
    try:
        return _dim(walker.walk(expr))
    except DimensionError:
        scaled = _dimension_by_scaling(expr, walker)
        if scaled is None:
            raise
        return _dim(scaled)


# Largest expression whose dimension is worked out by scaling (a symbolic step on student text).
SCALING_MAX_NODES = 200


def _dimension_by_scaling(expr, walker: "_DimensionWalker") -> _Exponents | None:
    """The dimension of an expression that the walker refuses node by node, but that is homogeneous
    as a whole: ``u (ln m₀ − ln m₁)`` (each log has a mass in it, their difference does not),
    ``V₀ rⁿ/Rⁿ`` (a length to a symbolic power, over another).

    That is the definition of a dimension: changing the units multiplies every mass by S_M, every
    length by S_L and every time by S_T, and a quantity of dimension M^a L^b T^c is multiplied by
    S_M^a S_L^b S_T^c. The expression is rescaled so, its logarithms and powers of products are
    expanded (ln(S m) = ln S + ln m, (S r)ⁿ = Sⁿ rⁿ), and the ratio to the expression must be such a
    monomial; otherwise (ln m₀ alone, sin of a mass) None, and the walker's error stands. Only
    expressions with a logarithm or a non-numeric power, of at most ``SCALING_MAX_NODES`` nodes.

    >>> import sympy
    >>> u, m0, m1, r, R, n = sympy.symbols("u m0 m1 r R n", positive=True)
    >>> dims = {u: "velocity", m0: "mass", m1: "mass", r: "length", R: "length", n: "dimensionless"}
    >>> dimension_of(u * (sympy.log(m0) - sympy.log(m1)), dims).describe()
    'a velocity (m/s)'
    >>> dimension_of(r**n / R**n, dims).is_dimensionless
    True
    >>> dimension_of(u * sympy.log(m0), dims)
    Traceback (most recent call last):
    ...
    grader.expressions.errors.DimensionError: log needs a dimensionless argument, got a mass (kg): log(m0)
    """
    if isinstance(expr, sympy.core.relational.Relational):
        sides = [_dimension_by_scaling(side, walker) if _rescalable(side) else _try_walk(walker, side)
                 for side in (expr.lhs, expr.rhs)]
        if None in sides or (sides[0] != sides[1] and not _is_zero(expr.lhs) and not _is_zero(expr.rhs)):
            return None
        return sides[1] if _is_zero(expr.lhs) else sides[0]
    if not _rescalable(expr):
        return None
    scales = [sympy.Dummy(f"S{i}", positive=True) for i in range(3)]
    rescale = {}
    for symbol in expr.free_symbols:
        try:
            exponents = walker.lookup(symbol, symbol.name)
        except DimensionError:
            return None
        if exponents != _NONE:
            factor = sympy.Mul(*[S ** sympy.Rational(e) for S, e in zip(scales, exponents)])
            rescale[symbol] = symbol * factor
    try:
        scaled = sympy.expand_power_base(sympy.expand_log(expr.xreplace(rescale), force=True), force=True)
        ratio = sympy.powsimp(sympy.cancel(sympy.expand_log(scaled, force=True) / expr), force=True)
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
        return None  # no ratio to read: the walker's error stands
    if ratio.free_symbols - set(scales):
        return None
    powers = ratio.as_powers_dict()
    if set(powers) - set(scales) - {sympy.S.One}:
        return None
    exponents = []
    for S in scales:
        e = powers.get(S, sympy.S.Zero)
        if not e.is_Rational:
            return None
        exponents.append(_whole(Fraction(int(e.p), int(e.q))))
    return tuple(exponents)


def _rescalable(expr) -> bool:
    """Whether the scaling rule applies: a logarithm or a non-numeric power in a small expression,
    and no applied function of time (those the walker alone knows)."""
    nodes, interesting = 0, False
    for node in sympy.preorder_traversal(expr):
        nodes += 1
        if nodes > SCALING_MAX_NODES or isinstance(node, (AppliedUndef, sympy.Derivative)):
            return False
        interesting = interesting or isinstance(node, sympy.log) or (node.is_Pow and not node.exp.is_Rational)
    return interesting


def _try_walk(walker: "_DimensionWalker", expr) -> _Exponents | None:
    try:
        return walker.walk(expr)
    except DimensionError:
        return None


class _DimensionWalker:
    def __init__(self, dims: Mapping, by_name: dict[str, Dimension]) -> None:
        self.dims = dims
        self.by_name = by_name

    def lookup(self, node, name: str) -> _Exponents:
        if node in self.dims:
            return parse_dimension(self.dims[node])._exponents
        if name in self.by_name:
            return self.by_name[name]._exponents
        if name == "t":
            return _T._exponents  # time in dynamicsymbols-style expressions, unless declared otherwise
        raise DimensionError(f"'{name}' has no known dimension", node)

    def walk(self, node) -> _Exponents:
        if node.is_Symbol:
            return self.lookup(node, node.name)
        if node.is_Mul:
            m = l = t = 0
            for factor in node.args:
                fm, fl, ft = self.walk(factor)
                m, l, t = m + fm, l + fl, t + ft
            return m, l, t
        if node.is_Number or isinstance(node, sympy.NumberSymbol) or node is sympy.I:
            return _NONE
        if node.is_Add:
            return self.add(node)
        if node.is_Pow:
            return self.power(node)
        if isinstance(node, sympy.Equality) or isinstance(node, sympy.core.relational.Relational):
            left, right = self.walk(node.lhs), self.walk(node.rhs)
            if left != right and not _is_zero(node.lhs) and not _is_zero(node.rhs):
                raise DimensionError(f"equates {_words(left)} to {_words(right)}: {node}", node)
            return right if _is_zero(node.lhs) else left
        if isinstance(node, AppliedUndef):
            return self.lookup(node, node.func.__name__)
        if isinstance(node, sympy.Derivative):
            m, l, t = self.walk(node.expr)
            for variable, count in node.variable_count:
                vm, vl, vt = self.walk(variable)
                n = int(count)
                m, l, t = m - vm * n, l - vl * n, t - vt * n
            return m, l, t
        spec = BY_SYMPY.get(node.func)
        if spec is not None:
            return self.function(node, spec.dimension)
        if isinstance(node, _OTHER_DIMENSIONLESS):  # engine output may hold these; no text can
            return self.function(node, "dimensionless")
        raise DimensionError(f"cannot work out the dimension of {node}", node)

    def function(self, node, rule: str) -> _Exponents:
        """A registered function's dimension rule (see :class:`.functions.Function`)."""
        dims = [self.walk(arg) for arg in node.args]
        if rule == "same":
            return dims[0]
        if rule == "any":
            return _NONE
        name = node.func.__name__
        if rule == "same_args":
            if any(d != dims[0] for d in dims):
                raise DimensionError(f"{name} needs two arguments of one dimension, got "
                                     f"{_words(dims[0])} and {_words(dims[1])}: {node}", node)
            return _NONE
        for dim in dims:
            if dim != _NONE:
                raise DimensionError(f"{name} needs a dimensionless argument, "
                                     f"got {_dim(dim).describe()}: {node}", node)
        return _NONE

    def add(self, node) -> _Exponents:
        # Fast pass in argument order. Only when a term fails or the terms disagree is the sum put in
        # printed order (slow), so that the message reads like str(expr) and names the same terms
        # as always. A term is walked once: its dimension, or its error, is kept for the second
        # pass (walking a failing term again at every level of nesting would take exponential time).
        walked: dict = {}
        first = None
        for term in node.args:
            if _is_zero(term):
                continue
            try:
                dim = walked[term] = self.walk(term)
            except Exception as error:
                walked[term] = error
                break
            if first is None:
                first = dim
            elif dim != first:
                break
        else:
            return first if first is not None else _NONE
        first_term, first_dim = None, None
        for term in node.as_ordered_terms():  # printed order, so messages read like str(expr)
            if _is_zero(term):
                continue  # an exact 0 fits any sum
            dim = walked[term] if term in walked else self.walk(term)
            if isinstance(dim, Exception):
                raise dim
            if first_dim is None:
                first_term, first_dim = term, dim
            elif dim != first_dim:
                raise DimensionError(f"adds {_words(first_dim)} to {_words(dim)}: "
                                     f"{first_term} + {term}", node)
        return first_dim if first_dim is not None else _NONE

    def power(self, node) -> _Exponents:
        base, exponent = node.args
        base_dim, exp_dim = self.walk(base), self.walk(exponent)
        if exp_dim != _NONE:
            raise DimensionError(f"raises to a power that is {_dim(exp_dim).describe()}: {node}", node)
        if base_dim == _NONE:
            return _NONE
        if not exponent.is_Rational:
            raise DimensionError(f"raises {_dim(base_dim).describe()} to the non-numeric power {exponent}: {node}",
                                 node)
        if exponent.is_Integer:
            n = int(exponent)
            return base_dim[0] * n, base_dim[1] * n, base_dim[2] * n
        q = Fraction(int(exponent.p), int(exponent.q))
        return tuple(_whole(Fraction(e) * q) for e in base_dim)


def _is_zero(node) -> bool:
    return bool(node.is_Number and node == 0)
