"""Running a ROS 2 Python launch file: its ``generate_launch_description()`` against Skydeck's
``launch``, ``launch_ros`` and ``ament_index_python`` (:mod:`services.launch.ros2.api`).

While the file runs, a finder first on ``sys.meta_path`` serves those names (and refuses their
other submodules in one line), and any real modules of those names already imported are set
aside, so Skydeck's win even where the ROS 2 extra installed the real ``launch``; afterwards
everything is as it was. An error in the file's own code is one line naming its line.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
import traceback
import types
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

from services.launch.errors import LaunchError
from services.launch.ros2.actions import LaunchDescription
from services.launch.ros2.api import MODULES
from services.launch.ros2.packages import Workspace
from services.launch.ros2.places import Place, not_provided, reading
from services.ros.aliases import AliasLoader

__all__ = ["load_python"]

_TOPS = frozenset(name.partition(".")[0] for name in MODULES)
_API = "services.launch.ros2.api."


def load_python(path: Path, workspace: Workspace) -> LaunchDescription:
    """The description the file's ``generate_launch_description()`` returns."""
    try:
        source = path.read_text(encoding="utf-8")
        code = compile(source, str(path), "exec")
    except SyntaxError as error:
        raise Place(path, error.lineno or 0).error(f"SyntaxError: {error.msg}") from None
    except (OSError, UnicodeDecodeError) as error:
        raise Place(path).error(f"cannot read it: {error}") from None
    namespace = {"__file__": str(path), "__name__": "__launch__", "__builtins__": __builtins__}
    with _served_modules(), reading(path, workspace):
        try:
            exec(code, namespace)
            generate = namespace.get("generate_launch_description")
            if not callable(generate):
                raise Place(path).error("defines no generate_launch_description() (a ROS 2 Python launch file does)")
            description = generate()
        except LaunchError:
            raise
        except Exception as error:  # the file's own code: its line, not our traceback
            raise Place(path, _line_in(error, path)).error(f"{type(error).__name__}: {error}") from None
    if not isinstance(description, LaunchDescription):
        raise Place(path).error(
            f"generate_launch_description() returned {type(description).__name__}, not a LaunchDescription"
        )
    return description


def _line_in(error: BaseException, path: Path) -> int:
    """The last line of ``path`` in the error's traceback."""
    lines = [frame.lineno or 0 for frame in traceback.extract_tb(error.__traceback__) if frame.filename == str(path)]
    return lines[-1] if lines else 0


class _ApiFinder(importlib.abc.MetaPathFinder):
    def find_spec(
        self, fullname: str, path: Sequence[str] | None = None, target: types.ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname in MODULES:
            return importlib.machinery.ModuleSpec(fullname, AliasLoader(_API + MODULES[fullname]), is_package=True)
        if fullname.partition(".")[0] in _TOPS:
            raise not_provided(f"the module {fullname}")
        return None


@contextmanager
def _served_modules() -> Iterator[None]:
    set_aside = {name: sys.modules.pop(name) for name in list(sys.modules) if name.partition(".")[0] in _TOPS}
    finder = _ApiFinder()
    sys.meta_path.insert(0, finder)
    try:
        yield
    finally:
        sys.meta_path.remove(finder)
        for name in [name for name in sys.modules if name.partition(".")[0] in _TOPS]:
            del sys.modules[name]
        sys.modules.update(set_aside)
