"""The ``grader`` command line.

Each subcommand lives in its own module and is imported only when it is run, so that
``grader check`` does not pay for Flask and ``grader serve`` does not pay for scipy.
"""

from __future__ import annotations

import importlib

import click

# command name -> "module:attribute" of a click command
_COMMANDS = {
    "derive": "grader.cli.derive:derive",
    "check": "grader.cli.check:check",
    "serve": "grader.cli.serve:serve",
    "db": "grader.cli.db:db",
    "token": "grader.cli.token:token",
    "simulate": "grader.cli.simulate:simulate",
    "lti": "grader.cli.lti:lti",
}
_BENCHMARKS = {
    "derive": "grader.bench.derive:bench_derive",
    "check": "grader.bench.check:bench_check",
    "http": "grader.bench.http:bench_http",
    "isolation": "grader.bench.isolation:bench_isolation",
    "accuracy": "grader.bench.accuracy:bench_accuracy",
    "load": "grader.bench.load:bench_load",
    "simulate": "grader.bench.simulate:bench_simulate",
    "gradebook": "grader.bench.gradebook:bench_gradebook",
}


def _load(target: str) -> click.Command:
    module, attribute = target.split(":")
    return getattr(importlib.import_module(module), attribute)


class _LazyGroup(click.Group):
    """A click group whose subcommands are imported on first use."""

    def __init__(self, *args, lazy: dict[str, str], **kwargs):
        super().__init__(*args, **kwargs)
        self._lazy = lazy

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(super().list_commands(ctx)) | set(self._lazy))

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        if name in self._lazy:
            return _load(self._lazy[name])
        return super().get_command(ctx, name)


@click.group(cls=_LazyGroup, lazy=_COMMANDS)
@click.version_option(package_name="lagrade")
def main() -> None:
    """lagrade: derive reference answers from scenes, check answers, serve the grader."""


@main.group(cls=_LazyGroup, lazy=_BENCHMARKS)
def bench() -> None:
    """Benchmarks: each prints a table and writes its figures to bench-results/."""
