"""`grader bench gradebook`: it fills a course, serves its gradebook as JSON and CSV, and writes figures."""

import json

from click.testing import CliRunner

from grader.bench.gradebook import bench_gradebook


def test_the_benchmark_times_both_formats_over_every_row(tmp_path):
    out = tmp_path / "gradebook.json"
    result = CliRunner().invoke(bench_gradebook, ["--students", "4", "--problems", "2", "--attempts", "2",
                                                  "--repeat", "1", "--out", str(out)])
    assert result.exit_code == 0, result.output
    rows = json.loads(out.read_text())
    assert [(r["format"], r["rows"], r["submissions"]) for r in rows] == [("json", 8, 32), ("csv", 8, 32)]
