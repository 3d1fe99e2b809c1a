"""Every verb and every flag of the `skydeck` command line is used by at least one test.

A flag is found when a test file passes it as an argument (the quoted option string, e.g.
``"--max-size"``); a verb when its name is passed as one. Names shared by several verbs (``-n``)
count once found anywhere: the point is that no flag ships with no test at all.
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

from services.cli.main import build_parser

TESTS = Path(__file__).resolve().parents[2]
# Verbs that are tested through their own harness rather than the CLI's arguments.
NOT_CLI = {"bench"}  # `skydeck bench` is run by tests/services/bench through run_bench


def _walk(parser: argparse.ArgumentParser, path: tuple[str, ...]):  # type: ignore[no-untyped-def]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield path + (name,), None
                yield from _walk(sub, path + (name,))
        elif action.option_strings and action.help != argparse.SUPPRESS:
            yield path, action


def test_every_verb_and_flag_appears_in_a_test() -> None:
    text = "\n".join(p.read_text() for p in TESTS.rglob("*.py") if p.name != Path(__file__).name)
    quoted = set(re.findall(r"""["']([^"'\s]+)["']""", text))
    missing = []
    for path, action in _walk(build_parser(), ()):
        if path[:1] and path[0] in NOT_CLI:
            continue
        if action is None:
            if path[-1] not in quoted:
                missing.append(" ".join(path))
            continue
        if action.option_strings == ["-h", "--help"]:
            continue
        if not any(option in quoted for option in action.option_strings):
            missing.append(f"{' '.join(path)} {'/'.join(action.option_strings)}")
    assert not missing, "no test uses: " + "; ".join(missing)
