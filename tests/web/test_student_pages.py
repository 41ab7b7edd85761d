"""Student pages: what a student sees, what they never see, and that every form needs its CSRF token."""

import re

import pytest
from sqlalchemy import func, select

from grader.store.models import Submission, Verdict
from tests.web.conftest_pages import (  # noqa: F401  (fixtures)
    accounts, as_instructor, as_other_student, as_student, checkers, csrf, form_token, grade_all, problems,
    submit_answers,
)

# Every form of the yo-yo's references as stored: none may reach a student's page.
REFERENCE_FORMS = ["g*m/3", "2*g/3", r"\frac{g m}{3}", r"\frac{2 g}{3}", "engine_version", "hand-written test data"]


def assert_no_reference(html: str) -> None:
    for form in REFERENCE_FORMS:
        assert form not in html, f"a student page shows the reference form {form!r}"


def submissions(app) -> int:
    with app.extensions["lagrade.db"].read() as session:
        return session.scalar(select(func.count(Submission.id)))


def test_the_problem_list_shows_published_problems_of_my_courses_only(as_student, problems):
    html = as_student.get("/problems").get_data(as_text=True)
    assert "Yo-yo" in html and "Mech problem" in html
    assert "Other problem" not in html and "Draft problem" not in html
    assert_no_reference(html)


def test_the_problem_page_has_the_statement_in_mathml_and_one_input_per_answer(as_student, problems):
    page = as_student.get("/problems/yoyo")
    html = page.get_data(as_text=True)
    assert page.status_code == 200
    assert "cylinder of mass <math" in html
    assert 'name="answer-acceleration"' in html and 'name="answer-tension"' in html
    assert 'formaction="/problems/yoyo/preview"' in html and form_token(html)
    assert_no_reference(html)


@pytest.mark.parametrize("slug", ["draft", "other", "nope"])
def test_problems_i_may_not_see_are_not_found(as_student, problems, slug):
    assert as_student.get(f"/problems/{slug}").status_code == 404
    preview = as_student.post("/preview", json={"problem": slug, "answer": "tension", "text": "m"},
                              headers={"X-CSRF-Token": csrf(as_student)})
    assert preview.status_code == 404
    assert submit_answers(as_student, slug, tension="m*g").status_code == 404


@pytest.mark.parametrize("path", ["/problems", "/problems/yoyo", "/submissions/1", "/submissions/1/status"])
def test_student_pages_are_for_students(as_instructor, client, problems, path):
    assert as_instructor.get(path).status_code == 403
    assert client.get(path).status_code == 302  # signed out: to the sign-in page


def test_the_live_preview_reads_the_text_and_returns_its_html(as_student, problems):
    reply = as_student.post("/preview", json={"problem": "yoyo", "answer": "tension", "text": "mg sin(0)+m g"},
                            headers={"X-CSRF-Token": csrf(as_student)})
    body = reply.get_json()
    assert reply.status_code == 200 and body["ok"]
    assert "read 'mg' as m·g" in body["notes"] and body["dimension"] == "a force (kg·m/s²)"
    assert "<math" in body["html"] and "Read as" in body["html"]
    assert_no_reference(reply.get_data(as_text=True))


def test_the_live_preview_points_at_an_error(as_student, problems):
    body = as_student.post("/preview", json={"problem": "yoyo", "answer": "tension", "text": "m*g*/3"},
                           headers={"X-CSRF-Token": csrf(as_student)}).get_json()
    assert not body["ok"] and body["error"]["position"] == 4
    assert 'class="caret"' in body["html"] and "at character 5" in body["html"]


def test_the_live_preview_needs_its_csrf_header_and_a_well_formed_body(as_student, problems):
    assert as_student.post("/preview", json={"problem": "yoyo", "answer": "tension", "text": "m"}).status_code == 400
    headers = {"X-CSRF-Token": csrf(as_student)}
    assert as_student.post("/preview", json={"problem": "yoyo"}, headers=headers).status_code == 400
    assert as_student.post("/preview", json={"problem": "yoyo", "answer": "nope", "text": "m"},
                           headers=headers).status_code == 404


