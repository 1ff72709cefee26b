"""Cam tables as CSV files in the project: `phase,distance` with a header, one cam data point per line.

Format (docs/cams.md, decision D36):

* UTF-8 (a byte-order mark is accepted); lines end with LF or CRLF; blank lines and lines starting with `#`
  (comments) are ignored anywhere;
* the first other line is the header `phase,distance` (case and surrounding spaces ignored);
* then one point per line: two numbers separated by one comma, `.` as decimal point, no thousands separators
  (Python `float` syntax, e.g. `0.1`, `-2.5`, `1e-3`); `nan` and `inf` are refused;
* the points are the valid cam data from the start point to the end point: the first is (0, 0), phases strictly
  ascending *as REAL* (two phases that round to the same float32 are refused), at least 2 and at most 65,535;
* values are stored as REAL (float32); writing prints each value's shortest decimal that reads back to the same
  REAL (`0.1`, not `0.100000001`), so write → read is exact.

Errors are values: `CamCsvError` lists every problem found (up to `MAX_PROBLEMS`) with its 1-based line number.
"""

from __future__ import annotations

import math
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from .table import MAX_POINTS, REAL

__all__ = ["HEADER", "CamCsvError", "CsvProblem", "format_cam_csv", "parse_cam_csv", "read_cam_csv",
           "write_cam_csv"]

HEADER = "phase,distance"
MAX_PROBLEMS = 20
_REAL_MAX = float(np.finfo(REAL).max)


@dataclass(frozen=True)
class CsvProblem:
    line: int  # 1-based line number in the file (0 = the file as a whole)
    message: str

    def __str__(self) -> str:
        return f"line {self.line}: {self.message}" if self.line else self.message


class CamCsvError(ValueError):
    """A cam table CSV that cannot be read; `problems` holds each one with its line."""

    def __init__(self, problems: list[CsvProblem]) -> None:
        self.problems = problems
        super().__init__("; ".join(str(p) for p in problems))


def _clip(text: str, n: int = 60, *, quote: bool = True) -> str:
    """A field or line as an error message quotes it: at most `n` characters (a hostile file can have a 4 MB line)."""
    head = repr(text[:n]) if quote else text[:n]
    return head if len(text) <= n else f"{head}… ({len(text)} characters)"


def _number(text: str) -> float | str:
    """The value of one field, or the reason it is not a REAL."""
    t = text.strip()
    if not t:
        return "empty field"
    try:
        v = float(t)
    except ValueError:
        return f"{_clip(t)} is not a number"
    if not math.isfinite(v):
        return f"{_clip(t)} is not a finite number"
    if abs(v) > _REAL_MAX:
        return f"{_clip(t, quote=False)} is beyond the range of REAL (±3.4e38)"
    return v


def parse_cam_csv(text: str) -> tuple[np.ndarray, np.ndarray]:
    """(phase, distance) REAL arrays of a cam table CSV text; raises `CamCsvError` listing the problems."""
    problems: list[CsvProblem] = []
    phases: list[float] = []
    dists: list[float] = []
    lines: list[int] = []
    header_seen = False
    last_line = 0
    for no, raw in enumerate(text.lstrip("\ufeff").splitlines(), start=1):
        last_line = no
        if len(problems) >= MAX_PROBLEMS:
            break
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        if not header_seen:
            header_seen = True
            if [f.strip().lower() for f in line.split(",")] != HEADER.split(","):
                # Without the header the columns are unknown: report only this.
                raise CamCsvError([CsvProblem(no, f"expected the header {HEADER!r}, found {_clip(line)}")])
            continue
        fields = line.split(",")
        if len(fields) != 2:
            problems.append(CsvProblem(no, f"expected 2 values (phase,distance), found {len(fields)}"))
            continue
        values = [_number(f) for f in fields]
        bad = [f"{name}: {v}" for name, v in zip(("phase", "distance"), values, strict=True) if isinstance(v, str)]
        if bad:
            problems.append(CsvProblem(no, "; ".join(bad)))
            continue
        if len(phases) == MAX_POINTS:
            problems.append(CsvProblem(no, f"more than {MAX_POINTS} points"))
            break
        phases.append(float(values[0]))
        dists.append(float(values[1]))
        lines.append(no)
    if not header_seen:
        problems.append(CsvProblem(0, f"empty file: expected the header {HEADER!r} and the points"))
    p = np.array(phases, dtype=REAL)
    d = np.array(dists, dtype=REAL)
    if header_seen and len(p) < 2 and not problems:
        problems.append(CsvProblem(last_line, f"a cam table needs at least 2 points, found {len(p)}"))
    if len(p) and (p[0] != 0 or d[0] != 0):
        problems.append(CsvProblem(lines[0], f"the first point is the start point (0, 0), found ({phases[0]}, "
                                             f"{dists[0]})"))
    for k in np.flatnonzero(~(p[1:] > p[:-1]))[: max(0, MAX_PROBLEMS - len(problems))]:
        what = "equal to" if p[k + 1] == p[k] else "below"
        note = " (equal as REAL)" if what == "equal to" and phases[k + 1] != phases[k] else ""
        problems.append(CsvProblem(lines[k + 1], f"phase {phases[k + 1]} is {what} the previous phase "
                                                 f"{phases[k]}{note}: phases must ascend"))
    if problems:
        problems.sort(key=lambda pr: pr.line)
        raise CamCsvError(problems)
    return p, d


def read_cam_csv(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Read a cam table CSV file (see `parse_cam_csv`); an undecodable file is a `CamCsvError` too."""
    try:
        text = Path(path).read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise CamCsvError([CsvProblem(0, f"not UTF-8 text ({exc.reason} at byte {exc.start})")]) from exc
    return parse_cam_csv(text)


def _real_text(v: np.float32) -> str:
    """Shortest decimal that reads back as the same REAL; −0 is written as 0."""
    return "0" if v == 0 else np.format_float_positional(v, unique=True, trim="-")


def format_cam_csv(phase: ArrayLike, distance: ArrayLike, *, comment: str | None = None) -> str:
    """CSV text of points (converted to REAL first), with an optional `#` comment block before the header."""
    p = np.asarray(phase, dtype=REAL).ravel()
    d = np.asarray(distance, dtype=REAL).ravel()
    if p.shape != d.shape:
        raise ValueError(f"{p.size} phases but {d.size} distances")
    out = [f"# {c}".rstrip() for c in comment.splitlines()] if comment else []
    out.append(HEADER)
    out.extend(f"{_real_text(a)},{_real_text(b)}" for a, b in zip(p, d, strict=True))
    return "\n".join(out) + "\n"


def write_cam_csv(path: str | Path, phase: ArrayLike, distance: ArrayLike, *, comment: str | None = None) -> None:
    """Write a cam table CSV atomically (a temporary file in the same folder, then renamed over the target)."""
    path = Path(path)
    text = format_cam_csv(phase, distance, comment=comment)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
