"""Errors raised while reading expressions and checking dimensions.

Both are ``ValueError`` subclasses so callers that only care "was the text bad?"
can catch one thing; the web layer reads ``code`` and ``position`` to point at
the problem in what the student typed.
"""

from __future__ import annotations

__all__ = ["ExpressionError", "DimensionError", "ERROR_CODES"]

#: Every ``ExpressionError.code`` the parser can produce.
ERROR_CODES = frozenset({
    "empty", "syntax", "unbalanced", "unknown_name", "unsupported_function",
    "too_long", "too_deep", "too_large", "bad_character", "ambiguous",
})


class ExpressionError(ValueError):
    """Text that cannot be read as an expression.

    Parameters
    ----------
    message : str
        What went wrong, in words a student understands.
    position : int or None
        0-based index (in code points) into the text where the problem is.
    code : str
        One of :data:`ERROR_CODES`, for programs.
    hint : str or None
        What to do about it ("did you mean 'theta'?").

    Examples
    --------
    >>> err = ExpressionError("unknown name 'thta'", 4, "unknown_name", "did you mean 'theta'?")
    >>> print(err.show("cos(thta)"))
    cos(thta)
        ^
    unknown name 'thta' at character 5; did you mean 'theta'?
    """

    def __init__(self, message: str, position: int | None = None,
                 code: str = "syntax", hint: str | None = None) -> None:
        if code not in ERROR_CODES:
            raise ValueError(f"unknown error code {code!r}")
        self.message = message
        self.position = position
        self.code = code
        self.hint = hint
        super().__init__(self._full())

    def _full(self) -> str:
        text = self.message
        if self.position is not None:
            # Counted as the caret shows it and as every page says it: 1-based characters.
            text += f" at character {self.position + 1}"
        if self.hint:
            text += f"; {self.hint}"
        return text

    def show(self, text: str) -> str:
        """The text with a caret under the error position, then the message."""
        if self.position is None or len(text) > 200:
            return self._full()
        return f"{text}\n{' ' * self.position}^\n{self._full()}"

    def to_json(self) -> dict:
        """``{"message", "position", "code", "hint"}`` for APIs."""
        return {"message": self.message, "position": self.position,
                "code": self.code, "hint": self.hint}


class DimensionError(ValueError):
    """Quantities of different dimensions combined, or an unknown dimension.

    Examples
    --------
    >>> str(DimensionError("adds a force (kg·m/s²) to a length (m)"))
    'adds a force (kg·m/s²) to a length (m)'
    """

    def __init__(self, message: str, expr: object = None) -> None:
        self.message = message
        self.expr = expr
        super().__init__(message)
