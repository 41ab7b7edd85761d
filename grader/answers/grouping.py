"""Wrong answers grouped by equivalence: "mg", "g*m" and "m*g*(sin²θ+cos²θ)" are one mistake.

Three steps, cheapest first, so that a course of 300 stays fast:

1. *Same reading*: texts that parse to the same sympy expression (``mg`` and ``m*g``) are one form,
   without any check.
2. *Numeric fingerprint*: each form is evaluated in float64 at a few fixed points of its
   variables' domains, by the checker's own evaluator (`grader.answers.evaluate`, compiled from the
   tree: no eval, the same function registry). Forms whose values differ cannot be equivalent, so
   they are never sent to the checker.
3. *The checker decides*: a form whose fingerprint matches a group's joins it only if the sandboxed
   checker (``grader.answers.check``, the same one that grades) says it is equivalent to the
   group's representative. Forms without a fingerprint (equations, unusual functions) are compared
   with every group by the checker.

Results are cached per (problem, answer) until a new verdict appears, and checker answers per pair
of forms for as long as the process lives, so a new wrong answer costs about one check.

It lives with the checker, not with the instructor pages that show it: it is a judgement about
answers, made with the checker's parser, evaluator and verdicts.
"""

from __future__ import annotations

import json
import math
import random
import threading
from collections import Counter, OrderedDict
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable

import sympy

from grader.answers.evaluate import SCALE, FloatBackend, Undefined, Unresolved, Unsupported, compile_expr
from grader.expressions import ExpressionError, Namespace, parse_equation, parse_expression

__all__ = ["Group", "GroupingCache", "fingerprint", "group_wrong_answers"]

POINTS = 3
REL_TOL = 1e-7
_FLOAT = FloatBackend()


@dataclass
class Group:
    """Equivalent wrong answers: the most common form first, with submission and student counts."""

    representative: str  # canonical text of the most common form
    latex: str | None
    forms: Counter = field(default_factory=Counter)  # text as typed -> submissions
    submissions: int = 0
    students: set = field(default_factory=set)
    values: tuple[float, ...] | None = None

    def to_json(self) -> dict[str, Any]:
        return {"representative": self.representative, "latex": self.latex, "submissions": self.submissions,
                "students": len(self.students), "forms": self.forms.most_common()}


def _points(namespace: Namespace) -> list[dict[sympy.Symbol, float]]:
    rng = random.Random(20240607)  # the same points every time, so fingerprints can be cached
    points = []
    for _ in range(POINTS):
        points.append({v.symbol: float(v.domain.sample(rng)) for v in namespace.variables})
    return points


def fingerprint(expr: sympy.Basic, namespace: Namespace) -> tuple[float, ...] | None:
    """The values of ``expr`` at fixed points of the namespace's domains, or None if it has none.

    >>> ns = Namespace.from_spec({"m": {"dimension": "kg", "domain": "positive"}})
    >>> fingerprint(parse_expression("2m", ns).expr, ns) == fingerprint(parse_expression("m+m", ns).expr, ns)
    True
    """
    try:
        function = compile_expr(expr, _FLOAT)
        values = tuple(function({**point, SCALE: 0.0}) for point in _points(namespace))
    except (Undefined, Unresolved, Unsupported, ValueError, ArithmeticError, RecursionError, KeyError):
        return None  # no plain value somewhere (a pole, an overflow, a name without a point)
    return values if all(isinstance(v, float) and math.isfinite(v) for v in values) else None


def _close(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    return all(math.isclose(x, y, rel_tol=REL_TOL, abs_tol=1e-12) for x, y in zip(a, b))


@dataclass(frozen=True)
class _Form:
    key: str  # canonical text (or the stripped text if it cannot be read)
    latex: str | None
    values: tuple[float, ...] | None


def _read(text: str, namespace: Namespace, kind: str) -> _Form:
    try:
        if kind == "equation":
            parsed = parse_equation(text, namespace)
            return _Form(f"{parsed.lhs} = {parsed.rhs}", parsed.latex, None)
        parsed = parse_expression(text, namespace)
    except (ExpressionError, ValueError, RecursionError):
        return _Form(" ".join(text.split()), None, None)
    return _Form(parsed.text, parsed.latex, fingerprint(parsed.expr, namespace))


def group_wrong_answers(reference: dict[str, Any], answers: Iterable[tuple[int, str]],
                        equivalent: Callable[[str, str], bool]) -> list[Group]:
    """Group ``(student id, text)`` wrong answers to ``reference``; most submissions first.

    ``equivalent(a, b)`` is the checker's opinion on two canonical texts (only asked when their
    fingerprints agree, or when either has none).
    """
    kind = reference.get("kind", "expression")
    try:
        namespace = Namespace.from_spec(reference.get("variables") or {})
    except ValueError:
        namespace = Namespace()
    forms: dict[str, _Form] = {}
    by_form: dict[str, list[tuple[int, str]]] = {}
    for student, text in answers:
        form = forms.get(text) or forms.setdefault(text, _read(text, namespace, kind))
        by_form.setdefault(form.key, []).append((student, text))
    groups: list[Group] = []
    readings = {form.key: form for form in forms.values()}
    for key in sorted(by_form, key=lambda k: (-len(by_form[k]), k)):  # big forms found groups
        form = readings[key]
        home = None
        for group in groups:
            if form.values is not None and group.values is not None and not _close(form.values, group.values):
                continue
            if equivalent(group.representative, key):
                home = group
                break
        if home is None:
            home = Group(representative=key, latex=form.latex, values=form.values)
            groups.append(home)
        for student, text in by_form[key]:
            home.forms[" ".join(text.split())] += 1
            home.submissions += 1
            home.students.add(student)
    return sorted(groups, key=lambda g: (-g.submissions, g.representative))


class GroupingCache:
    """Groupings per (problem, answer) until their inputs change, and checker answers per pair."""

    def __init__(self, max_pairs: int = 100_000):
        self._groups: dict[tuple, tuple[tuple, list[Group]]] = {}
        self._pairs: OrderedDict[tuple, bool] = OrderedDict()
        self._max_pairs = max_pairs
        self._lock = threading.Lock()

    def groups(self, key: tuple, signature: tuple, compute: Callable[[], list[Group]]) -> list[Group]:
        with self._lock:
            cached = self._groups.get(key)
        if cached is not None and cached[0] == signature:
            return cached[1]
        result = compute()
        with self._lock:
            self._groups[key] = (signature, result)
        return result

    def equivalent(self, reference: dict[str, Any], a: str, b: str, ask: Callable[[str, str], bool]) -> bool:
        scope = json.dumps([reference.get("kind"), reference.get("variables")], sort_keys=True)
        pair = (scope, *sorted((a, b)))
        with self._lock:
            if pair in self._pairs:
                self._pairs.move_to_end(pair)
                return self._pairs[pair]
        answer = ask(a, b)
        with self._lock:
            self._pairs[pair] = answer
            while len(self._pairs) > self._max_pairs:
                self._pairs.popitem(last=False)
        return answer

    def clear(self) -> None:
        with self._lock:
            self._groups.clear()
            self._pairs.clear()
