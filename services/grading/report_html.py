"""The grade as a page: each seed's run drawn over its world, and each criterion's figure.

One self-contained HTML file (``report.html`` beside ``grade.json``): inline CSS and SVG, no
script, nothing fetched, so it opens from a folder, an e-mail or a learning platform's upload.
The map shows the world's walls and obstacles (the drone world's boxes), the person's walk, the
path driven (or flown), where it started and ended, where the bumper touched, and the points
the criteria measured at (a square's corners, the goal, a missed box).
"""

from __future__ import annotations

import math
from html import escape
from pathlib import Path

from services.grading.criteria.base import Mark
from services.grading.grade import GradeReport, SeedRun
from services.grading.shapes import Box, Pose
from services.grading.verdicts import format_value, node_note

__all__ = ["render_report"]

_MAP_PX = 520
_MARGIN_M = 0.4

_STYLE = """
body { font: 14px/1.45 system-ui, sans-serif; margin: 24px; color: #1d2330; background: #fafbfc; }
h1 { font-size: 20px; margin: 0 0 4px; } h2 { font-size: 16px; margin: 28px 0 8px; }
.meta { color: #5b6475; margin-bottom: 16px; }
.verdict { display: inline-block; padding: 2px 10px; border-radius: 4px; font-weight: 600; color: #fff; }
.pass { background: #1f8a4c; } .fail { background: #c0392b; }
table { border-collapse: collapse; background: #fff; }
th, td { border: 1px solid #dde1e8; padding: 5px 9px; text-align: left; vertical-align: top; }
th { background: #eef1f5; } td.num { font-variant-numeric: tabular-nums; white-space: nowrap; }
.seed { display: inline-block; vertical-align: top; margin: 0 24px 24px 0; }
svg { background: #fff; border: 1px solid #dde1e8; }
.legend span { margin-right: 14px; white-space: nowrap; } .note { color: #8a5a00; }
code { background: #eef1f5; padding: 1px 4px; border-radius: 3px; }
"""


class _Frame:
    """World metres to SVG pixels (y up in the world, down on the page), square scale."""

    def __init__(self, xs: list[float], ys: list[float]) -> None:
        # Room for the labels of points at the edge: a margin that grows with the world.
        margin = _MARGIN_M + 0.06 * max(max(xs) - min(xs), max(ys) - min(ys))
        self.x0, self.x1 = min(xs) - margin, max(xs) + margin
        self.y0, self.y1 = min(ys) - margin, max(ys) + margin
        self.scale = _MAP_PX / max(self.x1 - self.x0, self.y1 - self.y0, 1e-6)

    def p(self, x: float, y: float) -> tuple[float, float]:
        return (x - self.x0) * self.scale, (self.y1 - y) * self.scale

    @property
    def size(self) -> tuple[int, int]:
        return math.ceil((self.x1 - self.x0) * self.scale), math.ceil((self.y1 - self.y0) * self.scale)


def _corners(box: Box) -> list[tuple[float, float]]:
    c, s = math.cos(box.yaw), math.sin(box.yaw)
    hx, hy = box.size_x / 2, box.size_y / 2
    return [(box.x + c * a * hx - s * b * hy, box.y + s * a * hx + c * b * hy) for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]


def _frame(run: SeedRun) -> _Frame:
    tracks = run.tracks
    xs: list[float] = []
    ys: list[float] = []
    for box in tracks.obstacles + tracks.boxes:
        for x, y in _corners(box):
            xs.append(x)
            ys.append(y)
    for pose in tracks.robot + tracks.drone + tracks.people:
        xs.append(pose.x)
        ys.append(pose.y)
    return _Frame(xs or [0.0], ys or [0.0])


def _box(frame: _Frame, box: Box, fill: str) -> str:
    points = " ".join("{:.1f},{:.1f}".format(*frame.p(x, y)) for x, y in _corners(box))
    return f'<polygon class="{box.kind}" points="{points}" fill="{fill}" stroke="#6b5236" stroke-width="0.6"/>'


def _path(frame: _Frame, track: list[Pose], colour: str, css: str, dashed: bool = False) -> str:
    if len(track) < 2:
        return ""
    points = " ".join("{:.1f},{:.1f}".format(*frame.p(pose.x, pose.y)) for pose in track)
    dash = ' stroke-dasharray="4 4"' if dashed else ""
    return f'<polyline class="{css}" points="{points}" fill="none" stroke="{colour}" stroke-width="2"{dash}/>'


def _mark(frame: _Frame, mark: Mark) -> str:
    x, y = frame.p(mark.x, mark.y)
    title = f"<title>{escape(mark.label)}</title>"
    if mark.kind == "bump":
        return f'<g class="mark bump">{title}<path d="M{x - 5:.1f},{y - 5:.1f}L{x + 5:.1f},{y + 5:.1f}M{x - 5:.1f},{y + 5:.1f}L{x + 5:.1f},{y - 5:.1f}" stroke="#d62728" stroke-width="2.5"/></g>'
    if mark.kind == "miss":
        return f'<circle class="mark miss" cx="{x:.1f}" cy="{y:.1f}" r="3" fill="#ff9f1c">{title}</circle>'
    if mark.kind == "target":
        return (
            f'<g class="mark target">{title}<circle cx="{x:.1f}" cy="{y:.1f}" r="7" fill="none" stroke="#7b2cbf" stroke-width="2"/>'
            f'<text x="{x + 9:.1f}" y="{y - 8:.1f}" font-size="11" fill="#7b2cbf">{escape(mark.label)}</text></g>'
        )
    return f'<circle class="mark note" cx="{x:.1f}" cy="{y:.1f}" r="4" fill="#7b2cbf">{title}</circle>'


