"""An implicit value: the k-th real root of f(x) = 0 in an interval, found numerically.

When a special value's condition has no closed form (m g l sin θ = k θ), a numeric answer can still
be graded: the engine states the value as "the answer's expression at the k-th root of the condition
in [lo, hi]", and the checker finds that root again at each student's parameter values. The rule
that finds the roots is here, in one place, because both sides must find the same ones: the engine
(`grader.mechanics.special_values`) to choose k, the checker (`grader.answers.numeric`) to evaluate.

Roots are found by a uniform scan for sign changes and exact zeros, each refined by bisection to
float precision. A sign change across a pole (1/x) is not a root: bisection towards a pole makes
|f| grow, towards a root shrink. A root where f touches zero without changing sign between two
scan points is missed (the engine checks that the count of roots stays the same across the
parameter draws, so both sides miss the same ones).

Examples
--------
>>> import math
>>> roots = real_roots(lambda x: 9.81 * math.sin(x) - 5 * x, 0.0, math.pi)
>>> [round(r, 6) for r in roots]
[0.0, 1.873056]
>>> real_roots(lambda x: 1 / x, -1.0, 1.0)  # a pole, not a root
[]
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Mapping

__all__ = ["Implicit", "ImplicitError", "SCAN_STEPS", "real_roots"]

SCAN_STEPS = 4000
_BISECTIONS = 200  # more than enough to reach adjacent floats from any float interval


class ImplicitError(ValueError):
    """Stored data that is not a valid implicit value (says which key and why)."""


def _value(f: Callable[[float], float], x: float) -> float:
    try:
        y = f(x)
    except (ArithmeticError, ValueError, TypeError):
        return math.nan
    return y if isinstance(y, float) and math.isfinite(y) else (float(y) if isinstance(y, int) else math.nan)


def _bisect(f: Callable[[float], float], a: float, fa: float, b: float, fb: float) -> float | None:
    """The root in (a, b) where f changes sign, or None when the change is a pole or a gap."""
    smallest = min(abs(fa), abs(fb))
    for _ in range(_BISECTIONS):
        m = a + (b - a) / 2
        if m <= a or m >= b:
            break
        fm = _value(f, m)
        if math.isnan(fm):
            return None
        if fm == 0:
            return m
        if (fm < 0) == (fa < 0):
            a, fa = m, fm
        else:
            b, fb = m, fm
    x, fx = (a, fa) if abs(fa) <= abs(fb) else (b, fb)
    return x if abs(fx) <= smallest else None


def real_roots(f: Callable[[float], float], lo: float, hi: float, steps: int = SCAN_STEPS) -> list[float]:
    """The real roots of ``f`` in ``[lo, hi]``, in increasing order (see the module notes).

    ``f`` returns a float; where it raises an arithmetic error or returns nan, it is undefined.
    """
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(f"roots are searched in a bounded interval, not [{lo}, {hi}]")
    xs = [lo + (hi - lo) * i / steps for i in range(steps)] + [hi]
    ys = [_value(f, x) for x in xs]
    roots: list[float] = []
    for i, (x, y) in enumerate(zip(xs, ys)):
        if y == 0:
            roots.append(x)
        elif i + 1 < len(xs) and not math.isnan(y) and not math.isnan(ys[i + 1]) and ys[i + 1] != 0 \
                and (y < 0) != (ys[i + 1] < 0):
            root = _bisect(f, x, y, xs[i + 1], ys[i + 1])
            if root is not None:
                roots.append(root)
    distinct: list[float] = []
    for r in roots:
        if not distinct or r - distinct[-1] > 1e-12 * max(1.0, abs(hi - lo)):
            distinct.append(r)
    return distinct


@dataclass(frozen=True)
class Implicit:
    """The k-th root (from 0, in increasing order) of ``condition = 0`` for ``unknown`` in
    ``[lo, hi]``: what a reference answer's ``unknown`` stands for when no closed form exists.

    ``condition`` is text in the checker's grammar (sympy's str form), in ``unknown`` and parameters.

    Examples
    --------
    >>> rule = Implicit.from_json({"condition": "-g*sin(theta) + k*theta", "unknown": "theta",
    ...                            "interval": [0, 3.1416], "root": 1})
    >>> rule.root, rule.to_json()["interval"]
    (1, [0.0, 3.1416])
    """

    condition: str
    unknown: str
    lo: float
    hi: float
    root: int

    @classmethod
    def from_json(cls, data: Any) -> "Implicit":
        if not isinstance(data, Mapping):
            raise ImplicitError("'implicit' must be an object {condition, unknown, interval, root}")
        for key in ("condition", "unknown"):
            if not isinstance(data.get(key), str) or not data[key].strip():
                raise ImplicitError(f"implicit.{key} must be a non-empty string")
        interval = data.get("interval")
        if not (isinstance(interval, (list, tuple)) and len(interval) == 2
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                        for v in interval) and interval[0] < interval[1]):
            raise ImplicitError("implicit.interval must be [lo, hi] with finite lo < hi")
        root = data.get("root")
        if isinstance(root, bool) or not isinstance(root, int) or root < 0:
            raise ImplicitError("implicit.root must be a whole number >= 0")
        return cls(data["condition"], data["unknown"], float(interval[0]), float(interval[1]), root)

    def to_json(self) -> dict[str, Any]:
        return {"condition": self.condition, "unknown": self.unknown, "interval": [self.lo, self.hi],
                "root": self.root}

    def solve(self, f: Callable[[float], float]) -> float | None:
        """The chosen root of ``f`` (the condition at given parameter values), or None if it has fewer."""
        roots = real_roots(f, self.lo, self.hi)
        return roots[self.root] if self.root < len(roots) else None
