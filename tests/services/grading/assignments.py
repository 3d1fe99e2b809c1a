"""The shipped assignments, and copies of them changed for a test (a shorter run, one seed)."""

from __future__ import annotations

from pathlib import Path

import yaml

SHIPPED = Path("examples/assignments")
SOLUTIONS = Path(__file__).parent / "solutions"


def shipped(name: str) -> Path:
    return SHIPPED / f"{name}.yaml"


def changed(name: str, folder: Path, **fields: object) -> Path:
    """The shipped assignment ``name`` with ``fields`` replaced (``seeds=[1]`` for the visible
    seeds), written into ``folder``."""
    data = yaml.safe_load(shipped(name).read_text())
    for field, value in fields.items():
        if field == "seeds":
            data["seeds"]["visible"] = value
        else:
            data[field] = value
    path = folder / f"{name}.yaml"
    path.write_text(yaml.safe_dump(data))
    return path
