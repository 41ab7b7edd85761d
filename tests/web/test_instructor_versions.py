"""Instructor pages over a problem's versions: edit the draft in place, unpublish, archive, compare
versions, regrade after a confirmation and follow its progress, read the scene-file format."""

import re
from datetime import datetime
from pathlib import Path

import pytest
from sqlalchemy import select

from grader.store.models import Problem, ProblemVersion, Submission
from grader.store.problems import save_problem
from grader.web.instructor.versions import reference_changes
from grader.web.policy import Action, Principal, allowed
from tests.web.conftest_pages import (  # noqa: F401  (fixtures)
    accounts, as_instructor, as_other_student, as_student, csrf, form_token, grade_all, problems, sign_in,
    submit_answers,
)
from tests.web.derive_in_process import derive_all, derive_in_process

ROOT = Path(__file__).resolve().parents[2]
YOYO_SCENE = (ROOT / "problems" / "yoyo.toml").read_text()


@pytest.fixture(scope="module")
def derived_yoyo():
    """The real yo-yo scene file, derived once for the module (the engine takes a few seconds)."""
    return derive_in_process(YOYO_SCENE, "yoyo.toml")


@pytest.fixture
def yoyo_from_file(app, accounts, derived_yoyo):
    """The yo-yo stored from its real scene file (version 1, published, in no course), so it can be edited."""
    with app.extensions["lagrade.db"].write() as session:
        save_problem(session, derived_yoyo, published=True)
    return "yoyo"


def _versions(app, slug):
    with app.extensions["lagrade.db"].read() as session:
        return [(v.number, v.published, v.source) for v in session.scalars(
            select(ProblemVersion).join(Problem).where(Problem.slug == slug).order_by(ProblemVersion.number))]


def test_the_edit_form_holds_the_newest_scene_file(as_instructor, yoyo_from_file):
    html = as_instructor.get("/instructor/problems/yoyo/edit").get_data(as_text=True)
    assert 'id = &#34;yoyo&#34;' in html or 'id = "yoyo"' in html
    assert 'href="/instructor/docs/scene-format"' in html


def test_an_edited_scene_is_derived_as_a_new_draft_and_students_keep_the_published_one(
        app, as_instructor, as_student, yoyo_from_file):
    edited = YOYO_SCENE.replace("Yo-yo", "Yo-yo (revised)", 1)
    form = as_instructor.get("/instructor/problems/yoyo/edit").get_data(as_text=True)
    response = as_instructor.post("/instructor/problems/yoyo/edit", data={"source": edited,
                                                                          "csrf_token": form_token(form)})
    assert response.status_code == 302 and response.headers["Location"].startswith("/instructor/derivations/")
    derive_all(app)
    assert [(n, p) for n, p, _ in _versions(app, "yoyo")] == [(1, True), (2, False)]
    assert _versions(app, "yoyo")[1][2] == edited
    page = as_student.get("/problems/yoyo").get_data(as_text=True)
    assert "Yo-yo (revised)" not in page and "Yo-yo" in page  # the draft is not shown to students


@pytest.mark.parametrize("change, status, message", [
    (lambda s: s.replace('id = "yoyo"', 'id = "other-id"'), 422, "keep `id = &#34;yoyo&#34;`"),
    (lambda s: "", 422, "The scene file is empty."),
    (lambda s: "id = ", 422, "TOML"),
    (lambda s: s + "#" * (300 * 1024), 422, "at most 256 KiB"),
    (lambda s: s.replace('title = "', 'title = "\\u0000'), 422, "yoyo.toml: title holds a NUL character"),
])
def test_an_edit_that_cannot_be_a_draft_of_this_problem_is_refused_and_kept(app, as_instructor, yoyo_from_file,
                                                                           change, status, message):
    response = as_instructor.post("/instructor/problems/yoyo/edit", data={"source": change(YOYO_SCENE),
                                                                          "csrf_token": csrf(as_instructor)})
    body = response.get_data(as_text=True)
    assert response.status_code == status and message.replace('"', "&#34;") in body.replace('"', "&#34;")
    assert derive_all(app) == 0 and len(_versions(app, "yoyo")) == 1


def test_saving_the_same_scene_makes_no_version(app, as_instructor, yoyo_from_file):
    response = as_instructor.post("/instructor/problems/yoyo/edit", data={"source": YOYO_SCENE,
                                                                          "csrf_token": csrf(as_instructor)})
    assert response.status_code == 302 and "/review" in response.headers["Location"]
    assert derive_all(app) == 0 and len(_versions(app, "yoyo")) == 1


def test_unpublishing_hides_the_problem_from_students_again(app, as_instructor, as_student, problems):
    assert as_student.get("/problems/mech").status_code == 200
    response = as_instructor.post("/instructor/problems/mech/versions/1/unpublish",
                                  data={"csrf_token": csrf(as_instructor)})
    assert response.status_code == 302
    assert "students now see nothing" in as_instructor.get(response.headers["Location"]).get_data(as_text=True)
    assert as_student.get("/problems/mech").status_code == 404
    assert "Mech problem" not in as_student.get("/problems").get_data(as_text=True)


