"""``skydeck class ROSTER``: the class's tokens, its address, and one launch of a core and a world.

    options = ClassOptions(tokens=Path("class-tokens.csv"), host="127.0.0.1")
    run_class(read_roster(Path("students.csv")), options)   # until Ctrl-C

The tokens (one per student, one for the instructor) are written once to ``options.tokens``
(0600, :func:`services.access.write_tokens`); started again with the same roster, the class
reads them back, so the students keep the tokens they were given. The launch is the robot
world's (``skydeck launch robot``), with the core fenced by those tokens
(``--class-tokens``) and the world holding a robot per student under ``/NAME``
(``SKYDECK_SIM_STUDENTS``). The class's own processes (the core, the world, the launch's node)
present a process token made for this run and kept nowhere: the instructor's token is for the
instructor, who may then run anything from another terminal with it.

The address: loopback by default. Anything else opens the class to the network, which only a
fenced core may do; a class always is (it has its tokens), and its core must still answer on
loopback for its own world, so the address is loopback or every interface (``0.0.0.0``, ``::``),
which a class's processes then listen on, reached by the machine's name (``--advertise`` says
better).
"""

from __future__ import annotations

import asyncio
import ipaddress
import os
import secrets
from dataclasses import dataclass
from pathlib import Path
from typing import TextIO

from services.access import ClassTokensError, make_class_tokens, read_tokens, write_tokens
from services.classroom.roster import ClassroomError, Roster
from services.launch import LaunchOptions, LaunchSpec, Supervisor
from services.launch.output import say
from services.launch.settings import LaunchSettings
from services.runtime.settings import reachable_host

__all__ = ["ClassOptions", "check_host", "class_spec", "class_tokens", "run_class"]

_EVERY_INTERFACE = ("0.0.0.0", "::")
_WORLD_READY_S = 90.0  # forty robots' bodies and the room, on a loaded machine


@dataclass(frozen=True)
class ClassOptions:
    """``skydeck class``'s options (see its ``--help``)."""

    tokens: Path = Path("class-tokens.csv")
    host: str = "127.0.0.1"
    advertise: str | None = None
    rules: Path | None = None
    gradebook: Path | None = None
    base_port: int = 8000
    speed: str = "1"
    seed: int | None = None
    obstacles: int = 0


def check_host(host: str, *, fenced: bool) -> None:
    """ClassroomError unless a class's core may listen on ``host``: loopback always; every
    interface only when ``fenced`` (tokens guard it); no single other address (the core must
    answer its own world on loopback)."""
    if _is_loopback(host):
        return
    if not fenced:
        raise ClassroomError(f"--host {host} opens the core to the network: only a class with tokens may")
    if host not in _EVERY_INTERFACE:
        raise ClassroomError(
            f"--host {host}: a class listens on loopback (the default) or every interface (--host 0.0.0.0); "
            "give --advertise ADDRESS to say where students reach it"
        )


def _is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def class_tokens(path: Path, roster: Roster) -> tuple[dict[str, str], bool]:
    """The class's tokens, and whether they are new: written to ``path`` now (0600), or read
    back from it when it was written for this roster before. ClassroomError when the file is
    another roster's, or cannot be used."""
    try:
        if not path.exists():
            tokens = make_class_tokens(roster.students)
            write_tokens(path, tokens)
            return tokens, True
        tokens = read_tokens(path)
    except ClassTokensError as error:
        raise ClassroomError(str(error)) from None
    students = set(tokens) - {"instructor"}
    if students != set(roster.students):
        differ = sorted(students.symmetric_difference(roster.students))
        raise ClassroomError(
            f"{path} holds another class's tokens (it and the roster differ in {', '.join(differ[:3])}"
            f"{'...' if len(differ) > 3 else ''}): give --tokens NEW_FILE, or remove {path} to make new ones"
        )
    return tokens, False


def class_spec(roster: Roster, options: ClassOptions) -> LaunchSpec:
    """The launch of a class: the fenced core, and the robot world with a robot per student."""
    core_args = ["--class-tokens", str(options.tokens), "--host", options.host]
    if options.rules is not None:
        core_args += ["--class-rules", str(options.rules)]
    if options.gradebook is not None:
        core_args += ["--class-gradebook", str(options.gradebook)]
    sim_args = ["--world", roster.world, "--speed", "{speed}", "--seed", "{seed}", "--obstacles", "{obstacles}"]
    if not _is_loopback(options.host):  # students' nodes link to the world's topics directly
        sim_args += ["--host", options.host]
    if options.advertise:
        core_args += ["--advertise-url", f"http://{options.advertise}:{options.base_port}"]
        sim_args += ["--advertise-url", f"http://{options.advertise}:{options.base_port + 1}"]
    return LaunchSpec.model_validate({
        "nodes": [
            {"name": "core", "run": "core", "port_offset": 0, "args": [_literal(a) for a in core_args]},
            {"name": "sim", "run": "sim", "port_offset": 1, "args": [_literal(a) if not a.startswith("{") else a for a in sim_args],
             "env": {"SKYDECK_SIM_STUDENTS": ",".join(roster.students)}, "ready_timeout_s": _WORLD_READY_S},
        ]
    })  # fmt: skip


def _literal(text: str) -> str:
    """``text`` as a launch template that means itself (a path may hold braces)."""
    return text.replace("{", "{{").replace("}", "}}")


def run_class(roster: Roster, options: ClassOptions, *, out: TextIO | None = None) -> int:
    """Write (or read back) the tokens, then run the class's launch until stopped."""
    check_host(options.host, fenced=True)  # a class always has its tokens
    tokens, new = class_tokens(options.tokens, roster)
    spec = class_spec(roster, options)
    launch = LaunchOptions(
        base_port=options.base_port, speed=options.speed, seed=options.seed,
        world_options={"obstacles": options.obstacles},
    )  # fmt: skip
    # The class's processes present a token of their own (the launch hands its environment to
    # each, and its own node reads it), never a class token: the core refuses one as its own.
    os.environ["SKYDECK_TOKEN"] = secrets.token_urlsafe(32)
    supervisor = Supervisor(spec, launch, out=out, control=True, settings=LaunchSettings())
    written = "written to" if new else "read back from"
    say(out, f"a class of {len(roster.students)}: tokens {written} {options.tokens} (hand each student their line)")
    say(out, f"the class page: {_page(options)} (sign in with the instructor's token)")
    return asyncio.run(supervisor.run())


def _page(options: ClassOptions) -> str:
    host = options.advertise or ("127.0.0.1" if _is_loopback(options.host) else reachable_host(options.host))
    return f"http://{host}:{options.base_port}/#class"

