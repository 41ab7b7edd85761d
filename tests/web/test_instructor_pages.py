"""Instructor pages: register and review a scene, publish it, follow results, export, regrade."""

import csv
import io
from pathlib import Path

import pytest
from sqlalchemy import select

from grader.store.models import Submission
from tests.web.derive_in_process import derive_all
from tests.web.conftest_pages import (  # noqa: F401  (fixtures)
    InProcessChecker, accounts, as_instructor, as_other_student, as_student, checkers, csrf, form_token, grade_all,
    problems, sign_in, submit_answers,
)

ROOT = Path(__file__).resolve().parents[2]
YOYO_SCENE = (ROOT / "problems" / "yoyo.toml").read_text()
PENDULUM = '''
id = "swing"
title = "Pendulum swing"
statement = "A bob of mass $m$ hangs from a string of length $l$."
[parameters]
m = { dimension = "mass", domain = "positive" }
g = { dimension = "acceleration", domain = "positive" }
l = { dimension = "length", domain = "positive" }
[coordinates]
theta = { dimension = "angle" }
[energy]
kinetic = "m*l^2/2*thetadot^2"
potential = "-m*g*l*cos(theta)"
[[answers]]
name = "angular_acceleration"
prompt = "Angular acceleration $\\\\ddot\\\\theta$"
expr = "thetaddot"
in_terms_of = ["g", "l", "theta"]
dimension = "angular_acceleration"
'''
PAGES = ["/instructor/", "/instructor/problems/new", "/instructor/problems/yoyo", "/instructor/derivations/1",
         "/instructor/problems/yoyo/review", "/instructor/problems/yoyo/submissions.csv"]
FORMS = ["/instructor/problems/new", "/instructor/problems/yoyo/versions/1/publish", "/instructor/problems/yoyo/regrade"]


@pytest.fixture
def as_other_instructor(app, accounts):
    client = app.test_client()
    sign_in(client, accounts["oth"])
    return client


@pytest.mark.parametrize("path", PAGES)
def test_instructor_pages_are_not_for_students(as_student, client, problems, path):
    assert as_student.get(path).status_code == 403
    assert client.get(path).status_code == 302


@pytest.mark.parametrize("path", FORMS)
def test_instructor_forms_are_not_for_students_and_need_csrf(as_student, as_instructor, problems, path):
    assert as_student.post(path, data={"csrf_token": csrf(as_student)}).status_code == 403
    assert as_instructor.post(path, data={"source": YOYO_SCENE}).status_code == 400


def test_the_dashboard_lists_the_problems_i_manage(as_instructor, as_other_instructor, problems):
    mine = as_instructor.get("/instructor/").get_data(as_text=True)
    theirs = as_other_instructor.get("/instructor/").get_data(as_text=True)
    assert "Mech problem" in mine and "Other problem" not in mine and "Draft problem" in mine and "Yo-yo" in mine
    assert "Other problem" in theirs and "Mech problem" not in theirs
    assert "v1 draft" in mine and "v1 published" in mine


def test_another_courses_problem_is_not_found(as_other_instructor, problems):
    for path in ("/instructor/problems/mech", "/instructor/problems/mech/review",
                 "/instructor/problems/mech/submissions.csv"):
        assert as_other_instructor.get(path).status_code == 404
    response = as_other_instructor.post("/instructor/problems/mech/versions/1/publish",
                                        data={"csrf_token": csrf(as_other_instructor)})
    assert response.status_code == 404


