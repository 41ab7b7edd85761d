"""Test-only checker factories for the Celery worker (``GRADER_CHECKER_FACTORY=celery_checkers:...``).

The worker process imports this by name, so tests put this folder on its ``PYTHONPATH``.
"""

import os
import time

from grader.jobs.grading import sandbox_checker


class _Slow:
    """The real sandboxed checker, after a pause: long enough to kill a worker mid-job."""

    def __init__(self, inner, delay_s: float):
        self.inner, self.delay_s = inner, delay_s

    def run(self, request, budget_s=None):
        time.sleep(self.delay_s)
        return self.inner.run(request, budget_s)

    def close(self):
        self.inner.close()


def slow_sandbox_checker():
    return _Slow(sandbox_checker(), float(os.environ.get("LAGRADE_TEST_CHECK_DELAY_S", "0")))