def test_an_archived_problem_vanishes_for_students_refuses_answers_and_comes_back(
        app, as_instructor, as_student, problems):
    assert "Mech problem" in as_student.get("/problems").get_data(as_text=True)
    assert as_instructor.post("/instructor/problems/mech/archive",
                              data={"csrf_token": csrf(as_instructor)}).status_code == 302
    assert "Mech problem" not in as_student.get("/problems").get_data(as_text=True)
    assert as_student.get("/problems/mech").status_code == 404
    assert submit_answers(as_student, "mech", tension="m*g").status_code == 404
    with app.extensions["lagrade.db"].read() as session:
        assert session.scalar(select(Submission.id)) is None  # nothing was stored
    review = as_instructor.get("/instructor/problems/mech/review").get_data(as_text=True)
    assert "Archived" in review and "Bring back from the archive" in review  # its managers still see it
    assert "archived" in as_instructor.get("/instructor/").get_data(as_text=True)
    assert as_instructor.post("/instructor/problems/mech/archive",
                              data={"restore": "1", "csrf_token": csrf(as_instructor)}).status_code == 302
    assert as_student.get("/problems/mech").status_code == 200


def test_the_diff_shows_the_scene_lines_and_the_references_that_changed(app, as_instructor, yoyo_from_file):
    edited = YOYO_SCENE.replace("Yo-yo", "Yo-yo (revised)", 1)
    as_instructor.post("/instructor/problems/yoyo/edit", data={"source": edited, "csrf_token": csrf(as_instructor)})
    derive_all(app)
    html = as_instructor.get("/instructor/problems/yoyo/diff").get_data(as_text=True)
    assert "version 1 → 2" in html
    assert re.search(r'<span class="del">-[^<]*Yo-yo', html) and re.search(r'<span class="add">\+[^<]*Yo-yo \(revised\)', html)
    assert "The reference answers are the same" in html
    same = as_instructor.get("/instructor/problems/yoyo/diff?from=2&to=2").get_data(as_text=True)
    assert "The scene files are the same." in same


@pytest.mark.parametrize("query", ["?from=9", "?to=0", "?from=x", "?to=-1", "?from=99999999999999999999"])
def test_the_diff_of_a_version_that_does_not_exist_is_not_found(as_instructor, yoyo_from_file, query):
    assert as_instructor.get(f"/instructor/problems/yoyo/diff{query}").status_code == 404


def test_reference_changes_name_the_fields_that_changed():
    before = [{"name": "T", "reference": "m*g", "kind": "expression"}, {"name": "a", "reference": "g"}]
    after = [{"name": "T", "reference": "m*g", "kind": "equation"}, {"name": "a", "reference": "g"},
             {"name": "N", "reference": "0"}]
    assert [(c.name, c.change, c.fields) for c in reference_changes(before, after)] == [
        ("T", "changed", ("kind",)), ("a", "same", ()), ("N", "added", ())]


def test_regrade_asks_first_saying_how_many_then_shows_progress(app, as_instructor, as_student, problems):
    submit_answers(as_student, "yoyo", tension="m*g", acceleration="g")
    grade_all(app)
    confirm = as_instructor.get("/instructor/problems/yoyo/regrade").get_data(as_text=True)
    assert "2 submissions" in confirm and "Regrade 2 submissions" in confirm
    with app.extensions["lagrade.db"].read() as session:  # asking changed nothing
        assert {s.grading_round for s in session.scalars(select(Submission))} == {1}
    response = as_instructor.post("/instructor/problems/yoyo/regrade", data={"csrf_token": csrf(as_instructor)})
    assert response.headers["Location"] == "/instructor/problems/yoyo/regrade/progress"
    waiting = as_instructor.get(response.headers["Location"]).get_data(as_text=True)
    assert '<meta http-equiv="refresh"' in waiting and "0 of 2 graded" in waiting
    assert re.search(r"Queued</td><td class=\"num\">2<", waiting)
    grade_all(app)
    done = as_instructor.get("/instructor/problems/yoyo/regrade/progress").get_data(as_text=True)
    assert "2 of 2 graded (100 %)" in done and 'http-equiv="refresh"' not in done


def test_the_results_page_links_to_the_confirmation_not_a_one_click_regrade(as_instructor, problems):
    html = as_instructor.get("/instructor/problems/yoyo").get_data(as_text=True)
    assert 'href="/instructor/problems/yoyo/regrade"' in html
    assert 'action="/instructor/problems/yoyo/regrade"' not in html


def test_the_scene_format_is_served_as_a_page_linked_from_the_navigation(as_instructor, as_student):
    nav = as_instructor.get("/instructor/").get_data(as_text=True)
    assert 'href="/instructor/docs/scene-format"' in nav
    page = as_instructor.get("/instructor/docs/scene-format")
    html = page.get_data(as_text=True)
    assert page.status_code == 200 and "<table>" in html and "<code>id</code>" in html
    assert "<script" not in html.split("</main>")[0].split("<main>")[1]
    assert as_student.get("/instructor/docs/scene-format").status_code == 403


@pytest.mark.parametrize("who, sees, submits", [
    (Principal(user_id=1, role="student", enrolled=frozenset({1})), False, False),
    (Principal(user_id=2, role="lms", enrolled=frozenset({1})), False, False),
    (Principal(user_id=3, role="instructor", enrolled=frozenset({1}), taught=frozenset({1})), True, False),
    (Principal(user_id=4, role="admin"), True, False),
])
def test_the_policy_keeps_an_archived_problem_for_its_managers_and_lets_nobody_answer_it(who, sees, submits):
    version = ProblemVersion(published=True, problem=Problem(slug="old", course_id=1, archived_at=datetime(2026, 1, 1)))
    assert allowed(who, Action.SEE, version) is sees and allowed(who, Action.SEE, version.problem) is sees
    assert allowed(who, Action.SUBMIT, version) is submits
    assert allowed(who, Action.SUBMIT_FOR_OTHERS, version) is submits
    version.problem.archived_at = None  # the same principals, before the archive
    assert allowed(who, Action.SEE, version) and allowed(who, Action.SUBMIT, version)