def test_without_javascript_the_preview_button_renders_the_same_previews(app, as_student, problems):
    page = as_student.post("/problems/yoyo/preview", data={"answer-tension": "mg/2", "answer-acceleration": "g*/2",
                                                           "csrf_token": csrf(as_student)})
    html = page.get_data(as_text=True)
    assert page.status_code == 200
    assert 'value="mg/2"' in html and "Read as" in html and "<mfrac><mrow><mi>g</mi><mi>m</mi></mrow><mn>2</mn>" in html
    assert "Cannot read this yet" in html and 'class="caret"' in html
    assert submissions(app) == 0  # a preview submits nothing
    assert_no_reference(html)


def test_forms_without_the_csrf_token_are_refused(app, as_student, problems):
    assert as_student.post("/problems/yoyo/submit", data={"answer-tension": "m*g"}).status_code == 400
    assert as_student.post("/problems/yoyo/preview", data={"answer-tension": "m*g"}).status_code == 400
    assert as_student.post("/problems/yoyo/submit", data={"answer-tension": "m*g", "csrf_token": "forged"}).status_code == 400
    assert submissions(app) == 0


def test_an_empty_submission_is_sent_back(app, as_student, problems):
    response = submit_answers(as_student, "yoyo", tension="  ", acceleration="")
    assert response.status_code == 422 and "Type at least one answer" in response.get_data(as_text=True)
    assert submissions(app) == 0


def test_a_submitted_answer_is_queued_then_graded_with_feedback(app, as_student, problems):
    response = submit_answers(as_student, "yoyo", tension="m g")
    assert response.status_code == 302 and response.headers["Location"] == "/problems/yoyo#answers"
    html = as_student.get("/problems/yoyo").get_data(as_text=True)
    assert "queued" in html and 'data-poll="/submissions/1/status"' in html
    assert '<noscript><meta http-equiv="refresh"' in html  # without JavaScript the page reloads itself
    assert as_student.get("/submissions/1/status").get_json()["pending"] is True

    assert grade_all(app) == 1
    status = as_student.get("/submissions/1/status").get_json()
    assert status["pending"] is False and status["label"] == "incorrect" and "badge incorrect" in status["html"]
    page = as_student.get("/problems/yoyo").get_data(as_text=True)
    assert "The tension must be less than the weight." in page and "data-poll" not in page
    assert "http-equiv" not in page
    detail = as_student.get("/submissions/1").get_data(as_text=True)
    assert "The tension must be less than the weight." in detail and "your answer gives" in detail
    with app.extensions["lagrade.db"].read() as session:
        reference_value = session.scalars(select(Verdict)).one().counterexample["reference"]
    for page_html in (page, detail, status["html"]):
        assert_no_reference(page_html)
        assert f"{reference_value:.4g}" not in page_html and str(reference_value) not in page_html


def test_a_correct_answer_reads_correct(app, as_student, problems):
    submit_answers(as_student, "yoyo", acceleration="2g/3")
    grade_all(app)
    assert as_student.get("/submissions/1/status").get_json()["label"] == "correct"
    assert "all correct" not in as_student.get("/problems").get_data(as_text=True)  # tension still open


def test_other_students_work_is_not_found(app, as_student, as_other_student, problems):
    submit_answers(as_other_student, "yoyo", tension="m*g*2")
    grade_all(app)
    assert as_student.get("/submissions/1").status_code == 404
    assert as_student.get("/submissions/1/status").status_code == 404
    assert "m*g*2" not in as_student.get("/problems/yoyo").get_data(as_text=True)
    assert "m*g*2" in as_other_student.get("/problems/yoyo").get_data(as_text=True)


def test_the_history_lists_my_attempts_newest_first(app, as_student, problems):
    submit_answers(as_student, "yoyo", tension="m*g")
    submit_answers(as_student, "yoyo", tension="m*g/2")
    grade_all(app)
    html = as_student.get("/problems/yoyo").get_data(as_text=True)
    history = html[html.index('id="history"'):]
    assert re.search(r"m\*g/2</code>.*m\*g</code>", history, re.S)
    assert history.count("badge incorrect") == 2


