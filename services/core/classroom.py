"""``GET /api/class``: the class page's table, the instructor's alone (docs/class.md).

Per student of the class's tokens: their nodes (the registry's, under ``/NAME``), how long ago
one of them last published (from the counts each node's session reports, about once a second),
and their grade from the gradebook ``skydeck grade ... --class`` writes (``--class-gradebook``:
``{"assignment": str, "students": {NAME: {"score", "passed", "criteria": [...]}}}``). The
gradebook is read when asked, so a new grading shows at the page's next poll; a missing file is
no grades yet, one that cannot be read is said in one line beside the table.
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

from fastapi import APIRouter, HTTPException, Request

from services.access import INSTRUCTOR, Fences, Role
from services.core.registry import Registry
from services.core.visitors import FENCED, VisitorDep

__all__ = ["class_table", "read_gradebook", "router"]

router = APIRouter(prefix="/api", tags=["class"])


@router.get("/class", responses={**FENCED, 404: {"description": "This core runs no class (`skydeck class ROSTER` starts one)"}})
async def class_page(request: Request, visitor: VisitorDep) -> dict[str, Any]:
    """The class: each student's nodes, last message age and grade (the instructor's token)."""
    fences: Fences = request.app.state.fences
    tokens = fences.policy.tokens
    if tokens is None:
        raise HTTPException(404, "this core runs no class: start one with `skydeck class ROSTER`")
    subject = visitor.subject
    if not subject.privileged:
        status = 401 if subject.role is Role.ANONYMOUS else 403
        raise HTTPException(
            status, f"the class page is the instructor's: present the instructor's token ({subject} may not see it)"
        )
    students = [name for name in tokens.names if name != INSTRUCTOR]
    return class_table(request.app.state.registry, students, request.app.state.settings.class_gradebook)


def class_table(registry: Registry, students: list[str], gradebook: Path | None) -> dict[str, Any]:
    """The table ``GET /api/class`` answers (see the module docstring)."""
    grades, said = read_gradebook(gradebook)
    now = time.monotonic()
    rows = []
    for name in students:
        prefix = f"/{name}/"
        nodes = sorted(node for node in registry.nodes if node.startswith(prefix))
        published = [registry.nodes[node].last_published for node in nodes]
        last = max((moment for moment in published if moment is not None), default=None)
        rows.append({
            "name": name,
            "namespace": f"/{name}",
            "nodes": nodes,
            "last_message_age_s": None if last is None else round(now - last, 1),
            "grade": grades.get(name),
        })  # fmt: skip
    return {"students": rows, "assignment": said["assignment"], "gradebook": said}


def read_gradebook(path: Path | None) -> tuple[dict[str, Any], dict[str, Any]]:
    """The grades by student, and what to say about the gradebook: its path, its assignment,
    and ``error`` (one line) when it cannot be read. No file: no grades, no error."""
    said: dict[str, Any] = {"path": str(path) if path else None, "assignment": None}
    if path is None or not path.is_file():
        return {}, said
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        students = data["students"]
        if not isinstance(students, dict):
            raise TypeError("students is not a mapping")
    except (OSError, UnicodeDecodeError, ValueError, KeyError, TypeError) as error:
        said["error"] = f"cannot read the gradebook {path}: {error}"
        return {}, said
    said["assignment"] = data.get("assignment") if isinstance(data.get("assignment"), str) else None
    grades = {}
    for name, grade in students.items():
        if isinstance(grade, dict):
            grades[str(name)] = {
                "score": grade.get("score") if isinstance(grade.get("score"), int | float) else None,
                "passed": grade.get("passed") if isinstance(grade.get("passed"), bool) else None,
                "criteria": [c for c in grade.get("criteria", []) if isinstance(c, dict)][:50],
            }
    return grades, said
