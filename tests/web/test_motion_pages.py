"""The simulated motion on the problem pages, in Debian's chromium: the instructor's review page always
shows it; the student's page shows it when the scene allows (the yo-yo does); the animation plays
and the pictures fit a phone's screen."""

from __future__ import annotations

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

PAGES = [(STUDENT, "/problems/yoyo"), (INSTRUCTOR, "/instructor/problems/yoyo/review")]


def test_the_motion_plays_on_both_pages_and_fits_a_phone(sync_playwright, server):
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
        try:
            for who, path in PAGES:
                for width in (1280, 390):
                    page = browser.new_page(viewport={"width": width, "height": 900})
                    _sign_in(page, server, who)
                    page.wait_for_load_state("networkidle")
                    page.goto(f"{server}{path}")
                    plot, animation = page.locator("svg.motion-plot"), page.locator("svg.motion-animation")
                    assert plot.count() == 1 and animation.count() == 1, path
                    page.wait_for_timeout(300)
                    # SMIL runs: the document's clock has advanced and the rim point has moved.
                    assert animation.evaluate("svg => svg.getCurrentTime()") > 0.1
                    moved = animation.evaluate("""svg => {
                        const dot = [...svg.querySelectorAll('circle')].pop();
                        return dot.cx.animVal.value !== dot.cx.baseVal.value || dot.cy.animVal.value !== dot.cy.baseVal.value;
                    }""")
                    assert moved, path
                    for picture in (plot, animation):
                        box = picture.bounding_box()
                        assert box["x"] >= 0 and box["x"] + box["width"] <= width + 1, (path, width, box)
                    assert "The motion" in page.locator("#motion-heading").inner_text()
                    page.close()
        finally:
            browser.close()
