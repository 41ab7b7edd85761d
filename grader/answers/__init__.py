"""Checking student answers: (reference, answer, variables, kind) -> `Verdict`.

``check`` parses with our whitelist grammar (never ``eval``), checks dimensions, decides
equivalence (symbolic when cheap, else ball arithmetic at sample points of the variables'
domains) and explains wrong answers. ``grader.answers.sandbox`` runs it under hard limits.
"""

from grader.answers.verdict import Verdict

__all__ = ["check", "Verdict"]


def __getattr__(name):
    # ``check`` pulls in sympy and the parser; the sandbox's parent only needs `Verdict`.
    if name == "check":
        from grader.answers.checker import check

        return check
    raise AttributeError(name)
