"""A class on one machine (issue 35): ``skydeck class ROSTER`` starts one core, fenced by the
class's tokens, and one robot world with a robot per student under ``/NAME``.

- :mod:`.roster`: the roster file (CSV or YAML), read and checked in one line;
- :mod:`.launch`: the tokens (written once), the address, and the launch of the core and the world.

Above the launcher, below the CLI. The fences themselves are :mod:`services.access`'s; the class
page's data is the core's (:mod:`services.core.classroom`). See docs/class.md.
"""

from services.classroom.launch import ClassOptions, check_host, class_tokens, run_class
from services.classroom.roster import ClassroomError, Roster, read_roster

__all__ = ["ClassOptions", "ClassroomError", "Roster", "check_host", "class_tokens", "read_roster", "run_class"]
