"""What a ``skydeck`` command reads of its environment, read once by :func:`services.cli.main.main`.

    SKYDECK_CORE_URL    where the core is (default http://127.0.0.1:8000), as ROS_MASTER_URI
    SKYDECK_TOKEN       the write token, sent as ``Authorization: Bearer ...``
    SKYDECK_COMP_WORDS, SKYDECK_COMP_CWORD   the words being completed (the completion scripts set them)
    SKYDECK_GRADE_SECRET  the instructor's secret that ``skydeck grade --seeds hidden`` derives seeds from

The processes a command starts (``skydeck core``, ``skydeck run``, ``skydeck launch``) have their
own settings on top (``CoreProcessSettings``, ``NodeSettings``, ``LaunchSettings``).
"""

from __future__ import annotations

from pydantic_settings import BaseSettings, SettingsConfigDict

from services.runtime.settings import DEFAULT_CORE_URL

__all__ = ["CliSettings", "cli_settings", "use_cli_settings"]


class CliSettings(BaseSettings):
    """The command's environment (see the module docstring)."""

    model_config = SettingsConfigDict(env_prefix="SKYDECK_", extra="ignore")

    core_url: str = DEFAULT_CORE_URL
    token: str = ""
    comp_words: str = ""
    comp_cword: str = ""
    grade_secret: str = ""


_this_command: CliSettings | None = None


def use_cli_settings(settings: CliSettings | None) -> None:
    """Make ``settings`` this command's (``main`` builds them once; None: none)."""
    global _this_command
    _this_command = settings


def cli_settings() -> CliSettings:
    """This command's settings; read from the environment now when no ``main`` built them (a
    function of the CLI called on its own, by a test)."""
    return _this_command if _this_command is not None else CliSettings()
