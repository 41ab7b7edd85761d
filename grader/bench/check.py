"""``grader bench check``: verdict accuracy and latency of the answer checker on the labelled corpus.

In one run:

1. our checker, in process, on every corpus item: wrong verdicts, p50/p99 latency;
2. the same through the sandbox (what ``grader check --jsonl`` and the grading worker do), with the
   slowest hostile input;
3. the naive baseline on the same items (sympy's ``parse_expr`` + ``simplify(a - b) == 0``), in a
   killable child process with a per-item timeout, and the ratio of the medians. The baseline
   executes its input (that is what ``parse_expr`` does), so it never sees the hostile items. On
   the textbook scenes' answers it also runs on the answers written in its own notation
   (`in_sympy_notation`), so that its time is that of its ``simplify``, not of a quick refusal;
4. what accuracy costs: error rate and latency as the number of spot points and the working
   precision change (float64 at WeBWorK's tolerance, float64 tight, mpmath at 30 digits, ball
   arithmetic), as a table and a PNG plot.

Figures go to ``bench-results/check.json`` and ``bench-results/check-precision.png``.
"""

from __future__ import annotations

import json
import multiprocessing
import statistics
import time
import warnings
from pathlib import Path

import click

DEFAULT_CORPUS = Path("tests/answers/corpus")
# A numeric answer's request also carries the student's numbers, the unit asked and the tolerance.
NUMERIC_KEYS = ("values", "unit", "tolerance", "dimension", "implicit")


def load_corpus(folder: Path) -> list[dict]:
    """All labelled items of the corpus folder (``*.jsonl``), in file order."""
    items = []
    for path in sorted(Path(folder).glob("*.jsonl")):
        with open(path, encoding="utf-8") as f:
            items.extend(json.loads(line) for line in f if line.strip())
    return items


def _percentile(values: list[float], q: float) -> float:
    if not values:
        return float("nan")
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


def _run_ours(items, options=None, budget_s=2.0, clock=time.perf_counter, cold=False, forget=False):
    """Check every item; ``clock`` times it (``time.thread_time``: CPU time, robust on a busy machine),
    ``cold`` empties sympy's cache and the parser's memory before each check (a new answer: nothing
    of it built before), ``forget`` only the parser's memory of texts."""
    from sympy.core.cache import clear_cache

    from grader.answers.checker import DEFAULT_OPTIONS, check
    from grader.expressions.parser import forget_parses

    results = []
    for item in items:
        if cold:
            clear_cache()
        if cold or forget:
            forget_parses()
        started = clock()
        verdict = check(item["reference"], item["answer"], item["variables"], kind=item["kind"],
                        feedback=item.get("feedback"), state=item.get("state"), budget_s=budget_s,
                        options=options or DEFAULT_OPTIONS, alternatives=item.get("alternatives"),
                        **{k: item[k] for k in NUMERIC_KEYS if k in item})
        ms = (clock() - started) * 1000
        results.append({"id": item["id"], "verdict": verdict.verdict, "ms": ms,
                        "codes": [f["code"] for f in verdict.feedback]})
    return results


MEASURES = (
    ("new_answer", "new answer, warm worker"),
    ("steady", "answer text seen before"),
    ("first_sight", "first sight (sympy cache empty)"),
)


def _prepare_references(items, options) -> None:
    """Prepare every reference as a running worker has (each checked once against ``0``), without
    parsing any of the answers."""
    for item in items:
        _run_ours([{**item, "answer": "0"}], options)


