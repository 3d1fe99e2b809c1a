"""The benchmark's output: rows with their references and ratios, the table, the JSON, the plots.

JSON (``--out FILE.json``)::

    {"results": [{"name", "value", "unit", "reference", "reference_value", "ratio",
                  "target", "met", "samples", "detail", "error"}, ...],
     "machine": {...}, "run": {...}}

``ratio`` is always ``value / reference_value`` (``None`` without a reference); ``target`` says
in words what the value or ratio should be, ``met`` whether it was (``None``: no target).
"""

from __future__ import annotations

import datetime
import json
import math
import os
import platform
import subprocess
from dataclasses import asdict, dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any

__all__ = ["Result", "format_table", "machine_info", "ratio_at_most", "write_json"]


@dataclass
class Result:
    """One row: a measured value, what it is compared with, and whether it meets its target."""

    name: str
    value: float | None
    unit: str
    reference: str | None = None
    reference_value: float | None = None
    target: str = ""
    met: bool | None = None
    samples: list[float] = field(default_factory=list)  # the value of each repetition
    detail: dict[str, Any] = field(default_factory=dict)
    error: str | None = None

    @property
    def ratio(self) -> float | None:
        if self.value is None or not self.reference_value:
            return None
        return self.value / self.reference_value

    def as_json(self) -> dict[str, Any]:
        data = asdict(self)
        data["ratio"] = self.ratio
        ordered = ["name", "value", "unit", "reference", "reference_value", "ratio", "target", "met"]
        return {key: _finite(data[key]) for key in ordered} | {
            key: _finite(data[key]) for key in data if key not in ordered
        }


def ratio_at_most(result: Result, limit: float) -> bool | None:
    """Whether the row's ratio to its reference is at most ``limit`` (None: no ratio to judge)."""
    return None if result.ratio is None else result.ratio <= limit


def _finite(value: Any) -> Any:
    """JSON has no NaN: a value that could not be measured is null."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_finite(v) for v in value]
    return value


def _number(value: float | None) -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if abs(value) >= 1000:
        return f"{value:,.0f}"
    if abs(value) >= 100:
        return f"{value:.0f}"
    if abs(value) >= 10:
        return f"{value:.1f}"
    return f"{value:.2f}"


def format_table(results: list[Result]) -> str:
    """A plain-text table, one row per result (also valid Markdown)."""
    header = ["name", "value", "unit", "reference", "ref. value", "ratio", "target", ""]
    rows = [header, ["---"] * len(header)]
    for r in results:
        status = {True: "ok", False: "MISSED", None: ""}[r.met]
        if r.error:
            status = "ERROR"
        rows.append([
            r.name,
            _number(r.value),
            r.unit,
            r.reference or "-",
            _number(r.reference_value),
            "-" if r.ratio is None else f"{r.ratio:.2f}",
            r.target or "-",
            status,
        ])
    widths = [max(len(row[i]) for row in rows) for i in range(len(header))]
    lines = []
    for row in rows:
        if row[0] == "---":
            lines.append("|" + "|".join("-" * (w + 2) for w in widths) + "|")
        else:
            lines.append("| " + " | ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)) + " |")
    errors = [f"{r.name}: {r.error}" for r in results if r.error]
    return "\n".join(lines + ([""] + errors if errors else []))


def machine_info() -> dict[str, Any]:
    """What the numbers were measured on."""
    info: dict[str, Any] = {
        "cpu": _cpu_model(),
        "logical_cpus": os.cpu_count(),
        "usable_cpus": len(os.sched_getaffinity(0)),
        "memory_gb": round(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30, 1),
        "os": f"{platform.system()} {platform.release()}",
        "python": platform.python_version(),
        "load_average_at_start": [round(x, 2) for x in os.getloadavg()],
        "packages": {},
        "git_commit": _git_commit(),
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
    }
    for package in ("websockets", "uvicorn", "fastapi", "starlette", "pydantic", "httpx", "eclipse-zenoh", "pybullet"):
        try:
            info["packages"][package] = metadata.version(package)
        except metadata.PackageNotFoundError:
            info["packages"][package] = None
    return info


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.partition(":")[2].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def _git_commit() -> str | None:
    try:
        out = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"],
            capture_output=True,
            text=True,
            timeout=5,
            cwd=Path(__file__).resolve().parent,
        )
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() or None


def write_json(path: Path, results: list[Result], machine: dict[str, Any], run: dict[str, Any]) -> None:
    """Write the results file (``{"results": [...], "machine": {...}, "run": {...}}``)."""
    document = {"results": [r.as_json() for r in results], "machine": machine, "run": _finite(run)}
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(document, indent=2) + "\n")
