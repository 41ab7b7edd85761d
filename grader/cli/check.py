"""``grader check``: check answers, one JSON request per line, in one sandboxed process."""

from __future__ import annotations

import json
import sys

import click

EXAMPLE = (
    '{"reference": "m*g/3", "answer": "mg/3", "kind": "expression", '
    '"variables": {"m": {"dimension": "mass", "domain": "positive"}, '
    '"g": {"dimension": "acceleration", "domain": "positive"}}}'
)


def _variable(spec: str) -> tuple[str, dict]:
    """``name=dimension[:domain]`` -> (name, {"dimension", "domain"})."""
    name, _, rest = spec.partition("=")
    dimension, _, domain = rest.partition(":")
    if not name or not dimension:
        raise click.BadParameter(f"expected name=dimension[:domain], got {spec!r}")
    return name.strip(), {"dimension": dimension.strip(), "domain": domain.strip() or "real"}


@click.command()
@click.option("--jsonl", is_flag=True, help="Read JSON requests, one per line, and write one verdict line each.")
# Bytes, decoded line by line: a line that is not UTF-8 gets its own verdict instead of ending the batch.
@click.argument("source", type=click.File("rb"), default="-")
@click.option("--reference", help="Reference answer (without --jsonl).")
@click.option("--answer", help="Student answer (without --jsonl).")
@click.option("--var", "variables", multiple=True, help="A variable: name=dimension[:domain], e.g. m=mass:positive.")
@click.option("--kind", type=click.Choice(["expression", "equation"]), default="expression")
@click.option("--budget", type=float, default=2.0, show_default=True, help="Wall-clock budget per answer, seconds.")
@click.option("--memory-mb", type=int, default=1024, show_default=True, help="Memory cap of the checker process.")
@click.option("--no-sandbox", is_flag=True, help="Check in this process (no hard limits; for debugging).")
def check(jsonl, source, reference, answer, variables, kind, budget, memory_mb, no_sandbox):
    """Check student answers against references.

    \b
    With --jsonl, reads SOURCE (default stdin), one request per line:
      {"reference", "answer", "variables": {name: {"dimension", "domain"}},
       "kind": "expression"|"equation"|"numeric", "feedback"?: [{"expr", "message", "score"?}],
       "state"?: [names], "feedback_detail"?: "kind"|"full",
       numeric only: "values": {name: number}, "unit": "N", "tolerance"?: {...}, "dimension"?,
       "implicit"?: {"condition", "unknown", "interval": [lo, hi], "root"}}
    and writes one line per request:
      {"verdict", "certainty", "reason", "parsed", "counterexample", "feedback", "ms", "score"?, ...}
    A line that is not UTF-8, not JSON or not an object gets an "invalid" line of its own; the
    batch goes on. Every check runs in a sandboxed child process with a hard time and memory limit.
    """
    runner = _runner(budget, memory_mb, no_sandbox)
    try:
        if jsonl:
            _jsonl(source, runner, budget)
            return
        if reference is None or answer is None:
            raise click.UsageError(f"give --jsonl, or --reference and --answer; a request line looks like:\n{EXAMPLE}")
        request = {"reference": reference, "answer": answer, "kind": kind,
                   "variables": dict(_variable(v) for v in variables), "budget_s": budget}
        result = runner(request)
        click.echo(_dumps(result, indent=2))
        sys.exit(0 if result.get("verdict") == "equivalent" else 1)
    finally:
        close = getattr(runner, "close", None)
        if close:
            close()


def _runner(budget: float, memory_mb: int, no_sandbox: bool):
    if no_sandbox:
        from grader.answers.checker import check_request

        return check_request
    from grader.answers.sandbox import SandboxedChecker

    box = SandboxedChecker(budget_s=budget, memory_mb=memory_mb)

    def run(request):
        return box.run(request)

    run.close = box.close
    return run


def _dumps(result: dict, indent: int | None = None) -> str:
    """JSON for stdout: readable Unicode, but escapes where a text cannot be encoded (a lone surrogate)."""
    text = json.dumps(result, ensure_ascii=False, indent=indent)
    try:
        text.encode(sys.stdout.encoding or "utf-8")
    except (UnicodeEncodeError, LookupError):
        text = json.dumps(result, indent=indent)
    return text


def _jsonl(source, runner, budget: float) -> None:
    out = sys.stdout
    for number, raw in enumerate(source, 1):
        result = _line_result(number, raw, runner, budget)
        if result is not None:
            out.write(_dumps(result) + "\n")
            out.flush()


def _line_result(number: int, raw: bytes, runner, budget: float) -> dict | None:
    """The verdict for one input line (None for a blank line); a bad line gets an ``invalid`` one."""
    from grader.answers.verdict import Verdict

    try:
        line = raw.decode("utf-8")
    except UnicodeDecodeError as error:
        return Verdict.invalid(f"malformed input line {number}: not UTF-8 (byte {error.start})").to_json()
    if not line.strip():
        return None
    try:
        request = json.loads(line)
    except ValueError as error:
        return Verdict.invalid(f"malformed input line {number}: not JSON ({error})").to_json()
    if not isinstance(request, dict):
        return Verdict.invalid(f"malformed input line {number}: expected a JSON object").to_json()
    request.setdefault("budget_s", budget)
    return runner(request)