def _textbook(items, baseline: dict | None, sympy_notation: dict | None = None) -> dict:
    """Before/after on the textbook scenes' answers, in CPU time, with identical verdicts required.

    "before" is ``Options(fast=False)`` (the older evaluation paths) with every text parsed afresh,
    "after" the default, with the parser's memory of texts. Each mode starts from an empty sympy
    cache and parser memory, and is measured three ways:

    - ``new_answer``: every reference prepared, each answer checked for the first time (the parser
      has not seen its text; sympy's cache holds what the references and the earlier answers
      built): a grading worker receiving a new answer, the measure that counts;
    - ``steady``: the same answers a second time (the parser remembers the text in "after"), a
      class typing the same few forms;
    - ``first_sight``: sympy's cache emptied before every check, nothing of the answer built before.

    ``baseline`` is the naive checker on the texts as typed, ``sympy_notation`` on the same
    answers written in its own notation (`in_sympy_notation`): the ratio that measures its work.
    """
    from sympy.core.cache import clear_cache

    from grader.answers.equivalence import Options
    from grader.expressions.parser import forget_parses

    modes = {"before": Options(fast=False), "after": Options()}
    figures: dict = {"items": len(items)}
    verdicts = {}
    for name, options in modes.items():
        forget = name == "before"
        clear_cache()
        forget_parses()
        _prepare_references(items, options)
        new = _run_ours(items, options, clock=time.thread_time, forget=True)
        _run_ours(items, options, forget=forget)  # forget=True above kept no text in the parser's memory
        steady = _run_ours(items, options, clock=time.thread_time, forget=forget)
        cold = _run_ours(items, options, clock=time.thread_time, cold=True)
        runs = {"new_answer": new, "steady": steady, "first_sight": cold}
        verdicts[name] = [r["verdict"] for run in runs.values() for r in run]
        figures[name] = {measure: _summary(items, run) for measure, run in runs.items()}
    figures["identical_verdicts"] = verdicts["before"] == verdicts["after"]
    for measure, _ in MEASURES:
        figures[f"speedup_{measure}"] = (figures["before"][measure]["p50_ms"]
                                         / figures["after"][measure]["p50_ms"])
    for label, runs in (("baseline", baseline), ("baseline_sympy_notation", sympy_notation)):
        if not runs:
            continue
        base = [runs[i["id"]] for i in items if i["id"] in runs]
        figures[label] = _summary([i for i in items if i["id"] in runs], base)
        figures[label]["cpu_p50_ms"] = _percentile([r["cpu_ms"] for r in base], 0.5)
        figures[label]["timeouts"] = sum(r["verdict"] == "timeout" for r in base)
        for measure, _ in MEASURES:
            figures[label][f"ratio_{measure}"] = (figures[label]["cpu_p50_ms"]
                                                  / figures["after"][measure]["p50_ms"])
    return figures


def in_sympy_notation(item: dict) -> dict:
    """``item`` with its answer written in sympy's own notation, as our parser read it.

    The naive baseline cannot read θ̇₁, ℓ, ``sin²x`` or implicit products with a function, and
    fails at once on them; timing that would measure how fast it gives up, not what its
    ``simplify`` costs. Given the same formula in a notation it reads, it does its real work. An
    answer our parser refuses is left as typed.

    Examples
    --------
    >>> item = {"reference": "m*g", "answer": "m g cos²θ", "kind": "expression",
    ...         "variables": {"m": {"dimension": "mass", "domain": "positive"},
    ...                       "g": {"dimension": "acceleration", "domain": "positive"},
    ...                       "theta": {"dimension": "angle", "domain": "real"}}}
    >>> in_sympy_notation(item)["answer"]
    'g*m*cos(theta)**2'
    """
    from grader.answers.checker import _namespace, _read
    from grader.expressions.errors import ExpressionError

    try:
        _, parsed, _ = _read(item["answer"], _namespace(item["variables"]), item["kind"])
    except (ExpressionError, ValueError, TypeError, KeyError):
        return item
    return {**item, "answer": parsed["text"]}


def _summary(items, results) -> dict:
    wrong = [(i["id"], i["expected"], r["verdict"]) for i, r in zip(items, results) if r["verdict"] != i["expected"]]
    ms = [r["ms"] for r in results]
    return {
        "items": len(items),
        "wrong": len(wrong),
        "accuracy": 1 - len(wrong) / len(items) if items else float("nan"),
        "p50_ms": _percentile(ms, 0.5),
        "p99_ms": _percentile(ms, 0.99),
        "max_ms": max(ms) if ms else float("nan"),
        "wrong_items": wrong[:50],
    }


# -- the naive baseline ---------------------------------------------------------------------------


