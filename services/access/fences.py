"""The fences as the core's edges use them: a :class:`Pass` per connection (or request).

    fences = Fences.load(tokens_file=path, rules_file=None, process_token="", limits=limits)
    visitor = fences.admit(presented_token(websocket))   # once, when a connection opens
    visitor.check(Verb.READ, "/bob/scan")                 # Forbidden / TokenNeeded, or nothing
    visitor.spend(len(frame))                             # per message: RateLimited once over

The rules are :mod:`.policy`'s; a pass remembers each decision it made (a connection asks about
the same few names again and again) and holds its subject's rate bucket (:mod:`.rates`), so a
message costs a dict lookup at most and, for a student, one bucket count. With no class and no
process token, every pass allows everything and counts nothing.
"""

from __future__ import annotations

import hmac
from pathlib import Path

import yaml
from pydantic import ValidationError

from services.access.policy import AccessRefused, ClassRules, Policy, Role, Subject, Verb
from services.access.rates import Bucket, RateLimits
from services.access.tokens import ClassTokensError, TokenSet, read_tokens

__all__ = ["Fences", "Pass", "load_rules"]


class Pass:
    """One connection's subject, the decisions made for it, and its rate bucket (if limited)."""

    __slots__ = ("_decisions", "_policy", "bucket", "subject", "token")

    def __init__(self, policy: Policy, subject: Subject, token: str, bucket: Bucket | None) -> None:
        self._policy = policy
        self.subject = subject
        self.token = token  # the token as presented: a call forwarded to a node carries it on
        self.bucket = bucket
        self._decisions: dict[tuple[Verb, str], AccessRefused | None] = {}

    @property
    def unlimited(self) -> bool:
        """Whether this pass allows everything (then the edges need not ask)."""
        return self.subject.privileged or self._policy.open

    def refusal(self, verb: Verb, name: str) -> AccessRefused | None:
        """Why this subject may not ``verb`` ``name`` (None: it may); decided once per name."""
        key = (verb, name)
        try:
            return self._decisions[key]
        except KeyError:
            refusal = self._decisions[key] = self._policy.refusal(self.subject, verb, name)
            return refusal

    def allows(self, verb: Verb, name: str) -> bool:
        return self.refusal(verb, name) is None

    def check(self, verb: Verb, name: str) -> None:
        """Raise the refusal (TokenNeeded 401, Forbidden 403: both close with 1008) unless allowed."""
        refusal = self.refusal(verb, name)
        if refusal is not None:
            raise type(refusal)(str(refusal))  # a new exception each time: no shared traceback

    def spend(self, size: int) -> None:
        """Count one message of ``size`` bytes against the subject's rate (RateLimited, 4002)."""
        if self.bucket is not None:
            self.bucket.spend(size)


class Fences:
    """The core's policy and rate limits (see the module docstring)."""

    def __init__(self, policy: Policy, limits: RateLimits) -> None:
        self.policy = policy
        self.limits = limits

    @classmethod
    def load(
        cls, *, tokens_file: Path | None, rules_file: Path | None, process_token: str, limits: RateLimits
    ) -> Fences:
        """The fences of a core: a class's when ``tokens_file`` is given (its rules from
        ``rules_file``, else the defaults), else the process token's alone.

        ClassTokensError (one line) for a file that cannot be used, rules without a class, rules
        naming someone the tokens file does not, or a process token that is a class token.
        """
        if tokens_file is None:
            if rules_file is not None:
                raise ClassTokensError(f"class rules ({rules_file}) need the class's tokens: add --class-tokens FILE")
            return cls(Policy(process_token=process_token), limits)
        tokens = read_tokens(tokens_file)
        holder = next((name for name, token in tokens.items() if hmac.compare_digest(token, process_token)), None)
        if process_token and holder is not None:
            raise ClassTokensError(
                f"SKYDECK_TOKEN is {holder}'s class token: the process token must be another (or none)"
            )
        rules = load_rules(rules_file) if rules_file is not None else ClassRules()
        unknown = sorted(set(rules.reads) - set(tokens))
        if unknown:
            raise ClassTokensError(f"{rules_file}: reads names {', '.join(unknown)}, who have no token in {tokens_file}")
        return cls(Policy(tokens=TokenSet(tokens), process_token=process_token, rules=rules), limits)

    @property
    def in_class(self) -> bool:
        return self.policy.in_class

    def admit(self, token: str) -> Pass:
        """The pass of a connection or request presenting ``token`` (``""``: none)."""
        subject = self.policy.subject(token)
        bucket = self.limits.bucket(subject.name) if subject.role is Role.STUDENT else None
        return Pass(self.policy, subject, token, bucket)


def load_rules(path: Path) -> ClassRules:
    """A class's rules from a YAML (or JSON) file; ClassTokensError naming the file and the field."""
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ClassTokensError(f"no class rules file {path}") from None
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as error:
        raise ClassTokensError(f"cannot read {path}: {str(error).splitlines()[0]}") from None
    try:
        return ClassRules.model_validate(data or {})
    except ValidationError as error:
        first = error.errors(include_url=False)[0]
        where = ".".join(str(part) for part in first["loc"]) or "(file)"
        raise ClassTokensError(f"{path}: {where}: {first['msg']}") from None
