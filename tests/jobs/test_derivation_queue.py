"""The derivation queue: uploads are stored as jobs, claimed once, finished or failed with a message."""

import dataclasses
import socket
from datetime import timedelta

import pytest
from sqlalchemy import select

from grader.jobs import derivation_queue as queue
from grader.store.models import Course, DerivationJob, Problem, utcnow
from grader.store.users import create_user

SOURCE = 'id = "yoyo"\n'
# Worker ids name their host and process: this one is on this host, in a process that does not exist.
DEAD = f"{socket.gethostname()}:{2 ** 22 + 7}"


def anyone_may_update(session, requester, problem):
    return True


def nobody_may_update(session, requester, problem):
    return False


@pytest.fixture
def people(database):
    with database.write() as session:
        ids = {name: create_user(session, role="instructor", name=name).id for name in ("ine", "oth")}
        course = Course(code="MECH", title="Mechanics")
        session.add(course)
        session.flush()
        ids["course"] = course.id
        return ids


def _job(database, job_id) -> DerivationJob:
    with database.read() as session:
        return session.get(DerivationJob, job_id)


def test_an_upload_is_stored_queued_with_its_source_hash(database, people):
    job_id = queue.enqueue(database, requester_id=people["ine"], source=SOURCE, filename="yoyo.toml")
    job = _job(database, job_id)
    assert (job.status, job.filename, job.source, job.attempts) == ("queued", "yoyo.toml", SOURCE, 0)
    assert len(job.source_sha256) == 64 and job.problem_version_id is None


@pytest.mark.parametrize("limit", [1, 2, 3])
def test_a_requester_has_at_most_the_limit_of_jobs_queued_or_running(database, people, limit):
    for _ in range(limit):
        queue.enqueue(database, requester_id=people["ine"], source=SOURCE, max_active=limit)
    with pytest.raises(queue.TooManyDerivations, match=f"You have {limit} scene") as refused:
        queue.enqueue(database, requester_id=people["ine"], source=SOURCE, max_active=limit)
    assert refused.value.retry_after_s > 0
    # Another instructor is not held up by the first one's uploads.
    queue.enqueue(database, requester_id=people["oth"], source=SOURCE, max_active=limit)


def test_a_finished_job_frees_its_place_under_the_limit(database, people, yoyo):
    queue.enqueue(database, requester_id=people["ine"], source=SOURCE, max_active=1)
    task = queue.claim(database, "w", lease_s=60)
    assert queue.finish(database, task, "w", yoyo, anyone_may_update)
    queue.enqueue(database, requester_id=people["ine"], source=SOURCE, max_active=1)


def test_a_job_is_claimed_once_then_finished_as_a_problem_version(database, people, yoyo):
    job_id = queue.enqueue(database, requester_id=people["ine"], source=SOURCE, course_id=people["course"],
                           publish=True)
    task = queue.claim(database, "w1", lease_s=60)
    assert task.job_id == job_id and task.attempts == 1 and task.publish
    assert _job(database, job_id).status == "running"
    assert queue.claim(database, "w2", lease_s=60) is None
    assert queue.finish(database, task, "w1", yoyo, anyone_may_update)
    job = _job(database, job_id)
    assert (job.status, job.new_version, job.error) == ("done", True, None)
    with database.read() as session:
        version = session.get(DerivationJob, job_id).problem_version
        assert (version.problem.slug, version.number, version.published) == ("yoyo", 1, True)
        assert version.problem.course_id == people["course"]  # a new problem joins the chosen course


def test_the_same_scene_again_is_done_without_a_new_version(database, people, yoyo):
    for expected in (True, False):
        queue.enqueue(database, requester_id=people["ine"], source=SOURCE, publish=True)
        task = queue.claim(database, "w", lease_s=60)
        queue.finish(database, task, "w", yoyo, anyone_may_update)
        assert _job(database, task.job_id).new_version is expected


def test_a_failed_job_keeps_the_scenes_message(database, people):
    job_id = queue.enqueue(database, requester_id=people["ine"], source=SOURCE)
    task = queue.claim(database, "w", lease_s=60)
    assert queue.fail(database, task, "w", "upload.toml: unknown name 'tehta'")
    job = _job(database, job_id)
    assert (job.status, job.error) == ("failed", "upload.toml: unknown name 'tehta'")
    assert job.finished_at is not None


def test_a_problem_id_the_requester_may_not_change_fails_the_job(database, people, yoyo):
    with database.write() as session:
        session.add(Problem(slug="yoyo", course_id=people["course"]))
    queue.enqueue(database, requester_id=people["oth"], source=SOURCE)
    task = queue.claim(database, "w", lease_s=60)
    assert queue.finish(database, task, "w", yoyo, nobody_may_update)
    job = _job(database, task.job_id)
    assert job.status == "failed" and "taken by another course" in job.error and job.problem_version_id is None