def _map(report: GradeReport, run: SeedRun) -> str:
    tracks = run.tracks
    frame = _frame(run)
    width, height = frame.size
    parts = [f'<svg class="map" width="{width}" height="{height}" viewBox="0 0 {width} {height}">']
    for box in tracks.obstacles:
        parts.append(_box(frame, box, "#d9d9de" if box.kind == "wall" else "#b08a5e"))
    for box in tracks.boxes:
        parts.append(_box(frame, box, "#b08a5e"))
    parts.append(_path(frame, tracks.people, "#e377c2", "person", dashed=True))
    vehicle = tracks.robot or tracks.drone
    parts.append(_path(frame, vehicle, "#1f77b4", "trajectory"))
    if vehicle:
        sx, sy = frame.p(vehicle[0].x, vehicle[0].y)
        ex, ey = frame.p(vehicle[-1].x, vehicle[-1].y)
        parts.append(f'<circle class="start" cx="{sx:.1f}" cy="{sy:.1f}" r="6" fill="#2ca02c"><title>start</title></circle>')
        parts.append(f'<rect class="end" x="{ex - 5:.1f}" y="{ey - 5:.1f}" width="10" height="10" fill="#1f77b4"><title>end, {vehicle[-1].t:.1f} s</title></rect>')
    seen: set[tuple[float, float, str]] = set()
    for criterion in report.criteria:
        for figure in criterion.figures:
            if figure.seed != run.seed:
                continue
            for mark in figure.marks:
                if (mark.x, mark.y, mark.label) not in seen:
                    seen.add((mark.x, mark.y, mark.label))
                    parts.append(_mark(frame, mark))
    parts.append("</svg>")
    return "".join(parts)


def _seed_section(report: GradeReport, run: SeedRun, out_dir: Path) -> str:
    result = run.result
    lines = [
        f'<div class="seed" id="seed-{run.seed}"><h2>Seed {run.seed}</h2>',
        _map(report, run),
        '<div class="legend"><span style="color:#1f77b4">━ path</span><span style="color:#e377c2">┅ person</span>'
        '<span style="color:#2ca02c">● start</span><span style="color:#d62728">✕ bump</span>'
        '<span style="color:#7b2cbf">◯ measured at</span><span style="color:#ff9f1c">● out of bounds</span></div>',
        f"<p>{result.sim_time_s:.1f} s of sim time in {result.steps} steps, {result.wall_time_s:.1f} s of wall time. "
        f"Recording: <code>{escape(_relative(result.bag, out_dir))}</code></p>",
    ]
    if result.lockstep_lost:
        lines.append(
            f'<p class="note">The run was not kept in lockstep {result.lockstep_lost} time(s) '
            f"({escape(result.lockstep_reason)}): another run may score differently.</p>"
        )
    for node in result.nodes:
        note = node_note(node)
        if note is not None:
            lines.append(f'<p class="note">{escape(note)}: see <code>{escape(_relative(node.log, out_dir))}</code>.</p>')
    lines.append("</div>")
    return "".join(lines)


def _relative(path: Path, base: Path) -> str:
    try:
        return str(path.resolve().relative_to(base.resolve()))
    except ValueError:
        return str(path)


def render_report(report: GradeReport, out_dir: Path) -> str:
    """The page (see the module docstring); paths in it are relative to ``out_dir``."""
    assignment = report.assignment
    verdict = '<span class="verdict pass">PASS</span>' if report.passed else '<span class="verdict fail">FAIL</span>'
    rows = []
    for criterion in report.criteria:
        use = criterion.use
        cells = "".join(
            f'<td class="num {"pass-cell" if f.passed else "fail-cell"}">'
            f'<span class="verdict {"pass" if f.passed else "fail"}">{"PASS" if f.passed else "FAIL"}</span> '
            f"{escape(format_value(f.value))}<br><small>{escape(f.detail)}</small></td>"
            for f in criterion.figures
        )
        rows.append(
            f'<tr class="criterion" data-name="{escape(criterion.name)}" data-passed="{str(criterion.passed).lower()}">'
            f"<td><b>{escape(criterion.name)}</b><br><small>{escape(use.spec.summary)}</small></td>"
            f'<td class="num">{use.comparison} {escape(format_value(use.threshold))} {escape(use.spec.unit)}</td>{cells}</tr>'
        )
    seeds = "".join(f"<th>seed {run.seed}</th>" for run in report.runs)
    title = escape(assignment.title or assignment.assignment)
    return (
        "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\">"
        f"<title>{title}: {escape(report.student)}</title><style>{_STYLE}</style></head><body>"
        f"<h1>{title} {verdict}</h1>"
        f'<div class="meta">Assignment <code>{escape(assignment.assignment)}</code> · student '
        f"<b>{escape(report.student)}</b> · files {', '.join(f'<code>{escape(f)}</code>' for f in report.files)} · "
        f"{escape(report.seed_kind)} seeds {', '.join(str(run.seed) for run in report.runs)} · "
        f"{assignment.duration_s:g} s of sim time each in the {escape(assignment.world)} world</div>"
        f'<table class="criteria"><tr><th>criterion</th><th>threshold</th>{seeds}</tr>{"".join(rows)}</table>'
        + "".join(_seed_section(report, run, out_dir) for run in report.runs)
        + "</body></html>"
    )
