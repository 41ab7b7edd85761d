"""Registering a scene runs its question tests: the review page shows what the grader said, and a
failing test stops the registration with the grader's words (nothing to publish)."""

from html import unescape
from pathlib import Path

from sqlalchemy import select

from grader.store.models import Submission

from tests.web.derive_in_process import derive_all
from tests.web.conftest_pages import accounts, as_instructor, as_student  # noqa: F401  (fixtures)
from tests.web.conftest_pages import csrf, form_token, grade_all, submit_answers

ROOT = Path(__file__).resolve().parents[2]
RANDOMISED = (ROOT / "tests" / "mechanics" / "randomised" / "yoyo_randomised.toml").read_text()


def register(app, as_instructor, accounts, source):
    form = as_instructor.get("/instructor/problems/new").get_data(as_text=True)
    response = as_instructor.post("/instructor/problems/new", data={
        "source": source, "course": str(accounts["course"]), "csrf_token": form_token(form)})
    assert response.status_code == 302
    derive_all(app)
    return as_instructor.get(response.headers["Location"]).get_data(as_text=True)


def test_the_review_shows_the_question_tests_and_the_drawn_parameters(app, as_instructor, accounts):
    progress = register(app, as_instructor, accounts, RANDOMISED)
    assert "as draft version 1" in progress
    review = as_instructor.get("/instructor/problems/yoyo-randomised/review?version=1").get_data(as_text=True)
    assert "Question tests" in review and "<code>98.1 cN</code>" in review
    assert "✗" not in review and review.count("✓") == 11
    assert "Drawn for each student" in review and "0.1 to 0.5 in steps of 0.05" in review
    assert "one of 0.02, 0.03, 0.04" in review
    assert "in N, tolerance relative 0.01, weight 2.0" in review and "(score 0.5)" in review


def test_a_failing_question_test_stops_the_registration_with_the_graders_words(app, as_instructor, accounts):
    failing = RANDOMISED.replace('answer = "m g/3"', 'answer = "m g/2"', 1)
    progress = register(app, as_instructor, accounts, failing)
    assert "question tests failed, so the problem cannot be published" in progress
    assert "answers (tension): test 'm g/2' expects equivalent, the grader said not_equivalent" in unescape(progress)
    assert as_instructor.get("/instructor/problems/yoyo-randomised/review").status_code == 404


def test_a_student_outside_an_assignment_sees_the_numbers_the_grader_uses(app, as_instructor, as_student, accounts):
    from grader.answers.randomised import PREVIEW_SEED, draw_parameters
    from grader.mechanics.references import parameter_specs
    from grader.mechanics.scene import parse_scene

    register(app, as_instructor, accounts, RANDOMISED)
    as_instructor.post("/instructor/problems/yoyo-randomised/versions/1/publish", data={"csrf_token": csrf(as_instructor)})
    numbers = draw_parameters(parameter_specs(parse_scene(RANDOMISED, "y.toml")), PREVIEW_SEED)
    page = as_student.get("/problems/yoyo-randomised").get_data(as_text=True)
    assert "The numbers for this problem:" in page and f"m = {numbers['m']:g} kg" in page and "g = 9.81 m/s²" in page
    assert "A number with its unit, for example in N" in page
    tension = numbers["m"] * numbers["g"] / 3
    response = submit_answers(as_student, "yoyo-randomised", tension_value=f"{tension:.4g} N", tension="m*g")
    assert response.status_code in (200, 302)
    assert grade_all(app) == 2
    with app.extensions["lagrade.db"].read() as session:
        graded = {s.answer_name: (s.verdict.verdict, s.verdict.score) for s in session.scalars(select(Submission))}
    assert graded == {"tension_value": ("equivalent", 1.0), "tension": ("not_equivalent", 0.25)}
