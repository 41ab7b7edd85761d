"""`grader check --jsonl`: one verdict line per request line, malformed lines included."""

import json

from click.testing import CliRunner

from grader.cli.check import check

VARIABLES = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"}}


def test_jsonl_round_trip_with_malformed_lines():
    lines = [
        json.dumps({"reference": "m*g/3", "answer": "mg/3", "variables": VARIABLES}),
        "this is not json",
        json.dumps([1, 2]),
        json.dumps({"reference": "m*g/3", "answer": "__import__('os')", "variables": VARIABLES}),
        json.dumps({"reference": "m*g/3", "answer": "m*g/2", "variables": VARIABLES, "kind": "expression"}),
    ]
    result = CliRunner().invoke(check, ["--jsonl"], input="\n".join(lines) + "\n")
    assert result.exit_code == 0, result.output
    replies = [json.loads(line) for line in result.output.splitlines()]
    assert [r["verdict"] for r in replies] == ["equivalent", "invalid", "invalid", "invalid", "not_equivalent"]
    assert "not JSON" in replies[1]["reason"]
    assert all({"verdict", "certainty", "reason", "parsed", "counterexample", "feedback", "ms"} <= set(r) for r in replies)


def test_single_check_from_options():
    result = CliRunner().invoke(check, ["--reference", "m*g/3", "--answer", "g m/3", "--var", "m=mass:positive",
                                        "--var", "g=acceleration:positive", "--no-sandbox"])
    assert result.exit_code == 0 and '"equivalent"' in result.output


def test_a_batch_continues_past_a_lone_surrogate_and_a_line_that_is_not_utf8():
    lines = [
        json.dumps({"reference": "m*g", "answer": "m g\ud800", "variables": VARIABLES}).encode(),
        b"\xff\xfe{}",
        json.dumps({"reference": "m*g", "answer": "g m", "variables": VARIABLES}).encode(),
    ]
    result = CliRunner().invoke(check, ["--jsonl"], input=b"\n".join(lines) + b"\n")
    assert result.exit_code == 0, result.output
    replies = [json.loads(line) for line in result.output.splitlines()]
    assert [r["verdict"] for r in replies] == ["invalid", "invalid", "equivalent"]
    assert replies[0]["parsed"]["text"] == "m g\ud800" and "not UTF-8" in replies[1]["reason"]
