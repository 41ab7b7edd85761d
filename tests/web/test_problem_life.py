"""The one intake of scene files (``queue_scene``), as the API and the instructor pages both call it."""

import pytest
from sqlalchemy import select

from grader.store.models import DerivationJob, User
from grader.store.problems import problem_by_slug
from grader.web.policy import Principal
from grader.web.problem_life import MAX_SCENE_BYTES, SceneRefused, queue_scene
from tests.web.conftest_pages import accounts, problems  # noqa: F401  (fixtures)

MAX_ACTIVE = 2


@pytest.fixture
def ine(app, accounts, problems):
    """Ine (instructor of MECH) as a principal, and the problem ``mech`` she manages, as a view finds them."""
    with app.extensions["lagrade.db"].read() as session:
        return Principal.of(session, session.get(User, accounts["ine"].id)), problem_by_slug(session, "mech")


def _jobs(app) -> list[DerivationJob]:
    with app.extensions["lagrade.db"].read() as session:
        return list(session.scalars(select(DerivationJob)))


@pytest.mark.parametrize("source, kind", [
    ("", "empty"),
    (" \n\t", "empty"),
    ('id = "mech"\n' + "#" * MAX_SCENE_BYTES, "too-large"),
    ("id = ", "invalid-scene"),
    ('id = "other-id"\n', "wrong-id"),  # an edit keeps its problem's id
    ("title = 'no id at all'\n", "wrong-id"),
])
def test_a_new_version_that_cannot_be_queued_is_refused_with_its_reason(app, ine, source, kind):
    principal, problem = ine
    with app.test_request_context("/"), pytest.raises(SceneRefused) as refused:
        queue_scene(principal, source, filename="mech.toml", publish=False, max_active=MAX_ACTIVE, problem=problem)
    assert refused.value.kind == kind and refused.value.message and _jobs(app) == []


def test_the_newest_source_again_is_nothing_to_derive(app, ine):
    principal, problem = ine
    with app.test_request_context("/"):
        queued = queue_scene(principal, 'id = "mech"\n', filename="mech.toml", publish=False, max_active=MAX_ACTIVE,
                             problem=problem)
    assert (queued.job_id, queued.same_as) == (None, 1) and _jobs(app) == []


@pytest.mark.parametrize("publish", [False, True])
def test_a_new_version_is_queued_in_its_problems_course_as_asked(app, ine, accounts, publish):
    principal, problem = ine
    with app.test_request_context("/"):
        queued = queue_scene(principal, 'id = "mech"\n# edited\n', filename="mech.toml", publish=publish,
                             max_active=MAX_ACTIVE, problem=problem, course_id=None)
    [job] = _jobs(app)
    assert (job.id, job.course_id, job.publish, job.requester_id) == (queued.job_id, accounts["course"], publish,
                                                                       accounts["ine"].id)


def test_a_requester_with_enough_derivations_waiting_is_told_when_to_try_again(app, ine):
    principal, problem = ine
    with app.test_request_context("/"):
        for n in range(MAX_ACTIVE):
            queue_scene(principal, f'id = "mech"\n# {n}\n', filename="mech.toml", publish=False,
                        max_active=MAX_ACTIVE, problem=problem)
        with pytest.raises(SceneRefused) as refused:
            queue_scene(principal, 'id = "mech"\n# more\n', filename="mech.toml", publish=False,
                        max_active=MAX_ACTIVE, problem=problem)
    assert refused.value.kind == "too-many-derivations" and refused.value.retry_after_s > 0
    assert len(_jobs(app)) == MAX_ACTIVE


def test_a_registration_joins_the_course_chosen(app, ine, accounts):
    principal, _ = ine
    with app.test_request_context("/"):
        queue_scene(principal, 'id = "brand-new"\n', filename="new.toml", publish=True, max_active=MAX_ACTIVE,
                    course_id=accounts["course"])
    [job] = _jobs(app)
    assert (job.course_id, job.publish) == (accounts["course"], True)