def test_an_unreadable_answer_is_shown_at_its_input_and_is_not_an_attempt(app, as_student, problems):
    response = submit_answers(as_student, "yoyo", tension="m*g/(3", acceleration="2*g/3")
    html = response.get_data(as_text=True)
    assert response.status_code == 422 and submissions(app) == 1  # the readable one was sent, this one not
    block = html[html.index('id="answer-tension"'):html.index('class="buttons"')]
    assert 'class="preview error"' in block and '<span class="caret">^</span>' in block
    assert "(at character 5)" in block and 'value="m*g/(3"' in block  # kept in its input, to fix
    assert "Nothing was counted as an attempt" in html


def test_sending_the_same_text_again_is_the_same_attempt(app, as_student, problems):
    submit_answers(as_student, "yoyo", tension="m*g")
    again = submit_answers(as_student, "yoyo", tension="m*g")
    assert again.status_code == 302 and submissions(app) == 1
    page = as_student.get("/problems/yoyo").get_data(as_text=True)
    assert "not counted as another attempt" in page


def test_a_verdict_shows_its_feedback_once_and_the_point_with_math(app, as_student, problems):
    submit_answers(as_student, "yoyo", tension="m*g/2")
    grade_all(app)
    detail = as_student.get("/submissions/1").get_data(as_text=True)
    verdict = detail[detail.index('class="verdict"'):]
    assert "ball arithmetic" not in verdict and "counterexample" not in verdict  # the instructor's words
    point = verdict[verdict.index('class="small point"'):]
    assert point.startswith('class="small point">At') and "<math" in point and "your answer gives" in point
    assert re.search(r"</math> = \d+(\.5)? (kg|m/s²)", point)  # round values, with their units


def test_the_history_names_each_answer_by_its_prompt(app, as_student, problems):
    submit_answers(as_student, "yoyo", tension="m*g")
    grade_all(app)
    html = as_student.get("/problems/yoyo").get_data(as_text=True)
    row = html[html.index('id="history"'):].split("<tr>")[2]
    assert "Tension" in row and ">tension<" not in row


def _answer_block(html: str, name: str) -> str:
    """The part of the page about one answer: its input, its preview, what became of it."""
    start = html.index(f'id="answer-{name}"')
    ends = [html.find('class="answer-block"', start), html.index('class="buttons"', start)]
    return html[start:min(end for end in ends if end != -1)]


# A refused answer (over the 4000-character limit) once ended the loop: the answers after it were
# neither stored nor kept in the form. Whichever is refused, the other is stored.
@pytest.mark.parametrize("refused, valid, text", [("tension", "acceleration", "2*g/3"),
                                                  ("acceleration", "tension", "m*g/3")])
def test_a_refused_answer_is_marked_at_its_input_and_the_others_are_stored(app, as_student, problems,
                                                                           refused, valid, text):
    too_long = "m*g+" * 1125  # 4500 characters
    response = submit_answers(as_student, "yoyo", **{refused: too_long, valid: text})
    html = response.get_data(as_text=True)
    assert response.status_code == 422 and submissions(app) == 1
    with app.extensions["lagrade.db"].read() as session:
        assert session.scalars(select(Submission.answer_name)).all() == [valid]
    block = _answer_block(html, refused)
    assert "Not submitted:" in block and "4500 characters long; the limit is 4000" in block
    assert f'value="{too_long}"' in block  # kept in its input, to shorten
    assert f'value="{text}"' in _answer_block(html, valid) and "Submitted 1 answer for grading" in html


def test_a_rate_limit_partway_names_the_answers_not_submitted_and_keeps_their_text(app, as_student, problems):
    app.config.update(RATE_LIMITS_ENABLED=True, RATE_LIMITS={**app.config["RATE_LIMITS"], "submit": (1, 1)})
    response = submit_answers(as_student, "yoyo", tension="m*g/3", acceleration="2*g/3")
    html = response.get_data(as_text=True)
    assert response.status_code == 429 and submissions(app) == 1  # the first; the limit stopped the second
    with app.extensions["lagrade.db"].read() as session:
        [sent] = session.scalars(select(Submission.answer_name)).all()
    [held] = {"tension", "acceleration"} - {sent}
    assert "Not submitted:" in _answer_block(html, held) and "Not submitted:" not in _answer_block(html, sent)
    assert f"Not submitted (too many submissions in a short time): {held}." in html
    assert 'value="2*g/3"' in html and 'value="m*g/3"' in html
