"""Question tests: the instructor's example answers and the verdict each must get.

A scene file lists, per answer, ``[[answers.tests]] answer = "...", expect = "equivalent" |
"not_equivalent" | "invalid"`` (and ``score`` for partial credit, ``values`` for the parameter values
of a numeric answer). They run when the problem is registered (``grader.jobs.derivation``), with the
checker that will grade the students, so a reference the instructor did not mean, a feedback entry
that never matches or a tolerance that is too tight shows up before any student sees the problem: a
failing test stops the registration, with what the grader said.
"""

from __future__ import annotations

from typing import Any, Iterable, Mapping

from grader.answers.checker import check_request
from grader.answers.numeric import NumericRequestError, reference_value
from grader.answers.randomised import PREVIEW_SEED, draw_parameters
from grader.answers.reference import ReferenceAnswer
from grader.answers.verdict import points

__all__ = ["QuestionTestFailure", "failure_report", "require_passing", "run_question_tests"]

TEST_BUDGET_S = 2.0


class QuestionTestFailure(ValueError):
    """Some question tests failed; the message lists them with the grader's verdicts."""


def run_question_tests(references: Iterable[Mapping[str, Any] | ReferenceAnswer],
                       budget_s: float = TEST_BUDGET_S) -> list[dict[str, Any]]:
    """Run every reference answer's tests; one result per test, in file order.

    Each result is ``{"answer_name", "answer", "expect", "expected_score"?, "got", "score",
    "passed", "reason", "feedback"}``: ``got`` is the grader's verdict, ``score`` the points it
    earns (`grader.answers.verdict.points`), ``feedback`` the messages a student would see.

    Examples
    --------
    >>> ref = {"name": "w", "prompt": "Weight", "kind": "expression", "reference": "g*m",
    ...        "variables": {"m": {"dimension": "kg", "domain": "positive"},
    ...                      "g": {"dimension": "m*s^-2", "domain": "positive"}},
    ...        "dimension": "kg*m*s^-2", "latex": "", "tests": [{"answer": "m g", "expect": "equivalent"},
    ...                                                          {"answer": "m", "expect": "equivalent"}]}
    >>> [(r["got"], r["passed"]) for r in run_question_tests([ref])]
    [('equivalent', True), ('not_equivalent', False)]
    """
    results = []
    for data in references:
        reference = data if isinstance(data, ReferenceAnswer) else ReferenceAnswer.from_json(data)
        for test in reference.tests:
            values = None
            if reference.kind == "numeric":
                values = {**draw_parameters(reference.parameters, PREVIEW_SEED), **(test.get("values") or {})}
            request = {**reference.request(test["answer"], values), "budget_s": budget_s}
            verdict = check_request(request)
            earned = points(verdict)
            passed = verdict["verdict"] == test["expect"]
            if test.get("score") is not None:
                passed = passed and abs(earned - float(test["score"])) < 1e-9
            result = {"answer_name": reference.name, "answer": test["answer"], "expect": test["expect"],
                      "got": verdict["verdict"], "score": earned, "passed": passed, "reason": verdict["reason"],
                      "feedback": [item.get("message", "") for item in verdict.get("feedback") or []]}
            if test.get("score") is not None:
                result["expected_score"] = float(test["score"])
            if values is not None:
                result["values"] = values
                try:  # what the grader expected at these numbers: the instructor may see it
                    result["expected_value"] = reference_value(reference.reference, reference.variables, values,
                                                               reference.implicit)
                except (NumericRequestError, ValueError):
                    pass
            results.append(result)
    return results


def failure_report(results: Iterable[Mapping[str, Any]]) -> str:
    """One line per failed test: what was expected and what the grader said."""
    lines = []
    for r in results:
        if r["passed"]:
            continue
        wanted = r["expect"] + (f" with score {r['expected_score']:g}" if "expected_score" in r else "")
        said = f"{r['got']} (score {r['score']:g}): {r['reason']}"
        if "expected_value" in r:
            said += f" (expected {r['expected_value']:.6g} in SI units at {r['values']})"
        if r["feedback"]:
            said += f"; feedback: {' / '.join(r['feedback'])}"
        lines.append(f"answers ({r['answer_name']}): test {r['answer']!r} expects {wanted}, the grader said {said}")
    return "\n".join(lines)


def require_passing(results: list[dict[str, Any]], source: str = "scene") -> list[dict[str, Any]]:
    """``results`` if every test passed; else raises :class:`QuestionTestFailure` naming the failures."""
    report = failure_report(results)
    if report:
        failed = sum(not r["passed"] for r in results)
        raise QuestionTestFailure(f"{source}: {failed} of {len(results)} question tests failed, so the problem "
                                  f"cannot be published:\n{report}")
    return results
