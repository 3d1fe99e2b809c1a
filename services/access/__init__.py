"""Identities and fences: who presents which token, and what each may do, at every edge of the core.

- :mod:`.tokens`: a class's tokens (one per student, one for the instructor), the file they are
  written to once, and the keyed hashes the core keeps instead of them;
- :mod:`.policy`: the one place the rules live (subject x verb x name), and the refusals;
- :mod:`.rates`: each student's rate and calls-in-flight limits on what enters the core;
- :mod:`.fences`: what the core's edges hold, a :class:`Pass` per connection.

Below the core and the protocols, above the SDK: the core, the protocol adapters and the CLI
(``skydeck class``) use it; it uses neither. See docs/security.md.
"""

from services.access.fences import Fences, Pass, load_rules
from services.access.policy import (
    AccessRefused,
    ClassRules,
    Forbidden,
    Policy,
    Role,
    Subject,
    TokenNeeded,
    Verb,
    service_verb,
)
from services.access.rates import RateLimited, RateLimits
from services.access.tokens import (
    INSTRUCTOR,
    ClassTokensError,
    TokenSet,
    check_class_names,
    check_student_name,
    make_class_tokens,
    read_tokens,
    write_tokens,
)

__all__ = [
    "INSTRUCTOR",
    "AccessRefused",
    "ClassRules",
    "ClassTokensError",
    "Fences",
    "Forbidden",
    "Pass",
    "Policy",
    "RateLimited",
    "RateLimits",
    "Role",
    "Subject",
    "TokenNeeded",
    "TokenSet",
    "Verb",
    "check_class_names",
    "check_student_name",
    "load_rules",
    "make_class_tokens",
    "read_tokens",
    "service_verb",
    "write_tokens",
]
