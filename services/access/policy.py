"""The one place the rules live: who (a subject) may do what (a verb) to which name.

    policy = Policy(tokens=TokenSet(read_tokens(path)), process_token="", rules=ClassRules())
    alice = policy.subject("TOKEN-OF-ALICE")           # Subject(STUDENT, "alice")
    policy.refusal(alice, Verb.PUBLISH, "/bob/cmd_vel") # Forbidden("alice may publish only under /alice ...")

Subjects, by the token a request presents:

- **instructor** (the class's ``instructor`` token) and **operator** (the process token,
  ``SKYDECK_TOKEN``: the instructor's own processes, the simulator, the launch): everything;
- **student NAME** (their class token): publish, call services, serve services, register nodes
  and set parameters only under ``/NAME``, plus what the class shares (:class:`ClassRules`);
  read their own namespace, the shared topics and what the rules grant them; stop only their own
  nodes, record only what they may read; never reset the world or change the class;
- **anonymous** (no token, or one nobody has): with no class and no process token, everything
  (Skydeck's default on one machine); with a process token and no class, reading only (today's
  write token); in a class, nothing the fences guard (the pages and the registry stay open).

A verb names what is done, whatever the protocol: every edge (HTTP, the native WebSocket, node
sessions, rosbridge, Foxglove) asks this module, so a rule changes here and nowhere else. Node
and service names count as names (a student's node lives under ``/NAME``); a call of a service
is also a verb of its own when the service is one (:func:`service_verb`: stopping a node,
resetting the world, setting parameters). A refusal is an :class:`AccessRefused`: 401
(:class:`TokenNeeded`) when a token would help, 403 (:class:`Forbidden`) when the subject's
token may not do it; both close a WebSocket with 1008 and say why in one line.
"""

from __future__ import annotations

import enum
import hmac
import json
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Annotated

from pydantic import AfterValidator, BaseModel, ConfigDict, Field

from services.access.tokens import INSTRUCTOR, TokenSet
from services.runtime.auth import NOT_AUTHORISED
from shared_models.close_codes import Close
from shared_models.errors import SkydeckError
from shared_models.names import InvalidNameError, resolve_name

__all__ = [
    "KILL_NODE_SERVICE",
    "WORLD_RESET_SERVICES",
    "AccessRefused",
    "ClassRules",
    "Forbidden",
    "Policy",
    "Role",
    "SharedNames",
    "Subject",
    "TokenNeeded",
    "Verb",
    "name_matches",
    "service_verb",
]

KILL_NODE_SERVICE = "/skydeck_launch/kill_node"
"""The launch's service that stops a node (services/launch/control.py); its request names it."""
WORLD_RESET_SERVICES = frozenset({"/simulator/reset"})
"""The simulator's reset (sim_server/world_node.py; a test checks the two agree)."""
_SET_PARAMETER_SUFFIXES = ("/set_parameters", "/set_parameters_atomically")


class Verb(enum.Enum):
    """What a subject does, whatever the protocol carries it."""

    READ = "read"  # a topic's messages: subscribe, stream, latest message
    PUBLISH = "publish"  # a message on a topic
    CALL = "call"  # a service
    SERVE = "serve"  # host a service (rosbridge's advertise_service, a node's service)
    REGISTER = "register"  # a node, by its name
    SET_PARAMETER = "set_parameter"  # a node's parameters (by its name), ROS 1's parameter server
    KILL_NODE = "kill_node"  # stop a node (by its name)
    RESET_WORLD = "reset_world"  # the simulator's reset
    RECORD = "record"  # record a topic (the core's recordings)
    CONFIGURE = "configure"  # change the class or the core's configuration

    @property
    def phrase(self) -> str:
        """How a refusal says it: ``alice may not <phrase> /bob/scan``."""
        return _PHRASES[self]


_PHRASES = {
    Verb.READ: "read",
    Verb.PUBLISH: "publish on",
    Verb.CALL: "call",
    Verb.SERVE: "serve",
    Verb.REGISTER: "run a node named",
    Verb.SET_PARAMETER: "set parameters of",
    Verb.KILL_NODE: "stop",
    Verb.RESET_WORLD: "reset the world with",
    Verb.RECORD: "record",
    Verb.CONFIGURE: "change",
}


class Role(enum.Enum):
    """What a subject is (see the module docstring)."""

    INSTRUCTOR = "instructor"
    OPERATOR = "operator"
    STUDENT = "student"
    ANONYMOUS = "anonymous"


