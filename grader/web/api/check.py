"""``POST /check``: a stateless check, exactly one line of ``grader check --jsonl``."""

from __future__ import annotations

from flask import current_app

from grader.jobs.grading import CheckersBusy
from grader.web.api import spec
from grader.web.policy import API_ROLES, Action, current_principal, require
from grader.web.api.schemas import CHECK_REQUEST, CHECK_RESULT, check_cost, read_json
from grader.web.errors import ApiProblem

ANY_ROLE = API_ROLES


@spec.route("/check", "POST", roles=ANY_ROLE, errors=(400, 413, 415, 422, 429, 503),
            rate_limit="check", cost=check_cost,
            request={"application/json": spec.schema("CheckRequest", CHECK_REQUEST)},
            responses={200: ("The verdict.", {"application/json": spec.schema("CheckResult", CHECK_RESULT)})})
def check_answer():
    """Check an answer against a reference, without storing anything.

    The check runs in a sandbox child with a hard time and memory limit; an answer that exhausts
    them gets a verdict saying so, not an error. A check costs one request of the rate limit, plus
    one per feedback item and a little for many variables or long texts.
    """
    require(current_principal(), Action.CHECK, None)
    body = read_json(CHECK_REQUEST)
    checkers = current_app.extensions["lagrade.checkers"]
    limit = current_app.config["CHECK_BUDGET_S"]
    try:
        with checkers.borrow(timeout=current_app.config["CHECK_QUEUE_TIMEOUT_S"]) as checker:
            budget = min(float(body.get("budget_s") or limit), limit)
            result = checker.run({"kind": "expression", **body, "budget_s": budget}, budget)
    except CheckersBusy:
        raise ApiProblem(503, "All checkers are busy; try again shortly.", kind="busy",
                         headers={"Retry-After": "1"}) from None
    if result.get("checker_failure"):  # the checker, not the answer, failed (its child would not start)
        raise ApiProblem(503, "The checker is unavailable; try again shortly.", kind="unavailable",
                         headers={"Retry-After": "1"})
    return result

