"""The reference-answer contract: what the checker needs to grade one answer, in one typed definition.

A `ReferenceAnswer` is what the engine derives for each ``[[answers]]`` entry of a scene, what the
store keeps as JSON in ``problem_versions.references`` and what the grading worker sends to the
checker, so grading never runs the engine again.

Why it lives here, in ``grader.answers``: the checker is what consumes it, and data flows one way
(``expressions -> mechanics -> ... -> answers -> store -> jobs``), so ``grader.mechanics`` may not
import it. The engine therefore emits plain JSON data with these keys
(:func:`grader.mechanics.references.reference_answers`), and whoever takes that data past the
engine (``grader.jobs.derivation`` before storing it, the grading worker before checking)
reads it through `ReferenceAnswer.from_json`, which refuses anything that breaks the contract. One
definition, validated where it crosses into the checker's side, and no import against the flow.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

__all__ = ["ReferenceAnswer", "ReferenceAnswerError", "KINDS", "DETAILS", "EXPECTS"]

KINDS = ("expression", "equation", "numeric")
EXPECTS = ("equivalent", "not_equivalent", "invalid")  # what a question test may expect
# How much a slip message may say: "kind" names the slip only; "full" adds factors and differences.
# (Here, not in grader.answers.feedback, so reading the contract does not import sympy.)
DETAILS = ("kind", "full")
_TEXT_KEYS = ("name", "prompt", "kind", "reference", "dimension", "latex")


def _is_number(value: Any, low: float, high: float = float("inf")) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and low <= value <= high


class ReferenceAnswerError(ValueError):
    """Stored or derived data that is not a valid reference answer (says which key and why)."""


@dataclass(frozen=True)
class ReferenceAnswer:
    """One answer a problem asks for, with everything needed to check a student's text against it.

    Attributes
    ----------
    name : str
        The answer's name in the scene (``tension``).
    prompt : str
        What the student is asked.
    kind : {"expression", "equation", "numeric"}
        ``numeric``: the student types a number with a unit, checked against ``reference``
        evaluated at the student's parameter values (`grader.answers.numeric`).
    reference : str
        The reference in the checker's grammar (sympy's ``str()`` form, which our parser reads back).
    variables : dict
        ``{name: {"dimension", "domain", "kind"?}}``: the names a student may use.
    dimension : str
        The answer's dimension as an SI expression (``"kg*m/s^2"``), or ``"dimensionless"``.
    latex : str
        The reference typeset, for instructors.
    feedback : tuple of dict
        The instructor's ``{"expr", "message", "score"?}`` entries for known wrong answers
        (``score``: partial credit in [0, 1] for an answer that matches the entry).
    feedback_detail : {"kind", "full"}
        How much slip messages may say (``"kind"`` never states a value; see
        `grader.answers.feedback`); set per problem by ``[feedback] detail`` in the scene file.
    alternatives : tuple of str
        Other references that are also right (``alternatives`` in the scene file: the mirror
        equilibrium, the other sign convention); the verdict's ``evidence["matched"]`` says which.
    unit : str
        Numeric answers: the unit text the answer is asked in (``"N"``); ``""`` asks for the answer's
        dimension in any unit of it, a pure number only where the reference is dimensionless. Kept as
        given: what it means, and whether it agrees with the reference, is decided by the checker
        (`grader.answers.numeric.asked_unit`), as for a request that names no unit.
    tolerance : dict or None
        Numeric answers: ``{"relative"?, "absolute"?, "sig_figs"?}`` (None: 1 % relative).
    weight : float
        The answer's weight in its problem's score (default 1: answers count equally).
    parameters : dict
        ``{name: {"value"? | "random"? | "choices"?, "dimension"}}``: the problem's parameters with
        numbers, from which `grader.answers.randomised.draw_parameters` draws a student's values.
    tests : tuple of dict
        The instructor's question tests ``{"answer", "expect", "score"?, "values"?}``, run when the
        problem is registered (`grader.answers.question_tests`).
    implicit : dict or None
        Numeric answers without a closed form: ``reference`` is in an unknown that stands for a root
        of a condition found numerically at the student's numbers
        (`grader.expressions.implicit.Implicit`, as JSON).

    Examples
    --------
    >>> ref = ReferenceAnswer.from_json({"name": "tension", "prompt": "T", "kind": "expression",
    ...     "reference": "g*m/3", "variables": {"m": {"dimension": "kg", "domain": "positive"},
    ...     "g": {"dimension": "m*s^-2", "domain": "positive"}}, "dimension": "kg*m*s^-2", "latex": ""})
    >>> ref.request("m g/3")["answer"], ref.feedback_detail
    ('m g/3', 'kind')
    >>> ReferenceAnswer.from_json({"name": "t"})
    Traceback (most recent call last):
    ...
    grader.answers.reference.ReferenceAnswerError: reference answer 't': 'prompt' is missing
    """

    name: str
    prompt: str
    kind: str
    reference: str
    variables: dict[str, dict[str, Any]]
    dimension: str
    latex: str
    feedback: tuple[dict[str, str], ...] = field(default_factory=tuple)
    feedback_detail: str = "kind"
    alternatives: tuple[str, ...] = ()
    unit: str = ""
    tolerance: dict[str, Any] | None = None
    weight: float = 1.0
    parameters: dict[str, dict[str, Any]] = field(default_factory=dict)
    tests: tuple[dict[str, Any], ...] = ()
    implicit: dict[str, Any] | None = None

    @classmethod
    def from_json(cls, data: Any) -> "ReferenceAnswer":
        """Read and validate one reference answer (the engine's output or a stored row).

        Raises
        ------
        ReferenceAnswerError
            When a key is missing or has the wrong type or value.
        """
        if not isinstance(data, Mapping):
            raise ReferenceAnswerError("a reference answer must be a JSON object")
        label = f"reference answer {data.get('name')!r}" if isinstance(data.get("name"), str) else "reference answer"

        def fail(message: str) -> ReferenceAnswerError:
            return ReferenceAnswerError(f"{label}: {message}")

        for key in _TEXT_KEYS:
            if key not in data:
                raise fail(f"{key!r} is missing")
            if not isinstance(data[key], str):
                raise fail(f"{key!r} must be a string")
        if data["kind"] not in KINDS:
            raise fail(f"'kind' must be one of {', '.join(KINDS)}")
        variables = data.get("variables")
        if not isinstance(variables, Mapping) or not all(
                isinstance(k, str) and isinstance(v, Mapping) and isinstance(v.get("dimension"), str)
                for k, v in variables.items()):
            raise fail("'variables' must map names to {dimension, domain}")
        feedback = data.get("feedback") or []
        if not isinstance(feedback, (list, tuple)) or not all(
                isinstance(f, Mapping) and isinstance(f.get("expr"), str) and isinstance(f.get("message"), str)
                for f in feedback):
            raise fail("'feedback' must be a list of {expr, message}")
        detail = data.get("feedback_detail", "kind")
        if detail not in DETAILS:
            raise fail(f"'feedback_detail' must be one of {', '.join(DETAILS)}")
        alternatives = data.get("alternatives") or []
        if not isinstance(alternatives, (list, tuple)) or not all(isinstance(a, str) for a in alternatives):
            raise fail("'alternatives' must be a list of reference texts")
        for f in feedback:
            if "score" in f and not _is_number(f["score"], 0, 1):
                raise fail("a feedback 'score' must be a number from 0 to 1")
        unit = data.get("unit", "")
        if not isinstance(unit, str):
            raise fail("'unit' must be a string")
        tolerance = data.get("tolerance")
        if tolerance is not None and (not isinstance(tolerance, Mapping) or set(tolerance) - {
                "relative", "absolute", "sig_figs"} or not all(_is_number(v, 0) for v in tolerance.values())):
            raise fail("'tolerance' must be {relative?, absolute?, sig_figs?} with numbers >= 0")
        weight = data.get("weight", 1.0)
        if not _is_number(weight, 0):
            raise fail("'weight' must be a number >= 0")
        parameters = data.get("parameters") or {}
        if not isinstance(parameters, Mapping) or not all(
                isinstance(k, str) and isinstance(v, Mapping) for k, v in parameters.items()):
            raise fail("'parameters' must map names to {value | random | choices}")
        tests = data.get("tests") or []
        if not isinstance(tests, (list, tuple)) or not all(
                isinstance(t, Mapping) and isinstance(t.get("answer"), str) and t.get("expect") in EXPECTS
                for t in tests):
            raise fail(f"'tests' must be a list of {{answer, expect}} with expect one of {', '.join(EXPECTS)}")
        implicit = data.get("implicit")
        if implicit is not None:
            from grader.expressions.implicit import Implicit, ImplicitError  # only here: sympy comes with it

            if data["kind"] != "numeric":
                raise fail("'implicit' applies to numeric answers only")
            try:
                implicit = Implicit.from_json(implicit).to_json()
            except ImplicitError as error:
                raise fail(str(error)) from None
            if implicit["unknown"] not in variables:
                raise fail("implicit.unknown must be one of the variables")
        return cls(**{k: data[k] for k in _TEXT_KEYS},
                   variables={k: dict(v) for k, v in variables.items()},
                   feedback=tuple({"expr": f["expr"], "message": f["message"],
                                   **({"score": float(f["score"])} if "score" in f else {})} for f in feedback),
                   feedback_detail=detail, alternatives=tuple(alternatives), unit=unit,
                   tolerance=dict(tolerance) if tolerance is not None else None, weight=float(weight),
                   parameters={k: dict(v) for k, v in parameters.items()}, tests=tuple(dict(t) for t in tests),
                   implicit=implicit)

    def to_json(self) -> dict[str, Any]:
        """The JSON object stored in ``problem_versions.references`` (`from_json` reads it back)."""
        return {"name": self.name, "prompt": self.prompt, "kind": self.kind, "reference": self.reference,
                "variables": self.variables, "dimension": self.dimension, "latex": self.latex,
                "feedback": [dict(f) for f in self.feedback], "feedback_detail": self.feedback_detail,
                "alternatives": list(self.alternatives), "unit": self.unit, "tolerance": self.tolerance,
                "weight": self.weight, "parameters": self.parameters, "tests": [dict(t) for t in self.tests],
                **({"implicit": dict(self.implicit)} if self.implicit is not None else {})}

    def values(self, drawn: Mapping[str, Any] | None = None) -> dict[str, float]:
        """The parameter values a numeric answer is checked at: the fixed ones, then ``drawn`` (the
        student's draw, `grader.answers.randomised.draw_parameters`) or else the preview draw."""
        from grader.answers.randomised import PREVIEW_SEED, draw_parameters, fixed_values

        if drawn is None:
            return draw_parameters(self.parameters, PREVIEW_SEED)
        return {**fixed_values(self.parameters), **{k: v for k, v in drawn.items() if isinstance(k, str)}}

    def request(self, text: str, values: Mapping[str, Any] | None = None) -> dict[str, Any]:
        """The checker request (``grader check --jsonl`` line) for a student's ``text`` against this reference.

        ``values``: the student's parameter values; used by numeric answers only (symbolic answers
        of a randomised problem stay symbolic: the student writes ``m*g/3``).
        """
        request = {"reference": self.reference, "answer": text, "variables": self.variables, "kind": self.kind,
                   "feedback": [dict(f) for f in self.feedback], "feedback_detail": self.feedback_detail}
        if self.alternatives:
            request["alternatives"] = list(self.alternatives)
        if self.kind == "numeric":
            request.update(values=self.values(values), unit=self.unit, dimension=self.dimension)
            if self.tolerance is not None:
                request["tolerance"] = dict(self.tolerance)
            if self.implicit is not None:
                request["implicit"] = dict(self.implicit)
        return request