# A derived problem the database cannot take (a NUL in its title; once let through at upload) was
# left running, claimed again and derived again, then failed as "interrupted 2 times".
@pytest.mark.parametrize("field, value, words", [
    ("title", "\x00Yo-yo", "problem_versions.title: holds a NUL character"),
    ("title", "Yo-yo " * 100, "problem_versions.title: 600 characters; the limit is 200"),
])
def test_a_derived_problem_that_cannot_be_stored_fails_its_job_at_once_with_the_reason(database, people, yoyo,
                                                                                     field, value, words):
    queue.enqueue(database, requester_id=people["ine"], source=SOURCE, filename="yoyo.toml")
    task = queue.claim(database, "w", lease_s=60)
    assert queue.finish(database, task, "w", dataclasses.replace(yoyo, **{field: value}), anyone_may_update)
    job = _job(database, task.job_id)
    assert job.status == "failed" and job.error.startswith("yoyo.toml: the derived problem cannot be stored")
    assert words in job.error and "interrupted" not in job.error and job.attempts == 1
    with database.read() as session:
        assert session.scalar(select(Problem).where(Problem.slug == "yoyo")) is None  # nothing half-stored


def test_an_outcome_from_a_worker_that_lost_its_claim_is_dropped(database, people, yoyo):
    queue.enqueue(database, requester_id=people["ine"], source=SOURCE)
    task = queue.claim(database, f"{DEAD}:w1", lease_s=60)
    assert queue.recover(database) == 1  # a restart found w1's process gone: the job is queued again
    again = queue.claim(database, "w2", lease_s=60)
    assert not queue.finish(database, task, f"{DEAD}:w1", yoyo, anyone_may_update)
    assert not queue.fail(database, task, f"{DEAD}:w1", "too late")
    assert _job(database, task.job_id).status == "running" and again.attempts == 2


def test_running_jobs_are_queued_again_after_a_restart_and_fail_after_max_attempts(database, people):
    job_id = queue.enqueue(database, requester_id=people["ine"], source=SOURCE, filename="chain.toml")
    for attempt in range(1, queue.MAX_ATTEMPTS + 1):
        assert queue.claim(database, f"{DEAD}:boot{attempt}", lease_s=60).attempts == attempt
        assert queue.recover(database) == 1
        assert _job(database, job_id).status == "queued"
    assert queue.claim(database, "last", lease_s=60) is None  # the scene that keeps stopping servers
    job = _job(database, job_id)
    assert job.status == "failed" and "interrupted" in job.error and job.error.startswith("chain.toml")


@pytest.mark.parametrize("holder, recovered", [
    (f"{DEAD}:pool/d0", 1),  # a process of this host that is gone: its job is taken back at once
    (f"{socket.gethostname()}:1:pool/d0", 0),  # a live process (pid 1 always exists): left alone
    ("other-host:123:pool/d0", 0),  # another host: its lease decides
])
def test_a_restart_takes_back_only_the_jobs_of_dead_processes(database, people, holder, recovered):
    queue.enqueue(database, requester_id=people["ine"], source=SOURCE)
    queue.claim(database, holder, lease_s=60)
    assert queue.recover(database) == recovered


def test_an_expired_lease_is_queued_again(database, people):
    job_id = queue.enqueue(database, requester_id=people["ine"], source=SOURCE)
    queue.claim(database, "w", lease_s=60)
    assert queue.requeue_expired(database) == 0
    assert queue.requeue_expired(database, now=utcnow() + timedelta(seconds=61)) == 1
    assert _job(database, job_id).status == "queued"


def test_requesters_take_turns_and_each_ones_jobs_go_oldest_first(database, people):
    ine = [queue.enqueue(database, requester_id=people["ine"], source=SOURCE, max_active=5) for _ in range(3)]
    oth = [queue.enqueue(database, requester_id=people["oth"], source=SOURCE, max_active=5) for _ in range(2)]
    # Ine uploaded first, but once she is served, Oth's waiting upload goes before her next one.
    claimed = [queue.claim(database, "w", lease_s=60).job_id for _ in range(5)]
    assert claimed == [ine[0], oth[0], ine[1], oth[1], ine[2]]
    with database.read() as session:
        assert set(session.scalars(select(DerivationJob.status))) == {"running"}


def test_concurrent_uploads_of_one_requester_cannot_slip_past_the_limit(database, people):
    import threading

    accepted, refused = [], []

    def upload():
        try:
            accepted.append(queue.enqueue(database, requester_id=people["ine"], source=SOURCE, max_active=2))
        except queue.TooManyDerivations:
            refused.append(True)

    threads = [threading.Thread(target=upload) for _ in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert (len(accepted), len(refused)) == (2, 6)
