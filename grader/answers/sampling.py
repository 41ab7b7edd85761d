"""Sample points for numeric comparison: from each variable's declared domain, plus scale stress.

Points are drawn from a generator seeded by the reference, so the same reference is always probed
at the same points (verdicts are reproducible and reference values can be cached), and every
point lies inside the declared domains, which is what makes the comparison domain-aware:
``sqrt(1 - sin(theta)**2)`` equals ``cos(theta)`` at every point of ``[-pi/2, pi/2]`` and
differs at most points of the real line.
"""

from __future__ import annotations

import hashlib
import math
from typing import Any, Mapping

import numpy as np
import sympy

__all__ = ["GivenPoints", "Sampler", "UnorderedPoint", "seed_for"]

# Every STRESS_EVERY-th point puts the unbounded positive variables at extreme scales
# (1e-6 .. 1e6), where float64 cancels badly and where an answer off by a small term shows.
STRESS_EVERY = 4
STRESS_DECADES = 6.0
# Offset of the seed of the wide points' generator from the ordinary one's.
WIDE_STREAM = 0x5EED
# Real variables on stress points: magnitudes 10**-3 .. 10**6, either sign, from a generator of
# their own (seed + REAL_STREAM).
REAL_DECADES = (3.0, 6.0)
REAL_STREAM = 0x4EA1
# Interval variables on stress points: a value from the bands ordinary points avoid (near zero,
# the outer ends; `Domain.sample_avoided`), from a generator of their own (seed + BAND_STREAM).
BAND_STREAM = 0xBA4D
# The other points of a bounded interval are stratified: in each block of 2 * STRESS_EVERY points,
# its ordinary points take the interval's equal parts once each, in an order drawn from a
# generator of their own (seed + STRATA_STREAM), so that no part is missed by chance.
STRATA_STREAM = 0x57A7
_BLOCK = 2 * STRESS_EVERY
_REGULAR_PER_BLOCK = _BLOCK - 2
# Draws tried for a point that keeps the variables' order relations (a < R) before pairs are swapped.
_RELATED_TRIES = 16


def seed_for(*parts: Any) -> int:
    """A stable 64-bit seed from the reference (not Python's salted ``hash``).

    >>> seed_for("m*g", "expression") == seed_for("m*g", "expression")
    True
    """
    digest = hashlib.blake2b(repr(parts).encode(), digest_size=8).digest()
    return int.from_bytes(digest, "little")


def _real_line(domain) -> bool:
    """A variable over the whole real line, whose stress points span both signs and every scale."""
    return getattr(domain, "kind", None) == "real"


def _stressable(domain) -> bool:
    assumptions = getattr(domain, "assumptions", {}) or {}
    if not (assumptions.get("positive") or assumptions.get("nonnegative")):
        return False
    try:
        return bool(domain.contains(10.0**-STRESS_DECADES)) and bool(domain.contains(10.0**STRESS_DECADES))
    except Exception:
        return False


def _moved(value: float, bound: float, domain, below: bool) -> float:
    """``value`` moved to the side of ``bound`` that ``below`` says, inside ``domain``; unchanged where the
    domain has no room there (the order then fails, and the caller's own check says so)."""
    kind = getattr(domain, "kind", None)
    if kind == "interval":
        lo, hi = float(domain.lo), float(domain.hi)
        share = min(max((value - lo) / (hi - lo), 1e-3), 1 - 1e-3) if hi > lo else 0.5
        lo, hi = (lo, min(hi, bound)) if below else (max(lo, bound), hi)
        return lo + share * (hi - lo) if hi > lo else value
    if below:
        if kind in ("positive", "nonnegative"):
            return bound * abs(value) / (abs(value) + bound) if bound > 0 else value
        return bound - abs(value) - 1e-3 * max(1.0, abs(bound))
    return bound + abs(value) + 1e-3 * max(1.0, abs(bound))


class UnorderedPoint(ValueError):
    """No point of the domains keeps a declared order ``a < R``: nothing may be compared there."""


