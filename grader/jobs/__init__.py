"""The grading queue: submissions are committed first, graded by workers outside any request."""

from grader.jobs.queue import AnswerUnreadable, IdempotencyConflict, SubmissionRejected, regrade, submit, wake_workers
from grader.jobs.worker import WorkerPool

__all__ = ["AnswerUnreadable", "IdempotencyConflict", "SubmissionRejected", "WorkerPool", "regrade", "submit",
           "wake_workers"]
