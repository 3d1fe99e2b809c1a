"""``skydeck completion bash | zsh``: shell completion for verbs, flags, live names and files.

    source <(skydeck completion bash)        # in ~/.bashrc
    source <(skydeck completion zsh)         # in ~/.zshrc

The script asks ``skydeck completion complete`` for the candidates of the word being typed,
giving it the words so far in ``SKYDECK_COMP_WORDS`` (one a line) and the word's index in
``SKYDECK_COMP_CWORD``. Candidates come from the command line's own parser (verbs and flags)
and, for names, from the running system (``/api/graph``: topics, services, actions, nodes) or the type
catalogue; an argument that is a file answers ``__files__``, and the shell lists files; after a
launch file, its launch arguments as ``name:=`` (no space after them: the value follows).
"""

from __future__ import annotations

import argparse

from services.cli.settings import cli_settings

__all__ = ["FILES", "add_parser", "candidates"]

FILES = "__files__"
"""Answered instead of candidates when the shell should complete a file path."""

_GRAPH_TIMEOUT_S = 1.0
# Positional arguments (by dest) and the names they take; "file" asks the shell for paths.
_KINDS = {
    "topic": "topics",
    "topics": "topics",
    "service": "services",
    "action": "actions",
    "node": "nodes",
    "type": "types",
    "file": "files",
}
_FILE_OPTIONS = {"-o", "--output", "--out", "--plots"}
_TOPIC_OPTIONS = {"--topics"}

_BASH = r"""# skydeck completion for bash: source <(skydeck completion bash)
_skydeck() {
    local IFS=$'\n' candidates
    candidates=$(SKYDECK_COMP_WORDS="$(printf '%s\n' "${COMP_WORDS[@]}")" SKYDECK_COMP_CWORD="$COMP_CWORD" \
        "${COMP_WORDS[0]}" completion complete 2>/dev/null)
    if [[ "$candidates" == "__files__" ]]; then
        compopt -o filenames 2>/dev/null
        COMPREPLY=($(compgen -f -- "${COMP_WORDS[COMP_CWORD]}"))
    else
        COMPREPLY=($(compgen -W "$candidates" -- "${COMP_WORDS[COMP_CWORD]}"))
        [[ "${COMPREPLY[0]}" == *:= ]] && compopt -o nospace 2>/dev/null  # a launch argument: its value follows
    fi
}
complete -F _skydeck skydeck
"""

_ZSH = r"""#compdef skydeck
# skydeck completion for zsh: source <(skydeck completion zsh)
_skydeck() {
    local -a candidates
    candidates=("${(@f)$(SKYDECK_COMP_WORDS="${(pj:\n:)words}" SKYDECK_COMP_CWORD=$((CURRENT - 1)) \
        "${words[1]}" completion complete 2>/dev/null)}")
    if [[ "${candidates[1]}" == "__files__" ]]; then
        _files
    elif [[ "${candidates[1]}" == *:= ]]; then
        compadd -S '' -- "${candidates[@]}"  # a launch argument: its value follows
    else
        compadd -- "${candidates[@]}"
    fi
}
if (( $+functions[compdef] )); then
    compdef _skydeck skydeck
else
    autoload -Uz compinit && compinit && compdef _skydeck skydeck
fi
"""


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "completion",
        help="print the shell completion script: source <(skydeck completion bash)",
        description="Prints a script that completes verbs, flags, live topic/service/node names, types and files.",
    )
    p.add_argument("shell", choices=["bash", "zsh", "complete"], metavar="{bash,zsh}", help="the shell")
    p.set_defaults(func=_completion)


def _completion(args: argparse.Namespace) -> int:
    if args.shell == "complete":
        settings = cli_settings()
        words = settings.comp_words.split("\n")
        try:
            index = int(settings.comp_cword)
        except ValueError:
            index = len(words) - 1
        words += [""] * (index + 1 - len(words))  # the shell's $(...) drops a last, empty word
        print("\n".join(candidates(args.parser, words[1 : index + 1])))
        return 0
    print(_BASH if args.shell == "bash" else _ZSH, end="")
    return 0


