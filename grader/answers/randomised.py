"""A different problem for every student: each student's numbers, drawn from a stored seed.

A scene's ``[parameters]`` may give a parameter a fixed ``value``, a ``random = {min, max, step}``
range or a list of ``choices``. The engine keeps every parameter symbolic; the stored problem carries
these specs (``derivation["parameters"]``, and each numeric reference answer's ``parameters``), and
the service draws a student's values with :func:`draw_parameters` from a seed made by
:func:`seed_for` and kept with the values, so the same student always sees the same numbers and a
regrade uses them again.

The draw is a pure function of (spec, seed): sha256 of the seed and the parameter's name, no global
random state, so it is the same on every machine and Python version, and adding a parameter to a
scene does not change the others' values.
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping
from decimal import Decimal
from typing import Any

__all__ = ["PREVIEW_SEED", "RandomSpecError", "draw_parameters", "fixed_values", "grid_size", "is_randomised",
           "random_names", "seed_for"]

# The numbers shown and checked where no student's draw exists: an instructor's preview, a
# ``POST /check`` without values, and question tests that state no values of their own.
PREVIEW_SEED = 0
_MAX_GRID = 10 ** 9  # more values than any problem needs: a step that small is a typo


class RandomSpecError(ValueError):
    """A parameter spec that cannot be drawn from (says which parameter and why)."""


def seed_for(secret: str | bytes, *ids: Any) -> int:
    """A seed fixed by ``secret`` and the ids (assignment, student, problem), in [0, 2**31).

    With a secret (the app's ``SECRET_KEY``) nobody can work out a classmate's numbers from the
    ids; the seed is stored with the draw anyway, so changing the secret later changes nothing drawn.

    Examples
    --------
    >>> seed_for("k", 1, 2, 3) == seed_for("k", 1, 2, 3), seed_for("k", 1, 2, 3) == seed_for("k", 1, 4, 3)
    (True, False)
    >>> 0 <= seed_for(b"", 7) < 2 ** 31
    True
    """
    key = secret if isinstance(secret, bytes) else str(secret).encode()
    digest = hashlib.sha256(key + b"\0" + ":".join(map(str, ids)).encode()).digest()
    return int.from_bytes(digest[:4], "big") & 0x7FFFFFFF  # fits a 32-bit integer column


def _choice(seed: int, name: str, n: int) -> int:
    """An index in range(n) for ``name`` under ``seed`` (sha256: uniform enough, stable everywhere)."""
    digest = hashlib.sha256(f"{int(seed)}:{name}".encode()).digest()
    return int.from_bytes(digest[:8], "big") % n


def _decimal(value: Any, where: str) -> Decimal:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise RandomSpecError(f"{where} must be a number")
    return Decimal(repr(value))  # repr: the shortest text of the float, as the instructor wrote it


def grid_size(random: Mapping[str, Any], name: str = "parameter") -> int:
    """How many values ``random = {min, max, step}`` allows (``min + k*step <= max``).

    Examples
    --------
    >>> grid_size({"min": 0.5, "max": 2.0, "step": 0.1})
    16
    """
    if not isinstance(random, Mapping):
        raise RandomSpecError(f"{name}.random must be a table {{min, max, step}}")
    lo = _decimal(random.get("min"), f"{name}.random.min")
    hi = _decimal(random.get("max"), f"{name}.random.max")
    step = _decimal(random.get("step"), f"{name}.random.step")
    if step <= 0:
        raise RandomSpecError(f"{name}.random.step must be positive")
    if hi < lo:
        raise RandomSpecError(f"{name}.random: max is less than min")
    count = int((hi - lo) / step) + 1
    if count > _MAX_GRID:
        raise RandomSpecError(f"{name}.random: the step allows more than {_MAX_GRID} values")
    return count


def _grid_value(random: Mapping[str, Any], index: int) -> float:
    # In decimal, so 0.5 + 3*0.1 is 0.8 and not 0.8000000000000002.
    return float(Decimal(repr(random["min"])) + index * Decimal(repr(random["step"])))


def is_randomised(parameters: Mapping[str, Mapping[str, Any]]) -> bool:
    """Whether some parameter is drawn per student (has ``random`` or ``choices``)."""
    return bool(random_names(parameters))


def random_names(parameters: Mapping[str, Mapping[str, Any]]) -> list[str]:
    """The names of the parameters drawn per student, sorted."""
    return sorted(n for n, s in parameters.items() if isinstance(s, Mapping) and ("random" in s or "choices" in s))


def fixed_values(parameters: Mapping[str, Mapping[str, Any]]) -> dict[str, float]:
    """The parameters with a fixed ``value``."""
    return {n: float(s["value"]) for n, s in parameters.items()
            if isinstance(s, Mapping) and s.get("value") is not None}


def draw_parameters(parameters: Mapping[str, Mapping[str, Any]], seed: int) -> dict[str, float]:
    """The values of every parameter that has a number: fixed ones as given, the others drawn.

    Parameters
    ----------
    parameters : mapping
        ``{name: {"value": x} | {"random": {"min", "max", "step"}} | {"choices": [x, ...]}}`` (other
        keys, such as ``dimension``, are ignored; a parameter with none of the three is left out:
        it stays symbolic).
    seed : int
        From :func:`seed_for` (stored with the values), or :data:`PREVIEW_SEED`.

    Returns
    -------
    dict
        ``{name: float}``; drawn values lie on the grid ``min + k*step`` within [min, max].

    Raises
    ------
    RandomSpecError
        A spec that cannot be drawn from (the scene loader refuses such scenes first).

    Examples
    --------
    >>> spec = {"m": {"random": {"min": 0.5, "max": 2.0, "step": 0.1}}, "g": {"value": 9.81},
    ...         "k": {"choices": [10, 20, 50]}, "l": {"dimension": "length"}}
    >>> values = draw_parameters(spec, 12345)
    >>> values == draw_parameters(spec, 12345), sorted(values), values["g"]
    (True, ['g', 'k', 'm'], 9.81)
    >>> 0.5 <= values["m"] <= 2.0 and round(values["m"], 1) == values["m"], values["k"] in (10, 20, 50)
    (True, True)
    """
    for attempt in range(_RELATED_DRAWS):
        # A parameter declared below another (a < R): the student's numbers keep the order; a draw
        # that breaks it is made again from a seed of its own (still reproducible from the stored seed).
        values = _draw(parameters, seed if attempt == 0 else seed_for(seed, attempt))
        if all(values[name] < values[spec["below"]] for name, spec in parameters.items()
               if isinstance(spec, Mapping) and spec.get("below") in values and name in values):
            return values
    raise RandomSpecError("no draw keeps every 'below' relation of the parameters: check their ranges")


_RELATED_DRAWS = 64


def _draw(parameters: Mapping[str, Mapping[str, Any]], seed: int) -> dict[str, float]:
    values: dict[str, float] = {}
    for name in sorted(parameters):
        spec = parameters[name]
        if not isinstance(spec, Mapping):
            raise RandomSpecError(f"parameter {name!r} must be a table")
        if spec.get("random") is not None:
            values[name] = _grid_value(spec["random"], _choice(seed, name, grid_size(spec["random"], name)))
        elif spec.get("choices") is not None:
            choices = spec["choices"]
            if not isinstance(choices, (list, tuple)) or not choices:
                raise RandomSpecError(f"{name}.choices must be a non-empty list of numbers")
            chosen = choices[_choice(seed, name, len(choices))]
            values[name] = float(_decimal(chosen, f"{name}.choices"))
        elif spec.get("value") is not None:
            values[name] = float(_decimal(spec["value"], f"{name}.value"))
    return values
