"""One settings object per process: flags over SKYDECK_* over the defaults, built once by the
entry point and passed down; another tool's variables read as fields of the settings."""

from __future__ import annotations

from pathlib import Path

import pytest

from services.cli.settings import CliSettings, cli_settings, use_cli_settings
from services.runtime import Node
from services.runtime.settings import NodeSettings, node_settings, use_node_settings

pytestmark = pytest.mark.timeout(30)


def test_flags_win_over_the_environment_and_none_is_not_a_flag(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SKYDECK_HOST", "0.0.0.0")
    monkeypatch.setenv("SKYDECK_CORE_URL", "http://core:8000")
    settings = NodeSettings.from_flags(host="127.0.0.2", port=None, core_url=None)
    assert (settings.host, settings.port, settings.core_url) == ("127.0.0.2", 0, "http://core:8000")


def test_a_built_in_nodes_port_is_its_own_unless_one_was_given(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("SKYDECK_PORT", raising=False)
    assert NodeSettings().with_default_port(8003).port == 8003
    assert NodeSettings(port=0).with_default_port(8003).port == 0  # given: 0 picks a free port
    monkeypatch.setenv("SKYDECK_PORT", "9123")
    assert NodeSettings().with_default_port(8003).port == 9123


def test_a_node_made_without_settings_takes_the_processs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SKYDECK_CORE_URL", "http://from-the-environment:1")
    assert node_settings().core_url == "http://from-the-environment:1"  # none set: read now
    built = NodeSettings(core_url="http://built-once:2", port=0)
    use_node_settings(built)
    try:
        monkeypatch.setenv("SKYDECK_CORE_URL", "http://changed-since:3")
        assert node_settings() is built
        assert Node("settings_probe").settings is built
    finally:
        use_node_settings(None)


def test_other_tools_variables_are_fields(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.delenv("SKYDECK_STATE_DIR", raising=False)
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    monkeypatch.setenv("ROS_NAMESPACE", "/robot1")
    settings = NodeSettings()
    assert settings.skydeck_state_dir == tmp_path / "state" / "skydeck"
    assert settings.skydeck_data_dir == tmp_path / "data" / "skydeck"
    assert settings.ros_namespace == "/robot1"
    monkeypatch.setenv("SKYDECK_STATE_DIR", str(tmp_path / "mine"))
    assert NodeSettings().skydeck_state_dir == tmp_path / "mine"
    monkeypatch.delenv("XDG_STATE_HOME")
    monkeypatch.delenv("SKYDECK_STATE_DIR")
    assert NodeSettings().skydeck_state_dir == Path.home() / ".local" / "state" / "skydeck"


def test_a_command_reads_its_environment_once(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SKYDECK_CORE_URL", "http://first:1")
    monkeypatch.setenv("SKYDECK_TOKEN", "t")
    use_cli_settings(CliSettings())
    try:
        monkeypatch.setenv("SKYDECK_CORE_URL", "http://second:2")
        assert (cli_settings().core_url, cli_settings().token) == ("http://first:1", "t")
    finally:
        use_cli_settings(None)
    assert cli_settings().core_url == "http://second:2"