def _baseline_verdict(item: dict) -> str:
    """What a naive checker says: sympy's parser and ``simplify(a - b) == 0``."""
    import sympy
    from sympy.parsing.sympy_parser import (
        convert_xor,
        implicit_multiplication_application,
        parse_expr,
        standard_transformations,
    )

    from grader.expressions import parse_domain

    transformations = standard_transformations + (implicit_multiplication_application, convert_xor)
    assumptions = {"positive": {"positive": True}, "nonnegative": {"nonnegative": True}}
    local = {}
    for name, spec in item["variables"].items():
        domain = spec.get("domain", "real")
        kw = assumptions.get(domain, {"real": True}) if isinstance(domain, str) else (
            {"positive": True} if parse_domain(domain).lo > 0 else {"real": True})  # ends may be "pi/2"
        local[name] = sympy.Symbol(name, **kw)

    def read(text):
        # parse_expr compiles the text as Python: "{x}(…)" prints a SyntaxWarning, which is its verdict's
        # business, not the table's
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SyntaxWarning)
            return parse_expr(text, local_dict=local, transformations=transformations)

    try:
        if item["kind"] == "expression":
            diff = read(item["answer"]) - read(item["reference"])
            return "equivalent" if sympy.simplify(diff) == 0 else "not_equivalent"

        def residuals(text):
            out = []
            for part in text.replace("\n", ";").split(";"):
                if part.strip():
                    lhs, _, rhs = part.replace("==", "=").partition("=")
                    out.append(read(lhs) - read(rhs or "0"))
            return out

        ref, ans = residuals(item["reference"]), residuals(item["answer"])
        if len(ref) != len(ans):
            return "not_equivalent"
        state = {local[n] for n, s in item["variables"].items() if s.get("kind")} or {
            local[n] for n in local if n.endswith("dot") or f"{n}dot" in local}
        for r, a in zip(ref, ans):
            ratio = sympy.simplify(a / r)
            if ratio == 0 or ratio.free_symbols & state or ratio.has(sympy.zoo, sympy.nan):
                return "not_equivalent"
        return "equivalent"
    except Exception:
        return "invalid"


def _baseline_worker(connection) -> None:
    from sympy.core.cache import clear_cache

    clear_cache()  # start cold, as our checker did: the fork inherited the cache our run filled
    while True:
        item = connection.recv()
        if item is None:
            return
        started, cpu = time.perf_counter(), time.thread_time()
        verdict = _baseline_verdict(item)
        connection.send((verdict, (time.perf_counter() - started) * 1000, (time.thread_time() - cpu) * 1000))


class _Baseline:
    """The baseline in a forked child, killed and restarted when an item overruns its timeout."""

    def __init__(self, timeout_s: float):
        self.timeout_s = timeout_s
        self._context = multiprocessing.get_context("fork")
        self._start()

    def _start(self):
        self._parent, child = self._context.Pipe()
        self._process = self._context.Process(target=_baseline_worker, args=(child,), daemon=True)
        self._process.start()

    def run(self, item: dict) -> tuple[str, float, float]:
        """(verdict, wall ms, CPU ms), timed inside the worker like ours (no pipe overhead)."""
        started = time.perf_counter()
        self._parent.send(item)
        if self._parent.poll(self.timeout_s):
            return self._parent.recv()
        self._process.kill()
        self._process.join()
        self._start()
        ms = (time.perf_counter() - started) * 1000
        return "timeout", ms, ms

    def close(self):
        try:
            self._parent.send(None)
        except OSError:
            pass
        self._process.join(1)
        if self._process.is_alive():
            self._process.kill()


def _run_baseline(items: list[dict], timeout_s: float) -> list[dict]:
    """The naive baseline on every item, in one killable child."""
    baseline = _Baseline(timeout_s)
    try:
        results = []
        for item in items:
            verdict, ms, cpu_ms = baseline.run(item)
            results.append({"id": item["id"], "verdict": verdict, "ms": ms, "cpu_ms": cpu_ms, "codes": []})
    finally:
        baseline.close()
    return results


# -- the run -------------------------------------------------------------------------------------

SWEEP_METHODS = [
    ("float64, tol 1e-3 (WeBWorK)", {"method": "float64", "tolerance": 1e-3}),
    ("float64, tol 1e-9", {"method": "float64", "tolerance": 1e-9}),
    ("mpmath 30 digits, tol 1e-20", {"method": "mpmath", "digits": 30, "tolerance": 1e-20}),
    ("arb balls, adaptive (ours)", {"method": "arb"}),
]
SWEEP_POINTS = [1, 2, 4, 8, 16]


def _sweep(items) -> list[dict]:
    from grader.answers.equivalence import Options

    rows = []
    for label, settings in SWEEP_METHODS:
        for points in SWEEP_POINTS:
            options = Options(points=points, symbolic=False, **settings)
            results = _run_ours(items, options)
            s = _summary(items, results)
            rows.append({"method": label, "points": points, "error_rate": 1 - s["accuracy"], "wrong": s["wrong"],
                         "p50_ms": s["p50_ms"], "p99_ms": s["p99_ms"]})
    return rows


