"""Domains, variables and the namespace of names a text may use."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from functools import cached_property
from typing import Iterable, Mapping

import sympy

from .dimensions import Dimension, parse_dimension
from .functions import FUNCTIONS
from .names import Resolved, latex_name, resolve_name

__all__ = ["Domain", "parse_domain", "Variable", "Namespace", "KINDS"]

#: What role a variable plays in a scene.
KINDS = frozenset({"parameter", "coordinate", "velocity", "acceleration", "multiplier",
                   "force", "time", "answer"})

# Spot checks sample magnitudes in [0.5, 3]: away from 0 (where x and sin(x)
# or x and x^3 agree too closely) and not so large that exp/cosh overflow.
_SAMPLE_LO, _SAMPLE_HI = 0.5, 3.0


@dataclass(frozen=True)
class Domain:
    """Where a variable's values live: positive, nonnegative, real, or [lo, hi].

    Examples
    --------
    >>> parse_domain("positive").assumptions
    {'positive': True}
    >>> d = parse_domain([0, "pi/2"]); d.contains(1.0), d.contains(2.0), d.assumptions
    (True, False, {'nonnegative': True})
    >>> import random
    >>> 0.5 <= parse_domain("positive").sample(random.Random(1)) <= 3
    True
    """

    kind: str
    lo: float = -math.inf
    hi: float = math.inf

    def __post_init__(self) -> None:
        if self.kind not in ("positive", "nonnegative", "real", "interval"):
            raise ValueError(f"unknown domain kind {self.kind!r}")
        if self.kind == "interval" and not self.lo < self.hi:
            raise ValueError(f"domain [{self.lo}, {self.hi}] is empty: the lower end must be below the upper")

    @property
    def assumptions(self) -> dict[str, bool]:
        """sympy symbol assumptions implied by the domain."""
        if self.kind != "interval":
            return {self.kind: True}
        if self.lo > 0:
            return {"positive": True}
        if self.lo == 0:
            return {"nonnegative": True}
        if self.hi < 0:
            return {"negative": True}
        if self.hi == 0:
            return {"nonpositive": True}
        return {"real": True}

    def contains(self, x) -> bool:
        """Whether the real number ``x`` lies in the domain (ends included)."""
        try:
            value = float(x)
        except (TypeError, ValueError):
            return False
        if math.isnan(value):
            return False
        if self.kind == "positive":
            return value > 0 and math.isfinite(value)
        if self.kind == "nonnegative":
            return value >= 0 and math.isfinite(value)
        if self.kind == "real":
            return math.isfinite(value)
        return self.lo <= value <= self.hi and math.isfinite(value)

    def sample(self, rng) -> float:
        """A random value well inside the domain, for numerical spot checks.

        ``rng`` is a ``random.Random`` or ``numpy.random.Generator`` (only
        ``rng.uniform`` is used).  Unbounded domains give log-uniform
        magnitudes in [0.5, 3] (with a random sign for ``real``); intervals
        avoid the outer 5% at each end and magnitudes below a tenth of the
        interval's scale.
        """
        if self.kind in ("positive", "nonnegative", "real"):
            magnitude = math.exp(float(rng.uniform(math.log(_SAMPLE_LO), math.log(_SAMPLE_HI))))
            if self.kind == "real" and float(rng.uniform(0, 1)) < 0.5:
                return -magnitude
            return magnitude
        lo, hi = self.lo, self.hi
        if math.isinf(lo) or math.isinf(hi):
            magnitude = math.exp(float(rng.uniform(math.log(_SAMPLE_LO), math.log(_SAMPLE_HI))))
            return hi - magnitude if math.isinf(lo) else lo + magnitude
        margin = 0.05 * (hi - lo)
        lo, hi = lo + margin, hi - margin
        tiny = 0.1 * max(abs(lo), abs(hi))
        value = float(rng.uniform(lo, hi))
        for _ in range(50):
            if abs(value) >= tiny:
                break
            value = float(rng.uniform(lo, hi))
        return value

    def sample_stratum(self, rng, j: int, n: int) -> float:
        """A value from the ``j``-th of ``n`` equal parts of a finite interval (strictly inside it), or
        `sample`'s kind of value for any other domain. Points that take each part once cover every
        part: eight random ones all miss |θ| > π/2 on [-π, π] once in 256 checks.

        Examples
        --------
        >>> import random
        >>> d = parse_domain([-4, 4])
        >>> sorted(int(d.sample_stratum(random.Random(j), j, 8) // 1) for j in range(8))
        [-4, -3, -2, -1, 0, 1, 2, 3]
        """
        if self.kind != "interval" or not (math.isfinite(self.lo) and math.isfinite(self.hi)):
            return self.sample(rng)
        width = (self.hi - self.lo) / n
        value = self.lo + (j + float(rng.uniform(0, 1))) * width
        if not self.lo < value < self.hi:
            value = self.lo + (j + 0.5) * width
        return value

    def avoided_bands(self) -> list[tuple[float, float]]:
        """The parts of a finite interval that `sample` never draws from: the values near zero
        (nearest first, where a sign or an ``abs`` changes) and the outer 5% at each end.

        Examples
        --------
        >>> [(round(a, 3), round(b, 3)) for a, b in parse_domain([-1, 10]).avoided_bands()]
        [(-0.945, 0.0), (0.0, 0.945), (-1.0, -0.45), (9.45, 10.0)]
        >>> parse_domain("real").avoided_bands()
        []
        """
        if self.kind != "interval" or not (math.isfinite(self.lo) and math.isfinite(self.hi)):
            return []
        margin = 0.05 * (self.hi - self.lo)
        lo, hi = self.lo + margin, self.hi - margin
        tiny = 0.1 * max(abs(lo), abs(hi))
        # each side of zero on its own: on [-0.2, π] the few negative values are what matters
        near_zero = [(a, b) for a, b in ((max(self.lo, -tiny), min(self.hi, 0.0)), (max(self.lo, 0.0), min(self.hi, tiny)))
                     if a < b]
        ends = [(a, b) for a, b in ((self.lo, lo), (hi, self.hi))
                if not any(c <= a < b <= d for c, d in near_zero)]
        return near_zero + ends

    def sample_avoided(self, rng, k: int) -> float:
        """A value from the ``k``-th (cyclically) of `avoided_bands`, strictly inside the interval,
        or `sample`'s kind of value where there is none: spot checks that only drew from `sample`
        never saw v < 0 on [-1, 10], where -c v|v| and -c v² differ.

        Examples
        --------
        >>> import random
        >>> d = parse_domain([-1, 10])
        >>> all(-1 < d.sample_avoided(random.Random(k), 2) < -0.45 for k in range(20))
        True
        """
        bands = self.avoided_bands()
        if not bands:
            return self.sample(rng)
        lo, hi = bands[k % len(bands)]
        value = float(rng.uniform(lo, hi))
        if not self.lo < value < self.hi:  # never an end itself, where the expressions may not be defined
            value = lo + 0.5 * (hi - lo)
        return value

    def sample_wide(self, rng, decades: tuple[float, float] = (-3.0, 6.0)) -> float:
        """A random value across the whole domain's scale, not only near 1.

        Unbounded domains give log-uniform magnitudes ``10**decades[0] .. 10**decades[1]`` (with a
        random sign for ``real``; measured from the finite end of a half-line); a bounded interval is
        sampled uniformly over its whole length, or log-uniformly when it spans decades on one side
        of zero. An expression defined only for x >= 5 is found here, where `sample` never goes.

        Examples
        --------
        >>> import random
        >>> rng = random.Random(2)
        >>> max(parse_domain("real").sample_wide(rng) for _ in range(50)) > 5
        True
        >>> all(1e-7 <= parse_domain([1e-7, 1e-5]).sample_wide(rng) <= 1e-5 for _ in range(50))
        True
        """
        lo, hi = self.lo, self.hi
        if self.kind in ("positive", "nonnegative", "real") or math.isinf(lo) or math.isinf(hi):
            magnitude = 10.0 ** float(rng.uniform(*decades))
            if self.kind in ("positive", "nonnegative"):
                return magnitude
            if self.kind == "real":
                return -magnitude if float(rng.uniform(0, 1)) < 0.5 else magnitude
            return hi - magnitude if math.isinf(lo) else lo + magnitude
        if lo > 0 and hi / lo > 100:
            return math.exp(float(rng.uniform(math.log(lo), math.log(hi))))
        if hi < 0 and lo / hi > 100:
            return -math.exp(float(rng.uniform(math.log(-hi), math.log(-lo))))
        return float(rng.uniform(lo, hi))

    def to_json(self):
        """The scene-file form that :func:`parse_domain` reads back: a kind name or ``[lo, hi]``.

        Infinite ends become the strings ``"inf"``/``"-inf"`` (JSON has no infinity).

        Examples
        --------
        >>> parse_domain("positive").to_json(), parse_domain([0, 2]).to_json()
        ('positive', [0.0, 2.0])
        """
        if self.kind != "interval":
            return self.kind
        return [end if math.isfinite(end) else ("inf" if end > 0 else "-inf") for end in (self.lo, self.hi)]

    def __str__(self) -> str:
        return self.kind if self.kind != "interval" else f"[{self.lo:g}, {self.hi:g}]"


def _bound(value, what: str) -> float:
    if isinstance(value, bool):
        raise ValueError(f"domain {what} end must be a number, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        if value.strip() in ("inf", "oo", "-inf", "-oo"):
            return -math.inf if value.strip().startswith("-") else math.inf
        from .parser import parse_expression  # bounds like "pi/2"; local import avoids a cycle
        expr = parse_expression(value, Namespace([])).expr
        if not expr.is_number or not expr.is_real:
            raise ValueError(f"domain {what} end {value!r} is not a real number")
        # Rounded outward, so that the interval holds its true end: with "pi/2" rounded down, cos θ had no
        # zero on [0, "pi/2"], and a factor that vanishes there was proved nonzero.
        end, exact = float(expr), expr.evalf(40)
        if what == "upper" and end < exact:
            return math.nextafter(end, math.inf)
        if what == "lower" and end > exact:
            return math.nextafter(end, -math.inf)
        return end
    raise ValueError(f"domain {what} end must be a number, got {value!r}")


def parse_domain(spec) -> Domain:
    """Read a domain from a scene file value.

    ``"positive"``, ``"nonnegative"``, ``"real"`` or a two-element list
    ``[lo, hi]`` of numbers (or number text such as ``"pi/2"``).

    Examples
    --------
    >>> parse_domain("real"), parse_domain([-1, 1])
    (Domain(kind='real', lo=-inf, hi=inf), Domain(kind='interval', lo=-1.0, hi=1.0))
    """
    if isinstance(spec, Domain):
        return spec
    if isinstance(spec, str):
        key = spec.strip().lower()
        if key in ("positive", "nonnegative", "real"):
            return Domain(key)
        raise ValueError(f"unknown domain {spec!r}; use 'positive', 'nonnegative', 'real' or [lo, hi]")
    if isinstance(spec, (list, tuple)) and len(spec) == 2:
        return Domain("interval", _bound(spec[0], "lower"), _bound(spec[1], "upper"))
    raise ValueError(f"a domain is 'positive', 'nonnegative', 'real' or [lo, hi], got {spec!r}")


_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


@dataclass(frozen=True)
class Variable:
    """A named quantity: its dimension, domain and role in the scene.

    ``dimension`` and ``domain`` may be given as text (or a list for the
    domain); they are parsed on construction.

    Examples
    --------
    >>> v = Variable("thetadot", "angular_velocity", "real", "velocity")
    >>> v.symbol, v.symbol.is_real, v.latex
    (thetadot, True, '\\\\dot{\\\\theta}')
    """

    name: str
    dimension: Dimension
    domain: Domain = field(default_factory=lambda: Domain("real"))
    kind: str = "parameter"

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not _NAME.match(self.name):
            raise ValueError(f"variable name {self.name!r} must start with a letter and contain "
                             "only letters, digits and underscores")
        if self.kind not in KINDS:
            raise ValueError(f"variable kind {self.kind!r} is not one of {sorted(KINDS)}")
        object.__setattr__(self, "dimension", parse_dimension(self.dimension))
        object.__setattr__(self, "domain", parse_domain(self.domain))

    @cached_property
    def symbol(self) -> sympy.Symbol:
        return sympy.Symbol(self.name, **self.domain.assumptions)

    @property
    def latex(self) -> str:
        return latex_name(self.name)


class Namespace:
    """The variables a text may refer to, by name.

    Parameters
    ----------
    variables : iterable of Variable (or a mapping name -> Variable)

    Examples
    --------
    >>> ns = Namespace([Variable("m", "mass", "positive"), Variable("theta", "angle", "real")])
    >>> ns.symbol("theta"), "m" in ns, ns["m"].dimension.describe()
    (theta, True, 'a mass (kg)')
    >>> ns.latex_names()[ns.symbol("theta")]
    '\\\\theta'
    """

    def __init__(self, variables: Iterable[Variable] | Mapping[str, Variable] = ()) -> None:
        if isinstance(variables, Mapping):
            variables = variables.values()
        self._variables: dict[str, Variable] = {}
        for variable in variables:
            if not isinstance(variable, Variable):
                raise TypeError(f"Namespace takes Variable objects, got {variable!r}")
            if variable.name in self._variables:
                raise ValueError(f"variable {variable.name!r} is declared twice")
            if variable.name in FUNCTIONS or variable.name in ("dot", "ddot"):
                raise ValueError(f"variable name {variable.name!r} is a function name; choose another")
            self._variables[variable.name] = variable
        self.names = frozenset(self._variables)
        # Underscore-free spelling -> names, so m_1 finds m1 and theta_dot finds thetadot.
        by_key: dict[str, list[str]] = {}
        for name in self._variables:
            by_key.setdefault(name.replace("_", ""), []).append(name)
        self.names_by_key = {key: tuple(names) for key, names in by_key.items()}
        # Built on first use and handed out as copies: every parse asks for the LaTeX names and every
        # check for the dimensions, and the variables never change after construction.
        self._dimensions: dict[sympy.Symbol, Dimension] | None = None
        self._latex_names: dict[sympy.Symbol, str] | None = None

    @classmethod
    def from_spec(cls, spec: Mapping[str, Mapping]) -> "Namespace":
        """Build from ``{name: {"dimension": ..., "domain": ..., "kind": ...}}`` (answer-checker JSON).

        Examples
        --------
        >>> Namespace.from_spec({"m": {"dimension": "mass", "domain": "positive"}}).symbol("m").is_positive
        True
        """
        return cls(Variable(name, info.get("dimension", "dimensionless"), info.get("domain", "real"),
                            info.get("kind", "parameter")) for name, info in spec.items())

    @property
    def variables(self) -> tuple[Variable, ...]:
        return tuple(self._variables.values())

    def symbol(self, name: str) -> sympy.Symbol:
        """The sympy symbol of a declared name; ``KeyError`` for anything else."""
        try:
            return self._variables[name].symbol
        except KeyError:
            raise KeyError(f"no variable named {name!r}; declared: {', '.join(sorted(self.names)) or 'none'}") from None

    def resolve(self, name: str, order: int = 0) -> Resolved:
        """What a typed name means here (the parser's name lookup); see :func:`.names.resolve_name`.

        Examples
        --------
        >>> ns = Namespace([Variable("theta", "angle"), Variable("thetadot", "1/s")])
        >>> ns.resolve("theta_dot").value, ns.resolve("theta", order=1).value
        (thetadot, thetadot)
        """
        return resolve_name(name, self, order=order)

    def dimensions(self) -> dict[sympy.Symbol, Dimension]:
        if self._dimensions is None:
            self._dimensions = {v.symbol: v.dimension for v in self._variables.values()}
        return dict(self._dimensions)

    def latex_names(self) -> dict[sympy.Symbol, str]:
        if self._latex_names is None:
            self._latex_names = {v.symbol: v.latex for v in self._variables.values()}
        return dict(self._latex_names)

    def __getitem__(self, name: str) -> Variable:
        return self._variables[name]

    def __contains__(self, name: object) -> bool:
        return name in self._variables

    def __iter__(self):
        return iter(self._variables.values())

    def __len__(self) -> int:
        return len(self._variables)

    def __repr__(self) -> str:
        return f"Namespace({', '.join(self._variables)})"