def test_a_pasted_scene_is_derived_as_a_draft_reviewed_then_published(app, as_instructor, as_student, accounts):
    form = as_instructor.get("/instructor/problems/new").get_data(as_text=True)
    response = as_instructor.post("/instructor/problems/new", data={
        "source": PENDULUM, "course": str(accounts["course"]), "csrf_token": form_token(form)})
    assert response.status_code == 302 and response.headers["Location"] == "/instructor/derivations/1"
    derive_all(app)
    progress = as_instructor.get(response.headers["Location"]).get_data(as_text=True)
    assert "Derived “Pendulum swing” as draft version 1" in progress
    assert 'href="/instructor/problems/swing/review?version=1"' in progress
    review = as_instructor.get("/instructor/problems/swing/review?version=1").get_data(as_text=True)
    assert "version 1 · draft" in review and "Publish version 1" in review
    assert "A bob of mass <math" in review  # the statement as students will see it
    assert "Angular acceleration <math" in review  # the prompt's $\ddot\theta$ renders too
    assert "-g*sin(theta)/l" in review and "<mfrac>" in review  # the reference, as text and as math
    assert "Derivation" in review
    assert as_student.get("/problems/swing").status_code == 404  # a draft is invisible

    published = as_instructor.post("/instructor/problems/swing/versions/1/publish",
                                   data={"csrf_token": csrf(as_instructor)})
    assert published.status_code == 302
    assert "version 1 · published" in as_instructor.get("/instructor/problems/swing/review").get_data(as_text=True)
    page = as_student.get("/problems/swing").get_data(as_text=True)
    assert "Pendulum swing" in page and "-g*sin(theta)/l" not in page


def test_an_uploaded_scene_file_works_too(app, as_instructor):
    response = as_instructor.post("/instructor/problems/new", content_type="multipart/form-data", data={
        "scene": (io.BytesIO(YOYO_SCENE.encode()), "yoyo.toml"), "course": "", "csrf_token": csrf(as_instructor)})
    assert response.status_code == 302
    assert "Deriving <code>yoyo.toml</code>" in as_instructor.get(response.headers["Location"]).get_data(as_text=True)
    derive_all(app)
    assert "Yo-yo: a solid cylinder" in as_instructor.get("/instructor/problems/yoyo/review").get_data(as_text=True)


def test_a_broken_scene_is_explained_and_nothing_is_stored(app, as_instructor):
    broken = PENDULUM.replace('potential = "-m*g*l*cos(theta)"', 'potential = "-m*g*l*cos(thta)"')
    response = as_instructor.post("/instructor/problems/new", data={"source": broken, "csrf_token": csrf(as_instructor)})
    assert response.status_code == 302
    derive_all(app)
    response = as_instructor.get(response.headers["Location"])
    body = response.get_data(as_text=True)
    assert response.status_code == 200 and "thta" in body and "Traceback" not in body
    assert "cos(thta)" in body  # the pasted source is kept for fixing
    assert as_instructor.get("/instructor/problems/swing/review").status_code == 404


@pytest.mark.parametrize("change, where", [
    (lambda s: s.replace('title = "Pendulum', 'title = "\\u0000Pendulum'), "title"),
    (lambda s: s.replace('statement = "A bob', 'statement = "\\u0000A bob'), "statement"),
])
def test_a_scene_holding_a_nul_character_is_refused_in_the_form_and_nothing_is_queued(app, as_instructor,
                                                                                       change, where):
    response = as_instructor.post("/instructor/problems/new", data={"source": change(PENDULUM),
                                                                    "csrf_token": csrf(as_instructor)})
    body = response.get_data(as_text=True)
    assert response.status_code == 422 and f"pasted.toml: {where} holds a NUL character" in body
    assert "\\u0000" in body  # the pasted source is kept for fixing
    assert derive_all(app) == 0


def test_a_scene_id_of_another_course_cannot_be_taken_over(as_other_instructor, problems):
    scene = YOYO_SCENE.replace('id = "yoyo"', 'id = "mech"')
    response = as_other_instructor.post("/instructor/problems/new",
                                        data={"source": scene, "csrf_token": csrf(as_other_instructor)})
    assert response.status_code == 422 and "taken by another course" in response.get_data(as_text=True)


