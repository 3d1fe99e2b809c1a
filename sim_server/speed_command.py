"""``python -m sim_server.WORLD.speed``: one reading of a world's speed against its bare loop,
printed as one line (the world's ``measure`` and its reading's ``str``; the figures themselves
belong to ``skydeck bench``)."""

from __future__ import annotations

import argparse
from collections.abc import Callable

__all__ = ["print_reading"]


def print_reading(doc: str, measure: Callable[..., object], *, count: str, default: int) -> None:
    """Read ``--COUNT N`` (the world's bodies: boxes, robots) and ``--steps N`` from the command
    line, measure, print the reading."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument(f"--{count}", type=int, default=default)
    parser.add_argument("--steps", type=int, default=4800)
    args = parser.parse_args()
    print(measure(**{count: getattr(args, count), "steps": args.steps}))
