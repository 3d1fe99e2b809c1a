"""Suggesting the nearest names for a mistyped one: a topic, service or node of the running
system, and a verb (argparse's "invalid choice" with "did you mean ...").

    unknown("topic", "/drone/poze", ["/drone/pose", "/clock"], listing="skydeck topic list")
    # "unknown topic /drone/poze (did you mean /drone/pose?): see `skydeck topic list`"
"""

from __future__ import annotations

import argparse
import difflib
from collections.abc import Iterable
from typing import Any

__all__ = ["SuggestingParser", "did_you_mean", "graph_names", "nearest", "unknown"]

_MAX_SUGGESTIONS = 3
_CUTOFF = 0.6
"""difflib's similarity (0-1) a name needs to be suggested: one or two letters wrong or missing
in a ROS name or a verb pass, an unrelated name of the same length does not."""


def nearest(name: str, names: Iterable[str]) -> list[str]:
    """Up to three of ``names`` closest to ``name``, the closest first; none when nothing is near."""
    scored = sorted(
        ((_similarity(name, other), other) for other in set(names) - {name}),
        key=lambda pair: (-pair[0], pair[1]),
    )
    return [other for score, other in scored[:_MAX_SUGGESTIONS] if score >= _CUTOFF]


def _similarity(name: str, other: str) -> float:
    # Two names in one namespace differ only in their last parts: compared on the whole, the
    # namespace they share would make every sibling look alike (/drone/poze, /drone/cmd_vel).
    base, _, last = name.rpartition("/")
    other_base, _, other_last = other.rpartition("/")
    if "/" in name and base == other_base:
        name, other = last, other_last
    return difflib.SequenceMatcher(None, name, other).ratio()


def did_you_mean(name: str, names: Iterable[str], *, quote: bool = False) -> str:
    """``" (did you mean /a or /b?)"``, or ``""`` when no name is near."""
    found = nearest(name, names)
    if not found:
        return ""
    shown = [repr(n) if quote else n for n in found]
    return f" (did you mean {' or '.join(shown)}?)"


def unknown(kind: str, name: str, names: Iterable[str], *, listing: str) -> str:
    """The one line for a name the system does not have: ``unknown topic /x (did you mean
    /y?): see `skydeck topic list```."""
    return f"unknown {kind} {name}{did_you_mean(name, names)}: see `{listing}`"


def graph_names(graph: dict[str, Any], kind: str) -> list[str]:
    """The names of one kind (``topics``, ``services``, ``nodes``) in ``GET /api/graph``'s answer."""
    return [entry["name"] for entry in graph.get(kind, ())]


class SuggestingParser(argparse.ArgumentParser):
    """An ``ArgumentParser`` whose "invalid choice" (a mistyped verb, ``skydeck topc list``)
    ends with the nearest choices: ``... (choose from ...); did you mean 'topic'?``.

    Python 3.14's ``suggest_on_error=True`` does the same; this is the one place to drop when
    the project's oldest Python has it. Subparsers are made of the same class (argparse's
    default ``parser_class``), so every level of verbs suggests.
    """

    def _check_value(self, action: argparse.Action, value: Any) -> None:
        try:
            super()._check_value(action, value)
        except argparse.ArgumentError as error:
            choices = [str(choice) for choice in action.choices or ()]
            found = nearest(str(value), choices) if isinstance(value, str) else []
            if not found:
                raise
            hint = " or ".join(repr(choice) for choice in found)
            raise argparse.ArgumentError(action, f"{error.message}; did you mean {hint}?") from None
