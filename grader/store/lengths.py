"""Text the database stores fits its column, checked before every INSERT and UPDATE, on every database.

SQLite stores a 300-character name in a ``String(200)`` column; PostgreSQL refuses it with a
``DataError`` (a 500 in the service), and text holding a lone surrogate cannot be encoded for either
(nor a NUL character for PostgreSQL).
The limits are read from the models' own column declarations, so this rule is in one place and
follows the schema; inputs are capped earlier too (the API's schemas, the scene schema), and this is
the last line for any path that forgets.

Examples
--------
>>> from grader.store.models import User
>>> check_row(User.__mapper__, None, User(role="student", name="n" * 201))
Traceback (most recent call last):
...
grader.store.lengths.StoredValueError: users.name: 201 characters; the limit is 200
"""

from __future__ import annotations

import re
from typing import Any

from sqlalchemy import String, event
from sqlalchemy.orm import Mapper

from grader.store.models import Base

__all__ = ["StoredValueError", "check_row"]

_SURROGATE = re.compile("[\ud800-\udfff]")


class StoredValueError(ValueError):
    """A value that its column cannot hold (too long, or not encodable text)."""

    def __init__(self, column: str, problem: str):
        self.column, self.problem = column, problem
        super().__init__(f"{column}: {problem}")


def check_row(mapper: Mapper, connection: Any, target: Any) -> None:
    """Raise :class:`StoredValueError` if a string attribute of ``target`` does not fit its column."""
    for attribute in mapper.column_attrs:
        column = attribute.columns[0]
        value = target.__dict__.get(attribute.key)
        if not isinstance(value, str) or not isinstance(column.type, String):
            continue
        name = f"{column.table.name}.{column.name}"
        if column.type.length is not None and len(value) > column.type.length:
            raise StoredValueError(name, f"{len(value)} characters; the limit is {column.type.length}")
        if _SURROGATE.search(value):
            raise StoredValueError(name, "holds a lone surrogate (U+D800-U+DFFF), which is not text")
        if "\x00" in value:  # PostgreSQL's text cannot hold NUL; SQLite would store it
            raise StoredValueError(name, "holds a NUL character, which is not text")


event.listen(Base, "before_insert", check_row, propagate=True)
event.listen(Base, "before_update", check_row, propagate=True)
