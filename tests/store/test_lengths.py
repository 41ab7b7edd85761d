"""Text that the database would refuse or truncate (PostgreSQL: a DataError; SQLite: stored whole)
is refused before the INSERT or UPDATE with the column and its limit named, on both databases."""

from __future__ import annotations

import pytest

from grader.store.lengths import StoredValueError
from grader.store.models import User
from grader.store.users import create_user


@pytest.mark.parametrize("fields, column, problem", [
    ({"name": "n" * 201}, "users.name", "201 characters; the limit is 200"),
    ({"name": "ok", "external_id": "e" * 201}, "users.external_id", "201 characters; the limit is 200"),
    ({"name": "ok", "email": "a" * 321}, "users.email", "321 characters; the limit is 320"),
    ({"name": "Ad\ud800a"}, "users.name", "lone surrogate"),
    ({"name": "Ad\x00a"}, "users.name", "NUL character"),  # PostgreSQL's text cannot hold it
], ids=["name", "external-id", "email", "surrogate", "nul"])
def test_text_that_does_not_fit_its_column_is_refused_with_the_column_named(database, fields, column, problem):
    with pytest.raises(StoredValueError) as refused:
        with database.write() as session:
            create_user(session, role="student", **fields)
    assert refused.value.column == column and problem in str(refused.value)
    with database.read() as session:
        assert session.query(User).count() == 0  # nothing half-written


def test_text_at_the_limit_is_stored_whole(database):
    with database.write() as session:
        user_id = create_user(session, role="student", name="n" * 200, external_id="e" * 200).id
    with database.read() as session:
        user = session.get(User, user_id)
        assert (len(user.name), len(user.external_id)) == (200, 200)


def test_an_update_is_checked_too(database):
    with database.write() as session:
        user_id = create_user(session, role="student", name="Ada").id
    with pytest.raises(StoredValueError, match="users.name"):
        with database.write() as session:
            session.get(User, user_id).name = "n" * 201
    with database.read() as session:
        assert session.get(User, user_id).name == "Ada"
