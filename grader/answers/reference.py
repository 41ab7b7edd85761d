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

__all__ = ["ReferenceAnswer", "ReferenceAnswerError", "KINDS", "DETAILS"]

KINDS = ("expression", "equation")
# How much a slip message may say: "kind" names the slip only; "full" adds factors and differences.
# (Here, not in grader.answers.feedback, so reading the contract does not import sympy.)
DETAILS = ("kind", "full")
_TEXT_KEYS = ("name", "prompt", "kind", "reference", "dimension", "latex")


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
    kind : {"expression", "equation"}
    reference : str
        The reference in the checker's grammar (sympy's ``str()`` form, which our parser reads back).
    variables : dict
        ``{name: {"dimension", "domain", "kind"?}}``: the names a student may use.
    dimension : str
        The answer's dimension as an SI expression (``"kg*m/s^2"``), or ``"dimensionless"``.
    latex : str
        The reference typeset, for instructors.
    feedback : tuple of dict
        The instructor's ``{"expr", "message"}`` entries for known wrong answers.
    feedback_detail : {"kind", "full"}
        How much slip messages may say (``"kind"`` never states a value; see
        `grader.answers.feedback`); set per problem by ``[feedback] detail`` in the scene file.
    alternatives : tuple of str
        Other references that are also right (``alternatives`` in the scene file: the mirror
        equilibrium, the other sign convention); the verdict's ``evidence["matched"]`` says which.

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
        return cls(**{k: data[k] for k in _TEXT_KEYS},
                   variables={k: dict(v) for k, v in variables.items()},
                   feedback=tuple({"expr": f["expr"], "message": f["message"]} for f in feedback),
                   feedback_detail=detail, alternatives=tuple(alternatives))

    def to_json(self) -> dict[str, Any]:
        """The JSON object stored in ``problem_versions.references`` (`from_json` reads it back)."""
        return {"name": self.name, "prompt": self.prompt, "kind": self.kind, "reference": self.reference,
                "variables": self.variables, "dimension": self.dimension, "latex": self.latex,
                "feedback": [dict(f) for f in self.feedback], "feedback_detail": self.feedback_detail,
                "alternatives": list(self.alternatives)}

    def request(self, text: str) -> dict[str, Any]:
        """The checker request (``grader check --jsonl`` line) for a student's ``text`` against this reference."""
        request = {"reference": self.reference, "answer": text, "variables": self.variables, "kind": self.kind,
                   "feedback": [dict(f) for f in self.feedback], "feedback_detail": self.feedback_detail}
        if self.alternatives:
            request["alternatives"] = list(self.alternatives)
        return request
