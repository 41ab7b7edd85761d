"""URL converters: an ``<int:...>`` id in any route is within the database's integer range.

Primary keys are INTEGER columns, 32-bit on PostgreSQL. A larger id in a URL names nothing, so it
does not match the route (404) instead of reaching the database, where PostgreSQL answers "integer
out of range" and SQLite's driver raises OverflowError (both were 500s).

Examples
--------
>>> from werkzeug.routing import Map, Rule
>>> urls = Map([Rule("/submissions/<int:n>", endpoint="s")], converters={"int": IdConverter}).bind("x")
>>> urls.match("/submissions/2147483647")
('s', {'n': 2147483647})
>>> urls.match("/submissions/2147483648")
Traceback (most recent call last):
...
werkzeug.exceptions.NotFound: 404 Not Found: ...
"""

from __future__ import annotations

from werkzeug.routing import IntegerConverter, Map

__all__ = ["IdConverter", "MAX_ID"]

MAX_ID = 2**31 - 1


class IdConverter(IntegerConverter):
    """Werkzeug's ``int`` converter with ``max`` defaulting to :data:`MAX_ID`."""

    def __init__(self, map: Map, fixed_digits: int = 0, min: int | None = None, max: int | None = MAX_ID,
                 signed: bool = False):
        super().__init__(map, fixed_digits=fixed_digits, min=min, max=max, signed=signed)
