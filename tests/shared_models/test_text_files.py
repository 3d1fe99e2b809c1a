"""Reading a text a user gives: one wording of what can go wrong, raised as the caller's error."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from shared_models.text_files import YamlProblem, parse_yaml, read_text_file

pytestmark = pytest.mark.timeout(10)


class _Mine(Exception):
    pass


def test_a_missing_file_a_folder_and_bytes_that_are_not_utf8_are_the_callers_error(tmp_path: Path) -> None:
    (tmp_path / "latin1.yaml").write_bytes(b"caf\xe9\n")
    for name, said in (("nope.yaml", "no such roster"), (".", "is a folder, not a roster"), ("latin1.yaml", "cannot read it")):
        with pytest.raises(_Mine, match=said):
            read_text_file(tmp_path / name, "roster", _Mine)
    (tmp_path / "ok.yaml").write_text("a: 1\n", encoding="utf-8")
    assert read_text_file(tmp_path / "ok.yaml", "roster", _Mine) == "a: 1\n"


def test_yaml_values_or_nodes_and_a_syntax_error_says_where() -> None:
    assert parse_yaml("a: [1, 2]\n", _Mine) == {"a": [1, 2]}
    node = parse_yaml("a: 1\nb: 2\n", _Mine, nodes=True)
    assert isinstance(node, yaml.MappingNode) and node.value[1][0].start_mark.line == 1
    said: list[YamlProblem] = []

    def mine(reason: YamlProblem) -> _Mine:
        said.append(reason)
        return _Mine(reason)

    with pytest.raises(_Mine) as raised:
        parse_yaml("a: 1\nb: [1, 2\n", mine)
    (reason,) = said
    assert str(raised.value) == reason and reason.startswith("YAML syntax error at line 3, column 1: ")
    assert reason.line == 3 and reason.problem and reason.problem in reason and "\n" not in reason