def candidates(parser: argparse.ArgumentParser, words: list[str]) -> list[str]:
    """What may come as the last of ``words`` (the command line after ``skydeck``, the last
    one being typed, perhaps empty); ``[FILES]`` when it is a file path."""
    typed = words[-1] if words else ""
    done = words[:-1]
    path: list[str] = []
    positionals: list[str] = []
    expecting: argparse.Action | None = None
    for word in done:
        if expecting is not None:
            expecting = None if expecting.nargs in (None, 1) else expecting
            if expecting is not None and word.startswith("-"):
                expecting = None
            else:
                continue
        sub = _subcommands(parser)
        if sub is not None and word in sub.choices:
            parser = sub.choices[word]
            path.append(word)
            positionals = []
            continue
        if word.startswith("-"):
            action = _option(parser, word)
            if action is not None and action.nargs != 0:
                expecting = action
            continue
        positionals.append(word)
    if expecting is not None and not typed.startswith("-"):
        return _option_values(expecting, typed)
    if typed.startswith("-"):
        return sorted(o for a in parser._actions for o in a.option_strings if o.startswith(typed) and a.help != argparse.SUPPRESS)
    sub = _subcommands(parser)
    if sub is not None:
        return sorted(name for name in sub.choices if name.startswith(typed) and name != "complete")
    return _positional_values(parser, path, positionals, typed)


def _subcommands(parser: argparse.ArgumentParser) -> argparse._SubParsersAction[argparse.ArgumentParser] | None:
    return next((a for a in parser._actions if isinstance(a, argparse._SubParsersAction)), None)


def _option(parser: argparse.ArgumentParser, word: str) -> argparse.Action | None:
    return parser._option_string_actions.get(word.split("=", 1)[0])


def _option_values(action: argparse.Action, typed: str) -> list[str]:
    if action.choices is not None:
        return sorted(str(choice) for choice in action.choices if str(choice).startswith(typed))
    if set(action.option_strings) & _FILE_OPTIONS:
        return [FILES]
    if set(action.option_strings) & _TOPIC_OPTIONS:
        return _live("topics", typed)
    return []


def _positional_values(parser: argparse.ArgumentParser, path: list[str], given: list[str], typed: str) -> list[str]:
    positionals = [a for a in parser._actions if not a.option_strings and not isinstance(a, argparse._SubParsersAction)]
    if not positionals:
        return []
    index = len(given)
    action = positionals[min(index, len(positionals) - 1)]
    if index >= len(positionals) and action.nargs not in ("*", "+", argparse.REMAINDER):
        return []
    if path[:1] == ["launch"] and action.dest == "launch_args":
        return _launch_arguments(given[0], given[1:], typed)
    if action.choices is not None:
        return sorted(str(c) for c in action.choices if str(c).startswith(typed) and c != "complete")
    if path[:1] == ["run"] and action.dest == "node":  # a built-in, or a .py file
        from services.builtin_nodes import BUILTIN_NODES

        builtins = sorted(name for name in BUILTIN_NODES if name.startswith(typed))
        return builtins if builtins and "/" not in typed else [FILES]
    if path[:1] == ["launch"] and action.dest == "file":
        return [FILES]
    kind = _KINDS.get(action.dest)
    if kind == "files":
        return [FILES]
    if kind == "types":
        from shared_models import interface_names

        wanted = {"service": "srv", "topic": "msg", "action": "action"}.get(path[0] if path else "")
        package = typed.split("/", 1)[0] if "/" in typed else None  # only its package is loaded
        return [name for name in interface_names(wanted, package=package) if name.startswith(typed)]
    if kind is not None:
        return _live(kind, typed)
    return []


def _launch_arguments(file: str, given: list[str], typed: str) -> list[str]:
    """``name:=`` for each argument the launch file declares and the line does not give yet."""
    from services.launch import LaunchError, launch_arguments

    try:
        declared = launch_arguments(file)
    except LaunchError:
        return []
    taken = {word.partition(":=")[0] for word in given}
    return [f"{name}:=" for name in declared if name not in taken and f"{name}:=".startswith(typed)]


def _live(kind: str, typed: str) -> list[str]:
    """Names of the running system (quietly none if the core does not answer at once)."""
    from services.cli.core_client import core_url, get
    from services.runtime.http_client import HttpError

    try:
        graph = get(core_url() + "/api/graph", timeout_s=_GRAPH_TIMEOUT_S).json()
    except (HttpError, ValueError):
        return []
    if kind == "actions":
        from services.runtime.actions.names import actions_in_graph

        return [name for name in actions_in_graph(graph) if name.startswith(typed)]
    return sorted(item["name"] for item in graph.get(kind, []) if item["name"].startswith(typed))