def test_results_group_equivalent_wrong_answers_with_counts(app, as_instructor, as_student, as_other_student,
                                                            problems, checkers):
    submit_answers(as_student, "yoyo", tension="m g", acceleration="2g/3")
    submit_answers(as_other_student, "yoyo", tension="g*m*(sin(1)^2 + cos(1)^2)", acceleration="g")
    submit_answers(as_other_student, "yoyo", tension="mg/2")
    grade_all(app)
    html = as_instructor.get("/instructor/problems/yoyo").get_data(as_text=True)
    tension = html[html.index('id="wrong-tension"'):]
    tension = tension[:tension.index("</table>")]
    rows = tension.split('class="wrong-group"')[1:]
    assert len(rows) == 2
    assert "<code>m g</code> × 1" in rows[0] and "sin(1)^2" in rows[0]  # one mistake, two spellings
    assert '<td class="num">2</td>' in rows[0]
    assert "g*m/2" in rows[1]
    assert "2 of 2" in html and "Mean score" in html


def test_the_grouping_is_cached_until_a_new_verdict(app, as_instructor, as_student, as_other_student, problems):
    runs = []

    class Counting(InProcessChecker):
        def run(self, request, budget_s=None):
            runs.append(request["answer"])
            return super().run(request, budget_s)

    app.extensions["lagrade.checkers"].factory = Counting
    submit_answers(as_student, "yoyo", tension="m*g")
    submit_answers(as_other_student, "yoyo", tension="g*m*(sin(1)^2 + cos(1)^2)")
    grade_all(app)
    as_instructor.get("/instructor/problems/yoyo")
    first = len(runs)
    assert first == 1
    as_instructor.get("/instructor/problems/yoyo")
    assert len(runs) == first
    submit_answers(as_student, "yoyo", tension="m*g*(sin(2)^2 + cos(2)^2)")
    grade_all(app)
    as_instructor.get("/instructor/problems/yoyo")
    assert len(runs) == first + 1  # only the new form is checked; the old pair comes from the cache


def test_the_csv_has_every_submission_and_no_live_formulas(app, as_instructor, as_student, problems):
    # Readable answers that start like formulas ("=1+1" is refused before it is stored).
    submit_answers(as_student, "yoyo", tension="-m*g", acceleration="+g")
    grade_all(app)
    response = as_instructor.get("/instructor/problems/yoyo/submissions.csv")
    assert response.mimetype == "text/csv" and "attachment" in response.headers["Content-Disposition"]
    rows = list(csv.DictReader(io.StringIO(response.get_data(as_text=True))))
    assert {r["answer"]: r["text"] for r in rows} == {"tension": "'-m*g", "acceleration": "'+g"}
    assert {r["answer"]: r["verdict"] for r in rows} == {"tension": "not_equivalent", "acceleration": "not_equivalent"}
    assert rows[0]["email"] == "ada@example.org"


def test_regrade_queues_every_submission_again(app, as_instructor, as_student, problems):
    submit_answers(as_student, "yoyo", tension="m*g", acceleration="g")
    grade_all(app)
    response = as_instructor.post("/instructor/problems/yoyo/regrade", data={"csrf_token": csrf(as_instructor)})
    assert response.status_code == 302
    assert "Queued 2 submissions" in as_instructor.get(response.headers["Location"]).get_data(as_text=True)
    with app.extensions["lagrade.db"].read() as session:
        assert {(s.status, s.grading_round) for s in session.scalars(select(Submission))} == {("queued", 2)}


def test_the_engines_steps_are_shown_as_math_when_stored(app, as_instructor, yoyo):
    import dataclasses

    from grader.store.problems import save_problem

    steps = [{"title": "Lagrangian", "text": ["L = T - V"], "latex": [r"L = \\frac{m}{2} \\dot{s}^{2} + g m s"]}]
    derived = dataclasses.replace(yoyo, slug="stepped", derivation=dict(yoyo.derivation, steps=steps))
    with app.extensions["lagrade.db"].write() as session:
        save_problem(session, derived, published=False)
    html = as_instructor.get("/instructor/problems/stepped/review").get_data(as_text=True)
    assert "<strong>Lagrangian</strong>" in html and '<math display="block">' in html
