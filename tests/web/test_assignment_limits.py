"""An assignment's attempt limit out of range is refused on every surface that builds one, and
nothing is stored (the page took any digits and answered 500 for 10**20)."""

from __future__ import annotations

import pytest
from sqlalchemy import func, select

from grader.store.models import Assignment
from tests.web.test_access_matrix import client_for, world, cell_app  # noqa: F401  (fixtures)

TIMES = {"opens_at": "2026-12-01T09:00", "due_at": "2026-12-08T17:00"}
SURFACES = {
    "page": ("/instructor/courses/MECH/assignments",
             lambda n: {"data": {"id": "hw2", "title": "Homework 2", "problems": "mech", "time_zone": "Europe/Paris",
                                 "max_attempts": str(n), **TIMES}}),
    "api": ("/api/v1/courses/MECH/assignments",
            lambda n: {"json": {"id": "hw2", "title": "Homework 2", "problems": ["mech"], "max_attempts": n,
                                "opens_at": "2026-12-01T09:00:00Z", "due_at": "2026-12-08T17:00:00Z"}}),
}


def _assignments(app) -> int:
    with app.extensions["lagrade.db"].read() as session:
        return session.scalar(select(func.count()).select_from(Assignment))


@pytest.mark.parametrize("surface", SURFACES)
@pytest.mark.parametrize("attempts", [1001, 3 * 10**9, 10**20])
def test_an_attempt_limit_out_of_range_is_refused_and_nothing_is_stored(world, cell_app, surface, attempts):
    client, headers = client_for(cell_app, world, "ins")
    url, body = SURFACES[surface]
    before = _assignments(cell_app)
    response = client.post(url, headers=headers, **body(attempts))
    assert response.status_code in (302, 422)
    if surface == "page":  # back to the form, saying why
        assert response.headers["Location"].endswith("/instructor/courses/MECH#new-assignment")
        assert "at most 1000" in client.get("/instructor/courses/MECH").get_data(as_text=True)
    assert _assignments(cell_app) == before
