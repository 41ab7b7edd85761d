"""The whole loop in a real browser against the real server (``grader serve`` in a subprocess).

A student signs in, types an answer, sees the live preview, submits and sees the verdict; then an
instructor signs in and finds that wrong answer among the grouped wrong answers. Screenshots of both
pages go to /tmp (lagrade-student.png, lagrade-dashboard.png, lagrade-review.png) for people to look at.

Needs Debian's chromium at /usr/bin/chromium and Playwright's Python package. Under ``CI=true`` a
missing browser fails the test; elsewhere it skips, saying why.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import threading
from contextlib import contextmanager
from pathlib import Path

import pytest

pytestmark = [pytest.mark.browser, pytest.mark.server, pytest.mark.slow]

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
STUDENT = ("student@example.org", "student-pass-1")
INSTRUCTOR = ("teacher@example.org", "teacher-pass-1")
SCREENSHOTS = Path("/tmp")


def _require_browser():
    """Playwright's sync API, or skip (fail under CI=true) saying what is missing."""
    problems = []
    if not os.access(CHROMIUM, os.X_OK):
        problems.append(f"Debian chromium is not installed at {CHROMIUM} (apt-get install chromium)")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        problems.append("the Playwright Python package is not installed (pip install playwright)")
        sync_playwright = None
    if problems:
        message = "browser test cannot run: " + "; ".join(problems)
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(message)
        pytest.skip(message)
    return sync_playwright


def _grader(*args: str) -> list[str]:
    return [sys.executable, "-c", "from grader.cli import main; main()", *args]


@pytest.fixture
def server(tmp_path):
    """``grader serve`` on a temporary SQLite file and a free port of 127.0.0.1; yields its base URL."""
    problems = tmp_path / "problems"
    problems.mkdir()
    shutil.copy(ROOT / "problems" / "yoyo.toml", problems / "yoyo.toml")
    env = dict(os.environ, DATABASE_URL=f"sqlite:///{tmp_path / 'lagrade.sqlite'}", PYTHONUNBUFFERED="1")
    for role, (email, password) in (("student", STUDENT), ("instructor", INSTRUCTOR)):
        subprocess.run(_grader("db", "create-user", "--role", role, "--email", email, "--name",
                               f"Demo {role}", "--password", password),
                       env=env, cwd=tmp_path, check=True, capture_output=True, timeout=120)
    with serving(env, tmp_path, problems) as base:
        yield base


@contextmanager
def serving(env: dict[str, str], cwd: Path, problems: Path, timeout: float = 300):
    """``grader serve`` on a free port of 127.0.0.1 in ``cwd``; yields its base URL, stops it after."""
    process = subprocess.Popen(_grader("serve", "--host", "127.0.0.1", "--port", "0", "--workers", "1",
                                       "--no-demo", "--problems", str(problems)),
                               env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines: list[str] = []
    base: list[str] = []
    ready = threading.Event()

    def read_output():  # keep draining the pipe so the server never blocks on a full one
        for line in process.stdout:
            lines.append(line)
            found = re.search(r"serving on (http://127\.0\.0\.1:\d+)/", line)
            if found:
                base.append(found.group(1))
                ready.set()
        ready.set()

    threading.Thread(target=read_output, daemon=True).start()
    try:
        ready.wait(timeout)
        assert base, "grader serve did not start:\n" + "".join(lines)
        yield base[0]
    finally:
        process.send_signal(signal.SIGTERM)
        try:
            process.wait(20)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(5)


def _sign_in(page, base: str, who: tuple[str, str]) -> None:
    page.goto(f"{base}/login")
    page.fill("#username", who[0])
    page.fill("#password", who[1])
    page.click("button[type=submit]")


@pytest.fixture
def sync_playwright():
    """Playwright's sync API, checked before the server is started (see _require_browser)."""
    return _require_browser()


@pytest.mark.parametrize("ci, outcome", [("true", pytest.fail.Exception), ("", pytest.skip.Exception)])
def test_a_missing_browser_fails_under_ci_and_skips_elsewhere(monkeypatch, ci, outcome):
    monkeypatch.setitem(globals(), "CHROMIUM", "/nonexistent/chromium")
    monkeypatch.setenv("CI", ci)
    with pytest.raises(outcome, match="chromium is not installed"):
        _require_browser()


def test_a_student_answers_and_the_instructor_sees_it_grouped(sync_playwright, server):
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
        try:
            page = browser.new_page(viewport={"width": 1100, "height": 1000})
            errors: list[str] = []
            page.on("pageerror", lambda error: errors.append(str(error)))

            _sign_in(page, server, STUDENT)
            page.wait_for_url(f"{server}/problems")
            page.click("text=Yo-yo")
            page.wait_for_url(f"{server}/problems/yoyo")
            assert page.locator(".statement math").count() > 0  # the statement's $...$ as MathML

            # Typing shows how the text is read, from POST /preview, without submitting anything.
            page.locator("#input-tension").press_sequentially("m g", delay=40)
            preview = page.locator("#preview-tension")
            preview.locator(".reads math").wait_for(timeout=15_000)
            assert "a force" in preview.inner_text()
            page.locator("#input-acceleration").press_sequentially("g*/3", delay=40)
            page.locator("#preview-acceleration .caret").wait_for(timeout=15_000)  # an error, pointed at
            page.locator("#input-acceleration").fill("")

            page.click("text=Submit for grading")
            page.wait_for_url(re.compile(r".*/problems/yoyo#answers$"))
            verdict = page.locator("#answer-tension .verdict .badge")
            verdict.filter(has_text="incorrect").wait_for(timeout=60_000)  # polled until graded
            feedback = page.locator("#answer-tension .verdict").inner_text()
            assert "less than its weight" in feedback  # the scene's own feedback for m*g
            page.locator("#answer-tension").scroll_into_view_if_needed()
            page.screenshot(path=str(SCREENSHOTS / "lagrade-student.png"), full_page=True)
            assert errors == []

            page.click("text=Sign out")
            page.wait_for_url(f"{server}/login")
            _sign_in(page, server, INSTRUCTOR)
            page.wait_for_url(f"{server}/instructor/")
            page.click("text=Yo-yo: a solid cylinder")
            page.wait_for_url(f"{server}/instructor/problems/yoyo")
            group = page.locator("#wrong-tension tr.wrong-group").first
            assert "g m" in group.inner_text() or "g*m" in group.inner_text()
            assert group.locator("td.num").first.inner_text().strip() == "1"
            page.screenshot(path=str(SCREENSHOTS / "lagrade-dashboard.png"), full_page=True)
            page.click("text=Review and publish")
            page.locator(".derivation").wait_for()
            assert page.locator("table math").count() >= 3  # each reference answer, as math
            page.screenshot(path=str(SCREENSHOTS / "lagrade-review.png"), full_page=True)
            assert errors == []
        finally:
            browser.close()