@dataclass(frozen=True)
class Subject:
    """Who a token says a request comes from."""

    role: Role
    name: str  # a student's name; otherwise the role's

    @property
    def namespace(self) -> str:
        """A student's namespace (``/alice``); ``/`` for everyone else."""
        return f"/{self.name}" if self.role is Role.STUDENT else "/"

    @property
    def privileged(self) -> bool:
        """Whether the subject may do everything (the instructor, the process token)."""
        return self.role in (Role.INSTRUCTOR, Role.OPERATOR)

    def __str__(self) -> str:
        return self.name


class AccessRefused(SkydeckError):
    """A subject may not do what it asked (base of the two refusals; closes with 1008)."""

    http_status = 403
    close_code = Close.POLICY


class Forbidden(AccessRefused):
    """The subject's token may not do this (HTTP 403)."""


class TokenNeeded(AccessRefused):
    """No token, or one nobody has, where a token is needed (HTTP 401)."""

    http_status = 401


# -- names ----------------------------------------------------------------------------------------


def _pattern(text: str) -> str:
    """A name pattern: an absolute name (``/clock``), or everything under one (``/bob/**``, ``/**``)."""
    base = text.removesuffix("/**")
    if base == "" and text == "/**":
        return text
    try:
        if resolve_name(base) != base:
            raise InvalidNameError(base, "not absolute")
    except InvalidNameError:
        raise ValueError(f"{text!r} is not a name pattern: an absolute name (/clock) or /NAME/** for everything under /NAME") from None
    return text


NamePattern = Annotated[str, AfterValidator(_pattern)]


def name_matches(pattern: str, name: str) -> bool:
    """Whether ``name`` is ``pattern`` (a name) or under it (``/bob/**`` holds ``/bob`` and ``/bob/scan``)."""
    if pattern.endswith("/**"):
        base = pattern[:-3]
        return not base or name == base or name.startswith(base + "/")
    return name == pattern


def _under(namespace: str, name: str) -> bool:
    return name == namespace or name.startswith(namespace + "/")


# -- the rules of a class -------------------------------------------------------------------------


class SharedNames(BaseModel):
    """What every student may do beyond their own namespace."""

    model_config = ConfigDict(extra="forbid")

    read: list[NamePattern] = Field(
        default=[
            "/clock", "/tf", "/tf_static",
            "/simulator/world", "/simulator/obstacles", "/simulator/people", "/simulator/boxes",
        ],
        description="topics every student may read: the world everyone shares",
    )  # fmt: skip
    publish: list[NamePattern] = Field(
        default=["/rosout", "/parameter_events"],
        description="topics every student may publish on: what every node publishes",
    )
    call: list[NamePattern] = Field(
        default=["/rosapi/**"], description="services every student may call (rosapi answers from the registry)"
    )


class ClassRules(BaseModel):
    """The rules of a class beyond the defaults, as the instructor writes them (YAML or JSON)::

        shared:
          read: [/clock, /tf, /tf_static, /simulator/world, /simulator/obstacles]
          publish: [/rosout, /parameter_events]
          call: [/rosapi/**]
        reads:                 # more to read for some students (pairs, a demo)
          alice: [/bob/**]
    """

    model_config = ConfigDict(extra="forbid")

    shared: SharedNames = Field(default_factory=SharedNames)
    reads: dict[str, list[NamePattern]] = Field(default_factory=dict, description="student -> more topics to read")


# -- what a service call is -----------------------------------------------------------------------


def service_verb(name: str, body: bytes) -> tuple[Verb, str]:
    """What calling service ``name`` with ``body`` does, and to which name: stopping a node (the
    node it names), resetting the world, setting a node's parameters (the node), or a call."""
    if name == KILL_NODE_SERVICE:
        try:
            node = json.loads(body or b"{}").get("node", "")
        except (ValueError, AttributeError):
            node = ""
        return Verb.KILL_NODE, "/" + node.strip("/") if isinstance(node, str) and node.strip("/") else ""
    if name in WORLD_RESET_SERVICES:
        return Verb.RESET_WORLD, name
    for suffix in _SET_PARAMETER_SUFFIXES:
        if name.endswith(suffix):
            return Verb.SET_PARAMETER, name.removesuffix(suffix)
    return Verb.CALL, name


# -- the policy ---------------------------------------------------------------------------------


