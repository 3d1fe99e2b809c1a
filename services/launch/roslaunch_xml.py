"""A roslaunch file's XML with line numbers (every error names its line), and the arguments it
declares (``skydeck launch FILE --show-args``), read without evaluating anything."""

from __future__ import annotations

import xml.parsers.expat
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from services.launch.arguments import LaunchArgument
from services.launch.errors import LaunchFileError

__all__ = ["Element", "declared_arguments", "read_xml"]


@dataclass
class Element:
    """One element of the file: its tag, attributes (as written), line, children and text."""

    tag: str
    attributes: dict[str, str]
    line: int
    children: list[Element] = field(default_factory=list)
    text: str = ""


def read_xml(path: Path) -> Element:
    """The file's ``<launch>`` element; LaunchFileError (one line, with the line) otherwise."""
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise LaunchFileError(path, "no such launch file") from None
    except IsADirectoryError:
        raise LaunchFileError(path, "is a folder, not a launch file") from None
    except OSError as error:
        raise LaunchFileError(path, f"cannot read it: {error.strerror or error}") from None
    parser = xml.parsers.expat.ParserCreate()
    stack: list[Element] = []
    roots: list[Element] = []

    def start(tag: str, attributes: dict[str, str]) -> None:
        element = Element(tag, attributes, parser.CurrentLineNumber)
        (stack[-1].children if stack else roots).append(element)
        stack.append(element)

    def end(tag: str) -> None:
        stack.pop()

    def text(data: str) -> None:
        if stack:
            stack[-1].text += data

    def no_doctype(*_: Any) -> None:
        raise LaunchFileError(path, f"line {parser.CurrentLineNumber}: a launch file has no DOCTYPE")

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = text
    parser.StartDoctypeDeclHandler = no_doctype
    try:
        parser.Parse(data, True)
    except xml.parsers.expat.ExpatError as error:
        problem = xml.parsers.expat.ErrorString(error.code)
        raise LaunchFileError(path, f"line {error.lineno}, column {error.offset + 1}: not valid XML: {problem}") from None
    if not roots:
        raise LaunchFileError(path, "the file is empty: expected <launch>...</launch>")
    if roots[0].tag != "launch":
        raise LaunchFileError(path, f"line {roots[0].line}: the top element is <{roots[0].tag}>, expected <launch>")
    return roots[0]


def declared_arguments(path: Path) -> dict[str, LaunchArgument]:
    """The arguments a roslaunch file takes from its command line (``roslaunch --ros-args``):
    its settable ``<arg>``s (those with ``value=`` are fixed), in its groups too, in file
    order; defaults as written (a ``$(...)`` in one is shown, not resolved)."""
    found: dict[str, LaunchArgument] = {}

    def walk(element: Element) -> None:
        for child in element.children:
            if child.tag == "arg" and "name" in child.attributes and "value" not in child.attributes:
                found.setdefault(
                    child.attributes["name"],
                    LaunchArgument(default=child.attributes.get("default"), description=child.attributes.get("doc", "")),
                )
            elif child.tag == "group":
                walk(child)

    walk(read_xml(path))
    return found
