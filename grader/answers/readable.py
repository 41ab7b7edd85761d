"""Can the grader read this answer text at all? Asked before a submission is stored.

An answer the grader cannot read is a typo to fix, not an attempt: the student pages and the API show
the reader's message (with a caret) and store nothing. The text is read exactly as the checker will
read it (:func:`grader.answers.checker.check`: the answer's own variables, the same grammar for
expressions, equations and numbers with units) but nothing is compared with the reference, so this
is cheap enough for a request thread: the parser has its own length and depth limits.

>>> reference = {"name": "T", "kind": "expression", "variables": {"m": {"dimension": "mass"}}}
>>> read_error(reference, "2*m") is None
True
>>> error = read_error(reference, "2*(m")
>>> error["code"], error["column"] == error["position"] + 1
('unbalanced', True)
"""

from __future__ import annotations

from typing import Any, Mapping

from grader.expressions import ExpressionError, Namespace

__all__ = ["read_error"]


def read_error(reference: Mapping[str, Any], text: str) -> dict[str, Any] | None:
    """None when ``text`` reads as an answer to ``reference`` (a stored reference-answer dict), else
    ``{"message", "position", "column", "code", "hint"}``: ``position`` is the 0-based index of the
    problem in ``text`` and ``column`` the same place counted as the caret shows it (1-based), or
    both None when the problem is not at one place.
    """
    if reference.get("kind") == "numeric":
        from grader.answers.numeric import QuantityError, parse_quantity

        try:
            parse_quantity(text)
        except QuantityError as error:
            message = str(error)
            return {"message": message[:1].upper() + message[1:], "position": None, "column": None,
                    "code": "number", "hint": None}
        return None
    # The checker's own reading (one rule, one place): an equation answer may also be "... = 0".
    from grader.answers.checker import _read

    try:
        namespace = Namespace.from_spec(reference.get("variables") or {})
    except (ValueError, TypeError, KeyError):
        return None  # a broken reference is the grader's problem, not the student's: let the checker say so
    try:
        _read(text, namespace, reference.get("kind") or "expression", printed=False)
    except ExpressionError as error:
        found = error.to_json()
        found["column"] = None if error.position is None else error.position + 1
        return found
    except RecursionError:
        return {"message": "The answer is nested too deeply", "position": None, "column": None,
                "code": "too_deep", "hint": None}
    return None
