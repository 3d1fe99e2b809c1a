"""Every verb and every flag of the `skydeck` command line is used by at least one test, with
that verb: `topic echo --rate` is not covered by a test of `topic pub --rate`.

The tests' command lines are read from their source (``ast``): the string literals of each call
(``skydeck(url, "topic", "echo", "/x", "--field", "a")``) and of each list or tuple (an argv
given to a subprocess), and the words of shell text (a script string, a ``.zsh`` file). A
test helper that puts words before its ``*args`` (``[..., "services.cli", "launch", *args]``)
lends them to its calls, also through a fixture that returns it, so ``launch("--seed", "3")``
is ``skydeck launch --seed 3``. A verb is used when its words come in a command line in order;
a flag when it (or ``--flag=value``) comes after them.
"""

from __future__ import annotations

import argparse
import ast
import functools
from collections.abc import Iterator
from pathlib import Path

from services.cli.main import build_parser

TESTS = Path(__file__).resolve().parents[2]
SHELL_FILES = ("*.zsh", "*.sh")


def _walk(parser: argparse.ArgumentParser, path: tuple[str, ...]) -> Iterator[tuple[tuple[str, ...], argparse.Action | None]]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield path + (name,), None
                yield from _walk(sub, path + (name,))
        elif action.option_strings and action.help != argparse.SUPPRESS:
            yield path, action


def _strings(nodes: list[ast.expr]) -> list[str]:
    return [node.value for node in nodes if isinstance(node, ast.Constant) and isinstance(node.value, str)]


def _callee(call: ast.Call) -> str | None:
    func = call.func
    return func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else None


def _prefixes(functions: list[ast.FunctionDef | ast.AsyncFunctionDef]) -> dict[str, set[tuple[str, ...]]]:
    """The words each helper puts before its ``*args``, by the helper's name (and by the name
    of a fixture that returns or yields the helper)."""
    spreads: list[tuple[str, tuple[str, ...], str | None]] = []  # (helper, words before *args, callee)
    handed: list[tuple[str, str]] = []  # (fixture, the helper it returns)
    for function in functions:
        varargs = function.args.vararg.arg if function.args.vararg else None
        for node in ast.walk(function):
            if varargs is not None and isinstance(node, (ast.List, ast.Tuple, ast.Call)):
                items = node.elts if isinstance(node, (ast.List, ast.Tuple)) else node.args
                spread = [i for i, item in enumerate(items) if isinstance(item, ast.Starred)
                          and isinstance(item.value, ast.Name) and item.value.id == varargs]  # fmt: skip
                if spread:
                    callee = _callee(node) if isinstance(node, ast.Call) else None
                    spreads.append((function.name, tuple(_strings(items[: spread[0]])), callee))
            elif isinstance(node, (ast.Return, ast.Yield)) and isinstance(node.value, ast.Name):
                handed.append((function.name, node.value.id))
    found: dict[str, set[tuple[str, ...]]] = {}
    for _ in range(3):  # a helper calling a helper calling the one with the argv
        for name, words, callee in spreads:
            found.setdefault(name, set()).update(p + words for p in found.get(callee or "", {()}))
        for fixture, helper in handed:
            if helper in found:
                found.setdefault(fixture, set()).update(found[helper])
    return found


@functools.cache
def command_lines() -> list[list[str]]:
    """Every command line the tests write, as words."""
    sources = [path for path in TESTS.rglob("*.py") if path != Path(__file__).resolve()]  # not this file's examples
    nodes = [node for path in sources for node in ast.walk(ast.parse(path.read_text()))]
    prefixes = _prefixes([node for node in nodes if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))])
    lines: list[list[str]] = []
    for node in nodes:
        if isinstance(node, ast.Call):
            words = _strings(node.args)
            lines += [[*prefix, *words] for prefix in prefixes.get(_callee(node) or "", {()})]
        elif isinstance(node, (ast.List, ast.Tuple)):
            lines.append(_strings(node.elts))
        elif isinstance(node, ast.Constant) and isinstance(node.value, str) and "skydeck" in node.value.lower():
            lines += [line.split() for line in node.value.splitlines()]
    for pattern in SHELL_FILES:
        lines += [line.split() for path in TESTS.rglob(pattern) for line in path.read_text().splitlines()]
    return [line for line in lines if line]


def _after(words: list[str], path: tuple[str, ...]) -> list[str] | None:
    for start in range(len(words) - len(path) + 1):
        if tuple(words[start : start + len(path)]) == path:
            return words[start + len(path) :]
    return None


def test_every_verb_and_flag_is_used_with_its_verb_in_a_test() -> None:
    lines = command_lines()
    missing = []
    for path, action in _walk(build_parser(), ()):
        rests = [rest for rest in (_after(line, path) for line in lines) if rest is not None]
        if action is None:
            if not rests:
                missing.append(" ".join(path))
            continue
        if action.option_strings == ["-h", "--help"]:
            continue
        if not any(word.split("=", 1)[0] in action.option_strings for rest in rests for word in rest):
            missing.append(f"{' '.join(path)} {'/'.join(action.option_strings)}")
    assert not missing, "no test uses: " + "; ".join(missing)


def test_the_reader_finds_helpers_and_shell_text() -> None:
    """The reading above can fail: a flag of another verb does not count, a helper's words do."""
    lines = command_lines()
    assert _after(["x", "topic", "echo", "/a", "-n", "2"], ("topic", "echo")) == ["/a", "-n", "2"]
    assert _after(["topic", "pub", "--rate"], ("topic", "echo")) is None
    assert any(_after(line, ("launch",)) is not None and "--seed" in line for line in lines)  # via start_launch
    # zsh_complete.zsh's `zpty -w shell 'eval "$(skydeck completion zsh)"'` (this file's own
    # literals are not read: they would pass these checks by themselves)
    assert any(line[:4] == ["zpty", "-w", "shell", "'eval"] and "completion" in line for line in lines)
