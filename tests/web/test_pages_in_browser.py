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
PAGES = {
    None: ["/login"],
    STUDENT: ["/problems", "/problems/yoyo", "/courses", "/account"],
    INSTRUCTOR: ["/instructor/", "/instructor/problems/yoyo", "/instructor/problems/yoyo/review",
                 "/instructor/problems/new", "/instructor/courses", "/instructor/problems/yoyo/edit",
                 "/instructor/problems/yoyo/diff", "/instructor/problems/yoyo/regrade",
                 "/instructor/problems/yoyo/regrade/progress", "/instructor/docs/scene-format", "/account"],
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


def test_every_page_is_accessible_rendered_and_readable_on_a_phone(sync_playwright, server):
    axe = _axe_source()
    SHOTS.mkdir(exist_ok=True)
    problems: list[str] = []
    titles: dict[str, str] = {}
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
        try:
            for who, paths in PAGES.items():
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
                        where = f"{path} ({'anonymous' if who is None else who[0]}, {width}px)"
                        name = f"{(who or ('anonymous',))[0].split('@')[0]}{path.replace('/', '_')}-{width_name}"
                        page.screenshot(path=str(SHOTS / f"{name}.png"), full_page=True)
                        problems += [f"{where}: {v}" for v in _audit(page, axe)]
                        text = page.evaluate("() => document.body.innerText")
                        if "$" in text and path not in LITERAL_DOLLARS:
                            problems.append(f"{where}: raw math left unrendered: "
                                            f"{text[max(0, text.index('$') - 40):text.index('$') + 40]!r}")
                        problems += [f"{where}: table clipped on a {width}px screen: {t}"
                                     for t in page.evaluate(CLIPPED_TABLES)]
                        titles.setdefault(path, page.title())
                    context.close()
        finally:
            browser.close()
    assert problems == [], json.dumps(problems, indent=1, ensure_ascii=False)
    assert all(titles.values()) and len(set(titles.values())) == len(titles), titles  # each says where you are
