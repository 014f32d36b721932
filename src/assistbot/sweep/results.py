"""results.csv (appended and flushed row by row) and results.parquet (rewritten from the CSV).

The CSV is the record: one line per finished episode, written in one call,
flushed and synced before the next, so a kill loses at most the episode that
was running. A torn last line (a kill in the middle of a write) is cut off
when the folder is opened again. Parquet is a typed copy for analysis,
rewritten from the CSV every so often, at the end and on interrupt.

Columns: ``job_id, scenario, <one per swept path>, seed, perception,
time_limit, success, time_to_drink, end_reason, end_detail, decisions, n_decisions,
n_failed_actions, errors_communicated, answered_cues, ignored_cues, uncued_decisions, spilled_fraction,
min_distance_human, touched_person, touch_depth, touch_force, sim_time, wall_seconds, cpu_seconds,
scenario_sha``. ``decisions`` is the AEL decision sequence joined by `` > ``;
``answered_cues``, ``ignored_cues`` and ``uncued_decisions`` count the decisions that answered a cue of the
person's shown just before, that ignored one, and that came without one (`assistbot.episode.cues`);
``end_reason`` is one of `assistbot.episode.judge.END_REASONS` (``object fell: bottle``
names the object) and ``end_detail`` what it concerns (the repeated action, say);
``touched_person`` whether any robot geom overlapped any of the person's, ``touch_depth``
the deepest overlap (m) and ``touch_force`` the largest contact force between them (N).
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import time
from pathlib import Path
from typing import Any, Iterable

from assistbot.errors import UserError

HEAD = ["job_id", "scenario"]
TAIL = ["seed", "perception", "time_limit", "success", "time_to_drink", "end_reason", "end_detail", "decisions",
        "n_decisions", "n_failed_actions", "errors_communicated", "answered_cues", "ignored_cues", "uncued_decisions",
        "spilled_fraction", "min_distance_human",
        "touched_person", "touch_depth", "touch_force", "sim_time", "wall_seconds", "cpu_seconds", "scenario_sha"]
FIXED = HEAD + TAIL
#: columns that depend on the machine, not on the episode
VOLATILE = ("wall_seconds", "cpu_seconds")
ERROR_COLUMNS = ["job_id", "scenario", "params", "seed", "error", "traceback", "wall_seconds", "when"]
_TYPES = {"seed": "int64", "time_limit": "float64", "success": "bool_", "time_to_drink": "float64",
          "n_decisions": "int64", "n_failed_actions": "int64", "errors_communicated": "int64",
          "answered_cues": "int64", "ignored_cues": "int64", "uncued_decisions": "int64",
          "spilled_fraction": "float64", "min_distance_human": "float64", "touched_person": "bool_",
          "touch_depth": "float64", "touch_force": "float64", "sim_time": "float64", "wall_seconds": "float64",
          "cpu_seconds": "float64"}


def columns_for(param_paths: Iterable[str]) -> list[str]:
    return HEAD + list(param_paths) + TAIL


def param_columns(columns: Iterable[str]) -> list[str]:
    """The swept paths among a results table's columns."""
    return [c for c in columns if c not in FIXED]


def format_value(v: Any) -> str:
    if v is None:
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("inf" if v > 0 else "-inf" if v < 0 else "nan")
    if isinstance(v, (list, tuple)):
        return json.dumps(list(v))
    return " ".join(str(v).split("\n"))


def parse_value(text: str) -> Any:
    """A CSV cell back to a value: '' -> None, true/false -> bool, numbers -> float/int, JSON lists -> list."""
    if text == "":
        return None
    if text in ("true", "false"):
        return text == "true"
    if text.startswith("["):
        try:
            return json.loads(text)
        except ValueError:
            return text
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return text


def read_rows(path: str | Path) -> tuple[list[str], list[dict[str, str]]]:
    """(header, rows as text) of a results CSV; a torn last line is ignored."""
    p = Path(path)
    text = p.read_text(encoding="utf-8") if p.exists() else ""
    if text and not text.endswith("\n"):
        text = text[: text.rfind("\n") + 1]
    reader = csv.reader(io.StringIO(text))
    header = next(reader, None)
    if header is None:
        return [], []
    rows = [dict(zip(header, r)) for r in reader if len(r) == len(header)]
    return header, rows


