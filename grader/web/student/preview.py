"""How the grader reads one answer text, before it is submitted: the live preview.

The text is parsed by :mod:`grader.expressions` with the answer's own namespace, exactly as the
checker will read it, and nothing is compared with the reference (that happens only on submit, in a
sandbox). The parser has its own length and depth limits, so this is safe to run in the request.
"""

from __future__ import annotations

from typing import Any

from grader.expressions import DimensionError, ExpressionError, Namespace, dimension_of, parse_dimension
from grader.expressions import parse_equation, parse_expression

__all__ = ["MAX_PREVIEW_CHARS", "allowed_names", "preview"]

MAX_PREVIEW_CHARS = 4000


def _namespace(answer: dict[str, Any]) -> Namespace:
    return Namespace.from_spec(answer.get("variables") or {})


def allowed_names(answer: dict[str, Any]) -> list[dict[str, str]]:
    """The variables an answer may use, for the hint under its input: [{"name", "latex", "meaning"}]."""
    try:
        namespace = _namespace(answer)
    except ValueError:
        return []
    return [{"name": v.name, "latex": v.latex, "meaning": v.dimension.describe()} for v in namespace.variables]


def _numeric_preview(answer: dict[str, Any], text: str, result: dict[str, Any]) -> dict[str, Any]:
    """A number with its unit, read with the checker's own grammar (`grader.answers.numeric`)."""
    from grader.answers.numeric import QuantityError, parse_quantity

    try:
        quantity = parse_quantity(text)
    except QuantityError as error:
        message = str(error)
        result["error"] = {"message": message[:1].upper() + message[1:] + ".", "position": None, "code": "number",
                           "hint": None}
        return result
    result.update(ok=True, latex=quantity.latex,
                  dimension="a pure number" if quantity.dimension.is_dimensionless else quantity.dimension.describe())
    try:
        wanted = parse_dimension(answer.get("dimension") or "dimensionless")
    except (ValueError, KeyError):
        return result
    if not quantity.unit and not wanted.is_dimensionless:
        result["warning"] = f"Give a unit: the answer is {wanted.describe()}."
    elif quantity.dimension != wanted:
        result["warning"] = (f"The unit {quantity.unit} is {result['dimension']}, but the answer should be "
                             f"{'a pure number' if wanted.is_dimensionless else wanted.describe()}.")
    return result


def expected_dimension(answer: dict[str, Any]) -> str | None:
    """The answer's dimension in words ("a force (kg·m/s²)"); the prompt says as much already."""
    try:
        return parse_dimension(answer["dimension"]).describe() if answer.get("dimension") else None
    except (ValueError, KeyError):
        return None


def preview(answer: dict[str, Any], text: str) -> dict[str, Any]:
    """``{"ok", "text", "latex", "notes", "dimension", "warning", "error"}`` for one answer text.

    ``error`` is ``{"message", "position", "code", "hint"}`` when the text cannot be read.
    """
    result: dict[str, Any] = {"ok": False, "text": text, "latex": None, "notes": [], "dimension": None,
                              "warning": None, "error": None}
    if not text.strip():
        result["error"] = {"message": "Type an answer to see how it is read.", "position": None,
                           "code": "empty", "hint": None}
        return result
    if len(text) > MAX_PREVIEW_CHARS:
        result["error"] = {"message": f"The answer is {len(text)} characters long; the limit is "
                                      f"{MAX_PREVIEW_CHARS}.", "position": None, "code": "too_long", "hint": None}
        return result
    if answer.get("kind") == "numeric":
        return _numeric_preview(answer, text, result)
    try:
        namespace = _namespace(answer)
        if answer.get("kind") == "equation":
            parsed = parse_equation(text, namespace)
            expr = parsed.lhs - parsed.rhs
        else:
            parsed = parse_expression(text, namespace)
            expr = parsed.expr
    except ExpressionError as error:
        result["error"] = error.to_json()
        return result
    result.update(ok=True, latex=parsed.latex, notes=list(parsed.notes))
    try:
        dimension = dimension_of(expr, namespace.dimensions())
        result["dimension"] = dimension.describe()
        wanted = parse_dimension(answer["dimension"]) if answer.get("dimension") and answer.get("kind") != "equation" \
            else None
        if wanted is not None and dimension != wanted:
            result["warning"] = f"This is {dimension.describe()}, but the answer should be {wanted.describe()}."
    except DimensionError as error:
        result["warning"] = str(error)
    except (ValueError, KeyError):
        pass  # a reference without a usable dimension: say nothing rather than something wrong
    return result