def _plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for label, _ in SWEEP_METHODS:
        mine = [r for r in rows if r["method"] == label]
        xs = [r["points"] for r in mine]
        left.plot(xs, [100 * r["error_rate"] for r in mine], marker="o", label=label)
        right.plot(xs, [r["p50_ms"] for r in mine], marker="o", label=label)
    left.set(xscale="log", xlabel="spot points", ylabel="wrong verdicts (%)", title="Accuracy")
    right.set(xscale="log", yscale="log", xlabel="spot points", ylabel="median check (ms)", title="Latency")
    for ax in (left, right):
        ax.set_xticks(SWEEP_POINTS, [str(p) for p in SWEEP_POINTS])
        ax.grid(True, alpha=0.3)
    left.legend(fontsize=8)
    fig.suptitle("What accuracy costs: spot points x working precision (numeric judge only, no symbolic step)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


@click.command("check")
@click.option("--corpus", type=click.Path(exists=True, file_okay=False, path_type=Path), default=DEFAULT_CORPUS,
              show_default=True)
@click.option("--out", type=click.Path(file_okay=False, path_type=Path), default=Path("bench-results"),
              show_default=True)
@click.option("--baseline-timeout", type=float, default=5.0, show_default=True,
              help="Per-item timeout of the naive baseline, seconds.")
@click.option("--no-baseline", is_flag=True, help="Skip the naive baseline.")
@click.option("--no-sweep", is_flag=True, help="Skip the points x precision sweep.")
def bench_check(corpus: Path, out: Path, baseline_timeout: float, no_baseline: bool, no_sweep: bool) -> None:
    """Accuracy and latency of `grader check` on the labelled corpus, against the naive baseline."""
    from grader.answers.sandbox import SandboxedChecker

    items = load_corpus(corpus)
    if not items:
        raise click.ClickException(f"no corpus items in {corpus}")
    out.mkdir(parents=True, exist_ok=True)
    hostile = [i for i in items if "hostile" in i["tags"]]
    benign = [i for i in items if "hostile" not in i["tags"]]
    # The naive baseline and the precision sweep judge expressions: numeric answers (a number with a
    # unit, no symbolic judge) are left out of both, explicitly.
    symbolic = [i for i in benign if i["kind"] != "numeric"]
    typical = [i for i in items if "typical" in i["tags"]]
    click.echo(f"corpus: {len(items)} items ({len(benign)} answers, {len(hostile)} hostile inputs) from {corpus}")

    _run_ours(items[:30])  # warm-up: imports, sympy's caches, first compilations
    ours = _run_ours(items)
    by_id = {r["id"]: r for r in ours}
    figures: dict = {"corpus": {"items": len(items), "hostile": len(hostile), "typical": len(typical)}}
    figures["ours"] = _summary(items, ours)
    figures["ours_typical"] = _summary(typical, [by_id[i["id"]] for i in typical])
    figures["ours_benign"] = _summary(benign, [by_id[i["id"]] for i in benign])
    expected_feedback = [i for i in items if i.get("expect_feedback")]
    missed = [i["id"] for i in expected_feedback if i["expect_feedback"] not in by_id[i["id"]]["codes"]]
    figures["feedback"] = {"expected": len(expected_feedback), "missed": len(missed), "missed_items": missed}

    with SandboxedChecker(budget_s=2.0) as box:
        sandboxed = []
        for item in items:
            request = {k: item[k] for k in ("reference", "answer", "variables", "kind") if k in item}
            for k in ("feedback", "state", "alternatives", *NUMERIC_KEYS):
                if k in item:
                    request[k] = item[k]
            started = time.perf_counter()
            reply = box.run(request)
            sandboxed.append({"id": item["id"], "verdict": reply.get("verdict"),
                              "ms": (time.perf_counter() - started) * 1000, "codes": []})
        figures["sandbox"] = _summary(items, sandboxed)
        host = [r for i, r in zip(items, sandboxed) if "hostile" in i["tags"]]
        figures["sandbox"]["hostile_max_ms"] = max(r["ms"] for r in host) if host else 0.0
        figures["sandbox"]["restarts"] = box.restarts

    if not no_baseline:
        base = _run_baseline(symbolic, baseline_timeout)
        figures["baseline"] = _summary(symbolic, base)
        figures["baseline"]["timeouts"] = sum(r["verdict"] == "timeout" for r in base)
        figures["baseline"]["timeout_s"] = baseline_timeout
        ours_symbolic = _summary(symbolic, [by_id[i["id"]] for i in symbolic])
        figures["speedup_median"] = figures["baseline"]["p50_ms"] / ours_symbolic["p50_ms"]
        baseline_by_id = {r["id"]: r for r in base}
    else:
        baseline_by_id = None

    textbook = [i for i in benign if "textbook" in i["tags"]]
    if textbook:
        transliterated = None
        if not no_baseline:
            transliterated = {r["id"]: r for r in _run_baseline([in_sympy_notation(i) for i in textbook],
                                                                 baseline_timeout)}
        figures["textbook"] = _textbook(textbook, baseline_by_id, transliterated)

    if not no_sweep:
        figures["sweep"] = _sweep(symbolic)
        _plot(figures["sweep"], out / "check-precision.png")

    (out / "check.json").write_text(json.dumps(figures, indent=2, default=str))
    _print(figures, out)


def _print(f: dict, out: Path) -> None:
    def row(name, s, extra=""):
        click.echo(f"{name:34s} {s['items']:6d} {s['wrong']:6d} {100 * s['accuracy']:8.2f}% "
                   f"{s['p50_ms']:9.2f} {s['p99_ms']:9.2f} {s['max_ms']:9.1f} {extra}")

    click.echo("")
    click.echo(f"{'checker':34s} {'items':>6s} {'wrong':>6s} {'accuracy':>9s} {'p50 ms':>9s} {'p99 ms':>9s} {'max ms':>9s}")
    row("ours (all items)", f["ours"])
    row("ours (typical answers)", f["ours_typical"])
    row("ours (answers, no hostile)", f["ours_benign"])
    row("ours via sandbox (all items)", f["sandbox"],
        f"hostile max {f['sandbox']['hostile_max_ms']:.0f} ms, restarts {f['sandbox']['restarts']}")
    if "baseline" in f:
        row("naive baseline (no hostile)", f["baseline"],
            f"timeouts {f['baseline']['timeouts']} (at {f['baseline']['timeout_s']:g} s)")
        click.echo(f"median speed-up over the baseline: {f['speedup_median']:.0f}x")
    click.echo(f"feedback: {f['feedback']['expected'] - f['feedback']['missed']}/{f['feedback']['expected']} "
               "expected feedback codes given")
    if "textbook" in f:
        t = f["textbook"]
        click.echo("")
        click.echo(f"textbook scenes' answers ({t['items']} items), CPU ms per check, before/after in this run "
                   f"(identical verdicts: {'yes' if t['identical_verdicts'] else 'NO'}):")
        click.echo(f"{'measure':34s} {'before p50':>10s} {'after p50':>10s} {'after p99':>10s} {'speed-up':>9s}"
                   f" {'wrong':>6s}")
        for measure, label in MEASURES:
            b, a = t["before"][measure], t["after"][measure]
            click.echo(f"{label:34s} {b['p50_ms']:10.3f} {a['p50_ms']:10.3f} {a['p99_ms']:10.2f} "
                       f"{t['speedup_' + measure]:8.2f}x {a['wrong']:6d}")
        for label, what in (("baseline", "as typed"), ("baseline_sympy_notation", "in sympy's notation")):
            if label in t:
                b = t[label]
                click.echo(f"naive baseline, answers {what}: CPU p50 {b['cpu_p50_ms']:.2f} ms, {b['wrong']} wrong, "
                           f"{b['timeouts']} timeouts; ours is "
                           + ", ".join(f"{b['ratio_' + m]:.0f}x ({label})" for m, label in MEASURES))
    if f["ours"]["wrong_items"]:
        click.echo("wrong verdicts (ours): " + ", ".join(f"{i} (expected {e}, got {g})" for i, e, g in f["ours"]["wrong_items"]))
    if "sweep" in f:
        click.echo("")
        click.echo("what accuracy costs (numeric judge alone, answers without hostile input):")
        click.echo(f"{'method':32s} {'points':>6s} {'wrong':>6s} {'error %':>8s} {'p50 ms':>8s} {'p99 ms':>8s}")
        for r in f["sweep"]:
            click.echo(f"{r['method']:32s} {r['points']:6d} {r['wrong']:6d} {100 * r['error_rate']:8.2f} "
                       f"{r['p50_ms']:8.2f} {r['p99_ms']:8.2f}")
    click.echo(f"\nfigures: {out / 'check.json'}" + (f", {out / 'check-precision.png'}" if "sweep" in f else ""))
