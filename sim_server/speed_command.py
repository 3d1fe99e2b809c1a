"""``python -m sim_server.WORLD.speed``: one reading of a world's speed against its bare loop,
printed as one line (the world's ``measure`` and its reading's ``str``; the figures themselves
belong to ``skydeck bench``)."""

from __future__ import annotations

import argparse
from collections.abc import Callable

__all__ = ["print_reading"]


def print_reading(doc: str, measure: Callable[..., object], *, count: str, default: int, span: tuple[int, int]) -> None:
    """Read ``--COUNT N`` (the world's bodies: boxes, robots; N in ``span``) and ``--steps N``
    from the command line, measure, print the reading."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument(f"--{count}", type=_whole_number(*span), default=default)
    parser.add_argument("--steps", type=_whole_number(1, None), default=4800)
    args = parser.parse_args()
    print(measure(**{count: getattr(args, count), "steps": args.steps}))


def _whole_number(least: int, most: int | None) -> Callable[[str], int]:
    wanted = f"a whole number from {least} to {most}" if most is not None else f"a whole number of at least {least}"

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{wanted}, not {text!r}") from None
        if value < least or (most is not None and value > most):
            raise argparse.ArgumentTypeError(f"{wanted}, not {text!r}")
        return value

    return parse
