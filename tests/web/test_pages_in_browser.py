"""Every page, as each audience sees it, at desktop (1280 px) and phone (390 px) width, in Debian's
chromium: axe-core finds no serious or critical WCAG 2.2 AA violation, no raw ``$`` math is left
unrendered, every page has a title of its own, and no table is clipped on a phone.

Screenshots go to ``/tmp/lagrade-pages/`` (the test artefacts). axe-core comes from the npm registry
(``package.json``; ``.ci/run`` runs ``npm ci``); under ``CI=true`` a missing axe fails the test.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from tests.web.test_browser_flow import (  # noqa: F401  (fixtures)
    CHROMIUM,
    CHROMIUM_ARGS,
    INSTRUCTOR,
    STUDENT,
    _sign_in,
    server,
    sync_playwright,
)

pytestmark = [pytest.mark.browser, pytest.mark.server, pytest.mark.slow]

ROOT = Path(__file__).resolve().parents[2]
AXE = ROOT / "node_modules" / "axe-core" / "axe.min.js"
SHOTS = Path("/tmp/lagrade-pages")
WIDTHS = {"desktop": 1280, "phone": 390}
AUDIENCES = {
    "anonymous": (None, ["/login"]),
    "student": (STUDENT, ["/problems", "/problems/yoyo", "/courses", "/account"]),
    "instructor": (INSTRUCTOR, [
        "/instructor/", "/instructor/problems/yoyo", "/instructor/problems/yoyo/review", "/instructor/problems/new",
        "/instructor/courses", "/instructor/problems/yoyo/edit", "/instructor/problems/yoyo/diff",
        "/instructor/problems/yoyo/regrade", "/instructor/problems/yoyo/regrade/progress",
        "/instructor/docs/scene-format", "/account"]),
}
# Pages whose text documents the math syntax itself, so a "$" there is meant to be read as typed.
LITERAL_DOLLARS = {"/instructor/docs/scene-format"}
WCAG = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "wcag22aa"]

# Tables that are wider than the screen must sit in something that scrolls sideways.
CLIPPED_TABLES = """() => [...document.querySelectorAll('table')].filter(table => {
    if (table.scrollWidth <= document.documentElement.clientWidth + 1) return false;
    for (let box = table.parentElement; box; box = box.parentElement) {
        const overflow = getComputedStyle(box).overflowX;
        if ((overflow === 'auto' || overflow === 'scroll') && box.clientWidth < box.scrollWidth + 1) return false;
    }
    return true;
}).map(table => table.id || table.className || table.outerHTML.slice(0, 60))"""


def _axe_source() -> str:
    if not AXE.exists():
        message = f"axe-core is not installed at {AXE} (npm ci)"
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(message)
        pytest.skip(message)
    return AXE.read_text()


def _audit(page, axe: str) -> list[str]:
    page.add_script_tag(content=axe)
    result = page.evaluate("(tags) => axe.run(document, {runOnly: {type: 'tag', values: tags}})", WCAG)
    return [f"{v['id']} ({v['impact']}): {v['help']} at {[n['target'] for n in v['nodes']][:3]}"
            for v in result["violations"] if v["impact"] in ("serious", "critical")]


@pytest.mark.parametrize("audience", list(AUDIENCES))
def test_every_page_is_accessible_rendered_and_readable_on_a_phone(sync_playwright, server, audience):
    who, paths = AUDIENCES[audience]
    axe = _axe_source()
    SHOTS.mkdir(exist_ok=True)
    problems: list[str] = []
    titles: dict[str, str] = {}
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
        try:
            for width_name, width in WIDTHS.items():
                # bypass_csp: axe is injected as a script; the pages themselves run under their CSP.
                context = browser.new_context(viewport={"width": width, "height": 900}, bypass_csp=True)
                page = context.new_page()
                if who is not None:
                    _sign_in(page, server, who)
                    page.wait_for_load_state("networkidle")
                for path in paths:
                    page.goto(f"{server}{path}")
                    page.wait_for_load_state("networkidle")
                    problems += _page_problems(page, axe, f"{path} ({audience}, {width}px)",
                                               f"{audience}{path.replace('/', '_')}-{width_name}",
                                               dollars_are_text=path in LITERAL_DOLLARS)
                    titles.setdefault(path, page.title())
                context.close()
        finally:
            browser.close()
    assert problems == [], json.dumps(problems, indent=1, ensure_ascii=False)
    assert all(titles.values()) and len(set(titles.values())) == len(titles), titles  # each says where you are


def _page_problems(page, axe: str, where: str, shot: str, dollars_are_text: bool = False) -> list[str]:
    """Screenshot ``page`` into the artefacts; what axe, the raw-``$`` check and the clipped-table check find."""
    page.screenshot(path=str(SHOTS / f"{shot}.png"), full_page=True)
    found = [f"{where}: {v}" for v in _audit(page, axe)]
    text = page.evaluate("() => document.body.innerText")
    if "$" in text and not dollars_are_text:
        found.append(f"{where}: raw math left unrendered: {text[max(0, text.index('$') - 40):text.index('$') + 40]!r}")
    return found + [f"{where}: table clipped: {t}" for t in page.evaluate(CLIPPED_TABLES)]


def test_verdicts_and_derivations_show_their_math_at_both_widths(sync_playwright, server):
    """A student sends a wrong answer whose scene feedback holds $...$ math, one without feedback (a
    counterexample), one the grader cannot read, and the same answers again; an instructor reviews the
    derivation. At 1280 and 390 px: math is MathML, never raw "$" or the checker's technical words."""
    axe = _axe_source()
    SHOTS.mkdir(exist_ok=True)
    problems: list[str] = []
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
        try:
            for round_, (width_name, width) in enumerate(WIDTHS.items()):
                context = browser.new_context(viewport={"width": width, "height": 900}, bypass_csp=True)
                page = context.new_page()
                _sign_in(page, server, STUDENT)
                page.wait_for_load_state("networkidle")
                page.goto(f"{server}/problems/yoyo")
                page.fill("#input-tension", "m*g")          # the scene's feedback: "... $T$ ... $mg$."
                page.fill("#input-acceleration", "g/2")     # no feedback: a counterexample
                page.click("text=Submit for grading")
                page.wait_for_url("**/problems/yoyo#answers")
                if round_:  # the same texts again: the same attempts, said so, and no new row in the history
                    assert "not counted as another attempt" in page.locator(".flash").inner_text()
                for answer in ("tension", "acceleration"):
                    page.locator(f"#answer-{answer} .verdict .badge.incorrect").wait_for(timeout=90_000)
                tension = page.locator("#answer-tension .verdict")
                assert tension.locator(".feedback math").count() == 2, tension.inner_html()  # T and mg
                assert tension.locator(".feedback li").count() == 1  # the instructor's line; no second guess
                assert "less than its weight" in tension.inner_text()
                point = page.locator("#answer-acceleration .verdict .point")
                assert point.locator("math").count() >= 1 and "your answer gives" in point.inner_text()
                for verdict in (tension, page.locator("#answer-acceleration .verdict")):
                    said = verdict.inner_text()
                    assert "$" not in said and "ball arithmetic" not in said and "counterexample" not in said
                history = page.locator("#history + .table-wrap tbody tr")
                assert history.count() == 2  # two attempts, however often they were sent
                assert history.first.locator("td").nth(1).locator("math").count() >= 1  # the prompt's $T$
                problems += _page_problems(page, axe, f"problem page ({width}px)", f"h12-student-verdicts-{width_name}")

                # An answer the grader cannot read: shown at its input, with the caret, and not an attempt.
                page.fill("#input-angular_acceleration", "2*g/(3*R")
                page.click("text=Submit for grading")
                page.locator("#preview-angular_acceleration .caret").wait_for(timeout=30_000)
                assert "at character 5" in page.locator("#preview-angular_acceleration").inner_text()  # the "("
                problems += _page_problems(page, axe, f"unreadable answer ({width}px)", f"h12-student-unreadable-"
                                                                                         f"{width_name}")
                page.goto(f"{server}/problems/yoyo")
                assert page.locator("#history + .table-wrap tbody tr").count() == 2

                page.locator("#history + .table-wrap tbody tr a").first.click()
                page.wait_for_url("**/submissions/*")
                assert page.locator("h1 math").count() >= 1  # "Attempt: Acceleration ..." or "Tension $T$ ..."
                problems += _page_problems(page, axe, f"attempt page ({width}px)", f"h12-student-attempt-{width_name}")
                context.close()

                context = browser.new_context(viewport={"width": width, "height": 900}, bypass_csp=True)
                page = context.new_page()
                _sign_in(page, server, INSTRUCTOR)
                page.wait_for_load_state("networkidle")
                page.goto(f"{server}/instructor/problems/yoyo/review")
                headings = page.locator(".derivation li > strong")
                titles = [headings.nth(i).inner_text() for i in range(headings.count())]
                # MathML's italic letters read back as mathematical italic: 𝜃 for θ, 𝜕 for ∂.
                assert any({"θ", "𝜃"} & set(t) for t in titles) and any({"∂", "𝜕"} & set(t) for t in titles), titles
                assert page.locator(".derivation li > strong math").count() >= 3  # s, θ and Q = λ ∂f/∂q
                # The constraint's name as one upright word, not a product of italic letters.
                assert page.locator(".derivation msub > mtext", has_text="unwind").count() > 0
                problems += _page_problems(page, axe, f"review page ({width}px)", f"h12-instructor-review-{width_name}")
                context.close()
        finally:
            browser.close()
    assert problems == [], json.dumps(problems, indent=1, ensure_ascii=False)
