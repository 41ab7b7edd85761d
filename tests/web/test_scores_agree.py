"""One score everywhere: a student who answers right, then wrong (best 1, latest 0) gets the same
number on their problem list, on the instructor's results page, in the grades API and in its CSV."""

from __future__ import annotations

import csv
import io
import re

from grader.store.users import create_token
from grader.store.models import User
from tests.web.conftest_pages import (  # noqa: F401  (fixtures)
    accounts, as_instructor, as_other_student, as_student, grade_all, problems, submit_answers,
)


def test_the_student_list_the_results_page_the_api_and_the_csv_agree(app, accounts, problems, as_student,
                                                                     as_other_student, as_instructor):
    submit_answers(as_student, "mech", tension="m*g/3", acceleration="2*g/3")
    grade_all(app)
    submit_answers(as_student, "mech", tension="m*g")  # latest wrong: the best stays 1
    submit_answers(as_other_student, "mech", tension="m*g/3")  # half the answers
    grade_all(app)
    expected = {"Ada": 1.0, "Bob": 0.5}
    for client, name in ((as_student, "Ada"), (as_other_student, "Bob")):
        listed = client.get("/problems").get_data(as_text=True)
        row = listed[listed.index('href="/problems/mech"'):]
        assert float(re.search(r'class="problem-score">([0-9.]+)<', row).group(1)) == expected[name]
    results = as_instructor.get("/instructor/problems/mech").get_data(as_text=True)
    shown = dict(re.findall(r'<tr><td>(\w+)</td><td class="num score">([0-9.]+)</td>', results))
    assert {k: float(v) for k, v in shown.items()} == expected
    with app.extensions["lagrade.db"].write() as session:
        token = {"Authorization": f"Bearer {create_token(session, session.get(User, accounts['ine'].id))}"}
    api = app.test_client().get("/api/v1/problems/mech/grades", headers=token).get_json()["grades"]
    assert {r["name"]: r["problem_score"] for r in api} == expected
    text = app.test_client().get("/api/v1/problems/mech/grades?format=csv", headers=token).get_data(as_text=True)
    assert {r["name"]: float(r["problem_score"]) for r in csv.DictReader(io.StringIO(text))} == expected