class ResultStore:
    """The results folder of one sweep: results.csv, results.parquet and errors.csv."""

    def __init__(self, out: str | Path, columns: list[str], parquet_every: float = 15.0) -> None:
        self.dir = Path(out)
        self.columns = list(columns)
        self.csv_path = self.dir / "results.csv"
        self.parquet_path = self.dir / "results.parquet"
        self.errors_path = self.dir / "errors.csv"
        self.parquet_every = parquet_every
        self._fh = None
        self._last_parquet = 0.0
        self._dirty = False

    # -- opening: repair, check the header, the finished ids ---------------------------------------
    def open(self) -> dict[str, dict[str, str]]:
        """Create or reopen the folder; return the finished rows by job id."""
        self.dir.mkdir(parents=True, exist_ok=True)
        done: dict[str, dict[str, str]] = {}
        if self.csv_path.exists() and self.csv_path.stat().st_size > 0:
            raw = self.csv_path.read_bytes()
            if not raw.endswith(b"\n"):  # torn by a kill mid-write: drop the partial line
                with open(self.csv_path, "r+b") as fh:
                    fh.truncate(raw.rfind(b"\n") + 1)
            header, rows = read_rows(self.csv_path)
            if header and header != self.columns:
                theirs, ours = param_columns(header), param_columns(self.columns)
                if theirs == ours:
                    raise UserError(str(self.csv_path), "columns",
                                    "this folder was written by another version of assistbot (its results have other "
                                    "columns); use another --out")
                raise UserError(str(self.csv_path), "columns",
                                f"this folder holds a sweep over {', '.join(theirs) or 'no parameters'}, this one sweeps "
                                f"{', '.join(ours) or 'no parameters'}; use another --out (or the same parameters)")
            for r in rows:
                done.setdefault(r["job_id"], r)
        new = not self.csv_path.exists() or self.csv_path.stat().st_size == 0
        self._fh = open(self.csv_path, "a", encoding="utf-8", newline="")
        if new:
            self._write_line(self.columns)
        return done

    def _write_line(self, cells: list[str]) -> None:
        buf = io.StringIO()
        csv.writer(buf, lineterminator="\n").writerow(cells)
        self._fh.write(buf.getvalue())  # one write per row
        self._fh.flush()
        os.fsync(self._fh.fileno())

    # -- appending -----------------------------------------------------------------------------------
    def append(self, row: dict[str, Any]) -> None:
        self._write_line([format_value(row.get(c)) for c in self.columns])
        self._dirty = True
        if time.monotonic() - self._last_parquet >= self.parquet_every:
            self.write_parquet()

    def append_error(self, row: dict[str, Any]) -> None:
        new = not self.errors_path.exists()
        params = {c: row[c] for c in param_columns(self.columns) if c in row}
        cells = [row.get("job_id"), row.get("scenario"), json.dumps(params), row.get("seed"), row.get("error"),
                 row.get("traceback"), row.get("wall_seconds"), time.strftime("%Y-%m-%dT%H:%M:%S")]
        with open(self.errors_path, "a", encoding="utf-8", newline="") as fh:
            w = csv.writer(fh, lineterminator="\n")
            if new:
                w.writerow(ERROR_COLUMNS)
            w.writerow([format_value(c) for c in cells])

    # -- parquet ---------------------------------------------------------------------------------------
    def write_parquet(self) -> Path:
        """Rewrite results.parquet from results.csv (atomically: a reader never sees half a file)."""
        write_parquet(self.csv_path, self.parquet_path)
        self._last_parquet = time.monotonic()
        self._dirty = False
        return self.parquet_path

    def close(self) -> None:
        if self._fh is not None:
            self._fh.close()
            self._fh = None
            self.write_parquet()


def write_parquet(csv_path: Path, parquet_path: Path) -> None:
    import pyarrow as pa
    import pyarrow.csv as pacsv
    import pyarrow.parquet as pq

    header, _ = read_rows(csv_path)
    types = {c: getattr(pa, t)() for c, t in _TYPES.items() if c in header}
    types.update({c: pa.string() for c in ("job_id", "scenario", "perception", "end_reason", "end_detail", "decisions",
                                                "scenario_sha")
                  if c in header})
    raw = csv_path.read_bytes()
    if not raw.endswith(b"\n"):
        raw = raw[: raw.rfind(b"\n") + 1]
    # arrow reads the whole rows from a file of its own: given a Python buffer, one of its I/O threads
    # may drop the last reference to it during interpreter exit, and the process aborts
    rows = parquet_path.with_name(parquet_path.name + ".rows.tmp")
    rows.write_bytes(raw)
    try:
        table = pacsv.read_csv(str(rows), convert_options=pacsv.ConvertOptions(
            column_types=types, true_values=["true"], false_values=["false"], strings_can_be_null=False))
    finally:
        rows.unlink(missing_ok=True)
    tmp = parquet_path.with_name(parquet_path.name + ".tmp")
    pq.write_table(table, tmp)
    os.replace(tmp, parquet_path)
