"""Uploads against the real server: `grader serve` derives them in its derivation workers, refuses
oversized bodies before reading them, stops a pathological scene at its budget, and finishes a
derivation that a kill -9 interrupted once it is started again."""

import re
import shutil
import time
from pathlib import Path

import pytest
import requests

from grader.bench.http import Server, make_tokens
from grader.bench.isolation import pathological_scene

pytestmark = [pytest.mark.server, pytest.mark.slow]

YOYO = Path(__file__).resolve().parents[2] / "problems" / "yoyo.toml"
TOML = {"Content-Type": "application/toml"}


@pytest.fixture
def site(tmp_path):
    """A working directory with the yo-yo problem, a migrated SQLite database and one instructor token."""
    (tmp_path / "problems").mkdir()
    shutil.copy(YOYO, tmp_path / "problems" / "yoyo.toml")
    url = f"sqlite:///{tmp_path / 'served.sqlite'}"
    [token] = make_tokens(url, "instructor", 1)
    servers = []

    def server(**env) -> Server:
        instance = Server(tmp_path, database_url=url, problems=tmp_path / "problems", log_name=f"s{len(servers)}.log",
                          env={"LAGRADE_RATE_LIMITS_ENABLED": "false", **env})
        servers.append(instance)
        return instance

    yield server, {"Authorization": f"Bearer {token}"}
    for instance in servers:
        instance.kill()


def _poll(base: str, location: str, headers: dict, until=("done", "failed"), timeout: float = 90.0) -> dict:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        body = requests.get(base + location, headers=headers, timeout=30).json()
        if body["status"] in until:
            return body
        time.sleep(0.1)
    raise AssertionError(f"{location} still {body['status']} after {timeout} s")


def test_the_server_derives_uploads_in_the_background_and_refuses_oversized_bodies_unread(site):
    server, headers = site
    with server(LAGRADE_DERIVE_TIMEOUT_S="2") as running:
        base = running.base_url
        scene = YOYO.read_text().replace('id = "yoyo"', 'id = "yoyo-served"')
        accepted = requests.post(base + "/api/v1/problems", data=scene.encode(), headers={**headers, **TOML},
                                 timeout=30)
        assert accepted.status_code == 202
        done = _poll(base, accepted.headers["Location"], headers)
        assert done["status"] == "done" and done["problem"]["id"] == "yoyo-served"

        slow = requests.post(base + "/api/v1/problems", data=pathological_scene(4).encode(),
                             headers={**headers, **TOML}, timeout=30)
        failed = _poll(base, slow.headers["Location"], headers)
        # The engine's budget (0.9 of 2 s) names the step; the child's kill at 2 s is the backstop.
        assert re.fullmatch(r"upload\.toml: the derivation (ran out of its 1\.8 s budget while .+"
                            r"|took longer than 2 s and was stopped)", failed["error"]), failed["error"]

        # Over the app's 1 MiB cap: waitress refuses from the Content-Length, without reading the body,
        # and the app writes the answer (grader.web.server_refusals).
        huge = requests.post(base + "/api/v1/check", data=b"x" * (2 * 1024 * 1024),
                             headers={**headers, "Content-Type": "application/json"}, timeout=30)
        assert huge.status_code == 413 and huge.headers["Content-Type"] == "application/problem+json"


def test_a_derivation_interrupted_by_a_kill_is_finished_after_the_restart(site):
    server, headers = site
    first = server().start()
    scene = YOYO.read_text().replace('id = "yoyo"', 'id = "yoyo-restarted"')
    # A three-link chain takes a second or two to derive: long enough to be caught running.
    location = requests.post(first.base_url + "/api/v1/problems", data=pathological_scene(3).encode(),
                             headers={**headers, **TOML}, timeout=30).headers["Location"]
    assert _poll(first.base_url, location, headers, until=("running", "done", "failed"))["status"] == "running"
    first.kill()
    second = server().start()
    try:
        job = _poll(second.base_url, location, headers)
        assert job["status"] == "done" and job["problem"]["id"] == "chain3", job
        again = requests.post(second.base_url + "/api/v1/problems", data=scene.encode(),
                              headers={**headers, **TOML}, timeout=30)
        assert _poll(second.base_url, again.headers["Location"], headers)["status"] == "done"
    finally:
        second.stop()