class Sampler:
    """Points ``{Symbol: float}`` inside the variables' domains, generated lazily and remembered.

    Parameters
    ----------
    domains : mapping of sympy.Symbol to Domain
        Each domain has ``sample(rng) -> float`` (rng a ``numpy.random.Generator``) and
        ``contains(x) -> bool``.
    seed : int
        Seed of the generator; the i-th point only depends on the seed and on i.
    stress : bool
        Whether every fourth point puts positive unbounded variables at extreme scales.

    Examples
    --------
    >>> import sympy
    >>> class Unit:                                  # a stand-in for grader.expressions.Domain
    ...     assumptions = {"real": True}
    ...     def sample(self, rng): return float(rng.uniform(0, 1))
    ...     def contains(self, x): return 0 <= x <= 1
    >>> x = sympy.Symbol("x", real=True)
    >>> s = Sampler({x: Unit()}, seed=1)
    >>> 0 <= s.point(5)[x] <= 1 and s.point(5) == s.point(5)
    True
    """

    def __init__(self, domains: Mapping[sympy.Symbol, Any], seed: int, stress: bool = True,
                 below: Mapping[sympy.Symbol, sympy.Symbol] | None = None):
        self.domains = dict(sorted(domains.items(), key=lambda item: item[0].name))
        # {a: R}: a < R at every point (a hoop's off-centre mass inside its radius); the pairs whose
        # two symbols this sampler draws.
        self.below = {a: b for a, b in (below or {}).items() if a in self.domains and b in self.domains}
        # and the pairs across this sampler and another (a coordinate x below a length L, a parameter):
        # kept by `joint`, which moves this sampler's value given the other's.
        self.across = {a: b for a, b in (below or {}).items() if (a in self.domains) != (b in self.domains)}
        self._seed = seed
        self._rng = np.random.default_rng(seed)
        self._wide_rng = None
        self._wide_points: list[dict[sympy.Symbol, float]] = []
        self._stress = {s for s, d in self.domains.items() if stress and _stressable(d)}
        # Real variables too: |x| <= 3 alone would call abs(x - 10) and 10 - x the same. Their
        # stress values come from a generator of their own, so every other value stays as it was.
        self._stress_real = {s for s, d in self.domains.items() if stress and _real_line(d)}
        self._real_rng = np.random.default_rng(seed + REAL_STREAM)
        self._stress_bands = {s for s, d in self.domains.items()
                              if stress and getattr(d, "sample_avoided", None) and d.avoided_bands()}
        self._band_rng = np.random.default_rng(seed + BAND_STREAM)
        self._stratified = {s for s, d in self.domains.items() if getattr(d, "sample_stratum", None) and d.avoided_bands()}
        self._strata_rng = np.random.default_rng(seed + STRATA_STREAM)
        self._strata: dict = {}
        self._points: list[dict[sympy.Symbol, float]] = []

    @property
    def banded(self) -> set:
        """The variables whose stress points take the bands of a finite interval that the others avoid
        (`Domain.avoided_bands`): its ends and each side of zero, one band per stress point in turn."""
        return self._stress_bands

    def point(self, i: int) -> dict[sympy.Symbol, float]:
        while len(self._points) <= i:
            self._points.append(self._related(lambda: self._draw(len(self._points))))
        return self._points[i]

    def joint(self, given: Mapping[sympy.Symbol, float], point: Mapping[sympy.Symbol, float]) -> dict:
        """``given`` (another sampler's point, the parameters) with this sampler's ``point``, each of this
        sampler's values that breaks a ``below`` order with a given one moved inside its domain to keep it
        (x of (0, ∞) below L: L x/(x + L)); a deterministic function of both points.

        >>> class Positive:
        ...     kind = "positive"
        ...     def contains(self, v): return v > 0
        >>> x, L = sympy.symbols("x L")
        >>> states = Sampler({x: Positive()}, seed=1, below={x: L})
        >>> states.joint({L: 1.0}, {x: 3.0})[x]
        0.75
        """
        joint = {**given, **point}
        for a, b in self.across.items():
            if a in joint and b in joint and not joint[a] < joint[b]:
                moved = a if a in point else b
                joint[moved] = _moved(joint[moved], joint[b] if moved is a else joint[a], self.domains[moved],
                                      below=moved is a)
        return joint

    def _related(self, draw) -> dict[sympy.Symbol, float]:
        """A point from ``draw`` that keeps every ``below`` relation: drawn again (from the same stream, so
        the i-th point still depends on the seed and i only), or, past a few tries, with each pair that
        breaks it swapped (a < R holds wherever R < a did)."""
        point = draw()
        for _ in range(_RELATED_TRIES):
            if all(point[a] < point[b] for a, b in self.below.items()):
                return point
            point = draw()
        for a, b in self.below.items():
            if not point[a] < point[b] and self.domains[a].contains(point[b]) and self.domains[b].contains(point[a]):
                point[a], point[b] = point[b], point[a]
        broken = [f"{a} < {b}" for a, b in self.below.items() if not point[a] < point[b]]
        if broken:
            # Never compare where the order fails: an answer right only there would be proved wrong.
            raise UnorderedPoint(f"no point of the variables' domains found that keeps {', '.join(broken)}: "
                                 "check their domains")
        return point

    def wide_point(self, i: int) -> dict[sympy.Symbol, float]:
        """The i-th point drawn across the domains' whole scale (``Domain.sample_wide``).

        Used where the reference is undefined at the ordinary points (an expression defined only for
        x >= 5, with x real): a stream of its own, so the ordinary points never change.
        """
        if self._wide_rng is None:
            self._wide_rng = np.random.default_rng(self._seed + WIDE_STREAM)
        while len(self._wide_points) <= i:
            self._wide_points.append(self._related(self._draw_wide))
        return self._wide_points[i]

    def _draw_wide(self) -> dict[sympy.Symbol, float]:
        point = {}
        for symbol, domain in self.domains.items():
            wide = getattr(domain, "sample_wide", None)
            value = float(wide(self._wide_rng)) if wide is not None else float(domain.sample(self._wide_rng))
            point[symbol] = value if math.isfinite(value) else 1.0
        return point

    def _stratum_value(self, symbol, domain, i: int) -> float:
        """The i-th (ordinary, not stress) point's value of an interval variable: one of the equal
        parts of its block's order."""
        block, position = divmod(i, _BLOCK)
        order = self._strata.get((symbol, block))
        if order is None:
            order = self._strata[symbol, block] = self._strata_rng.permutation(_REGULAR_PER_BLOCK)
        regular = position - position // STRESS_EVERY  # the stress positions (3, 7) take no part
        return float(domain.sample_stratum(self._strata_rng, int(order[regular]), _REGULAR_PER_BLOCK))

    def _draw(self, i: int) -> dict[sympy.Symbol, float]:
        stress = i % STRESS_EVERY == STRESS_EVERY - 1
        point = {}
        for symbol, domain in self.domains.items():
            if stress and symbol in self._stress:
                value = 10.0 ** self._rng.uniform(-STRESS_DECADES, STRESS_DECADES)
            else:
                value = float(domain.sample(self._rng))
                if not math.isfinite(value):  # a domain that cannot sample: fall back to 1
                    value = 1.0
                if stress and symbol in self._stress_real:
                    magnitude = 10.0 ** self._real_rng.uniform(-REAL_DECADES[0], REAL_DECADES[1])
                    value = magnitude if self._real_rng.uniform() < 0.5 else -magnitude
                elif stress and symbol in self._stress_bands:
                    value = float(domain.sample_avoided(self._band_rng, i // STRESS_EVERY))
                elif not stress and symbol in self._stratified:
                    value = self._stratum_value(symbol, domain, i)
            point[symbol] = value
        return point


class GivenPoints:
    """A stand-in for a `Sampler` whose points are given: the i-th is ``points[i % len(points)]``,
    with the sampler's domains and orders, and its way of joining another sampler's point (`Sampler.joint`).

    >>> class Positive:
    ...     kind = "positive"
    ...     def contains(self, v): return v > 0
    >>> x = sympy.Symbol("x")
    >>> given = GivenPoints(Sampler({x: Positive()}, seed=1), [{x: 2.0}, {x: 5.0}])
    >>> given.point(0)[x], given.point(7)[x]
    (2.0, 5.0)
    """

    def __init__(self, sampler: Sampler, points: list[dict]):
        self._sampler = sampler
        self._points = list(points)
        self.domains = sampler.domains
        self.below = sampler.below
        self.across = sampler.across

    def point(self, i: int) -> dict[sympy.Symbol, float]:
        return self._points[i % len(self._points)]

    def joint(self, given: Mapping[sympy.Symbol, float], point: Mapping[sympy.Symbol, float]) -> dict:
        return self._sampler.joint(given, point)