class Policy:
    """Who a token is, and what each subject may do (see the module docstring)."""

    def __init__(self, *, tokens: TokenSet | None = None, process_token: str = "", rules: ClassRules | None = None) -> None:
        self.tokens = tokens
        self.process_token = process_token
        self.rules = rules or ClassRules()
        self._anonymous = Subject(Role.ANONYMOUS, "anonymous")
        self._operator = Subject(Role.OPERATOR, "operator")
        self._instructor = Subject(Role.INSTRUCTOR, INSTRUCTOR)

    @property
    def in_class(self) -> bool:
        """Whether a class's tokens are loaded."""
        return self.tokens is not None

    @property
    def open(self) -> bool:
        """Whether everyone may do everything (no class, no process token: one machine's default)."""
        return self.tokens is None and not self.process_token

    def subject(self, token: str) -> Subject:
        """Who presents ``token`` (``""``: none)."""
        if self.tokens is not None:
            name = self.tokens.name_of(token)
            if name == INSTRUCTOR:
                return self._instructor
            if name is not None:
                return Subject(Role.STUDENT, name)
        if self.process_token and token and hmac.compare_digest(token.encode(), self.process_token.encode()):
            return self._operator
        return self._anonymous

    def refusal(self, subject: Subject, verb: Verb, name: str) -> AccessRefused | None:
        """Why ``subject`` may not ``verb`` ``name``; None when it may."""
        if subject.privileged:
            return None
        if subject.role is Role.ANONYMOUS:
            return self._anonymous_refusal(verb, name)
        if self._student_may(subject, verb, name):
            return None
        return Forbidden(self._student_reason(subject, verb, name))

    def _anonymous_refusal(self, verb: Verb, name: str) -> AccessRefused | None:
        if self.open or (not self.in_class and verb is Verb.READ):
            return None
        if not self.in_class:
            return TokenNeeded(NOT_AUTHORISED)
        what = f"{verb.phrase} {name}" if name else verb.phrase
        return TokenNeeded(
            f"this core runs a class: to {what} present your class token (Authorization: Bearer TOKEN or ?token=TOKEN)"
        )

    def _student_may(self, subject: Subject, verb: Verb, name: str) -> bool:
        own = _under(subject.namespace, name)
        shared = self.rules.shared
        if verb is Verb.READ or verb is Verb.RECORD:
            grants = self.rules.reads.get(subject.name, ())
            return own or any(name_matches(p, name) for p in (*shared.read, *grants))
        if verb is Verb.PUBLISH:
            return own or any(name_matches(p, name) for p in shared.publish)
        if verb is Verb.CALL:
            return own or any(name_matches(p, name) for p in shared.call)
        if verb in (Verb.SERVE, Verb.REGISTER, Verb.SET_PARAMETER, Verb.KILL_NODE):
            return own
        return False  # RESET_WORLD, CONFIGURE: the instructor's

    def _student_reason(self, subject: Subject, verb: Verb, name: str) -> str:
        if verb is Verb.RESET_WORLD:
            return f"only the instructor may reset the world ({name}): {subject} may not"
        if verb is Verb.CONFIGURE:
            return f"only the instructor may change the class: {subject} may not"
        if verb is Verb.KILL_NODE and not name:
            return f"{subject} may stop only their own nodes, under {subject.namespace}: name one"
        shared = self._shared_for(subject, verb)
        also = f" and the class's shared {_listed(shared)}" if shared else ""
        return f"{subject} may not {verb.phrase} {name}: only under {subject.namespace}{also}"

    def _shared_for(self, subject: Subject, verb: Verb) -> Sequence[str]:
        shared = self.rules.shared
        if verb in (Verb.READ, Verb.RECORD):
            return [*shared.read, *self.rules.reads.get(subject.name, ())]
        if verb is Verb.PUBLISH:
            return shared.publish
        if verb is Verb.CALL:
            return shared.call
        return ()

    def describe(self, subject: Subject) -> dict[str, object]:
        """What ``subject`` may do, as ``GET /api/access`` answers it (for the dashboard's view
        and ``skydeck run``'s namespace)."""
        described: dict[str, object] = {
            "subject": subject.name,
            "role": subject.role.value,
            "class": self.in_class,
            "namespace": subject.namespace,
        }
        if subject.role is Role.STUDENT:
            own = f"{subject.namespace}/**"
            shared = self.rules.shared
            described["may"] = {
                "read": [own, *shared.read, *self.rules.reads.get(subject.name, ())],
                "publish": [own, *shared.publish],
                "call": [own, *shared.call],
                "serve": [own],
                "register": [own],
                "set_parameter": [own],
                "kill_node": [own],
                "record": [own, *shared.read, *self.rules.reads.get(subject.name, ())],
                "reset_world": [],
                "configure": [],
            }
        else:
            everything = ["/**"] if self.refusal(subject, Verb.PUBLISH, "/x") is None else []
            described["may"] = {verb.value: everything for verb in Verb}
            if subject.role is Role.ANONYMOUS and not self.in_class and self.process_token:
                described["may"] = {verb.value: (["/**"] if verb is Verb.READ else []) for verb in Verb}
        return described


def _listed(names: Sequence[str], most: int = 6) -> str:
    shown = ", ".join(names[:most])
    return shown + (f" (+{len(names) - most} more: GET /api/access)" if len(names) > most else "")
