"""Assignment files: what to run, in which world, for how long, and what to score.

    assignment = load_assignment(Path("examples/assignments/wall_follower.yaml"))
    assignment.seeds_for("visible")            # [1, 2]
    assignment.seeds_for("hidden", secret="...")  # derived from the instructor's secret

The file (YAML), every field checked; anything else is an error naming the file and the field::

    assignment: wall_follower          # its name (the file's, by convention)
    title: Follow the wall on the right
    world: robot                       # a world of sim_server/worlds.py
    options: {obstacles: 4}            # the world's own options
    duration_s: 40                     # the run's length, sim seconds
    nodes: []                          # built-in nodes the world needs beside the student's
    parameters: {distance: 0.5}        # ROS parameters given to the student's nodes
    seeds:
      visible: [1, 2]                  # students may run these
      hidden: 3                        # this many more, from SKYDECK_GRADE_SECRET
    reference: wall_follower           # a built-in node that passes (for instructors and tests)
    criteria:
      - name: wall_follower.band_fraction
        params: {distance: 0.5, tolerance: 0.15}
        min: 0.8                       # passes when the figure is >= 0.8 (max: <=)

Hidden seeds: the repository (and so every student) can read this file, so it says only how many
hidden seeds there are; each is an HMAC of the instructor's secret and the assignment's name, so
only whoever holds the secret can run them, and the same secret gives the same seeds every term.
"""

from __future__ import annotations

import hashlib
import hmac
import math
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from services.grading.criteria import CRITERIA, CriterionSpec, Options
from shared_models.errors import SkydeckError
from shared_models.text_files import parse_yaml, read_text_file

__all__ = ["Assignment", "AssignmentError", "CriterionUse", "SeedKind", "load_assignment"]

SeedKind = Literal["visible", "hidden"]
MAX_SEED = 2**32 - 1
MAX_DURATION_S = 600.0


class AssignmentError(SkydeckError):
    """An assignment file that cannot be used: the message names the file and the field."""


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class Seeds(_Strict):
    visible: list[int] = Field(min_length=1, max_length=20)
    hidden: int = Field(default=0, ge=0, le=20)

    @field_validator("visible")
    @classmethod
    def _in_range(cls, seeds: list[int]) -> list[int]:
        for seed in seeds:
            if not 0 <= seed <= MAX_SEED:
                raise ValueError(f"seed {seed} is outside 0..{MAX_SEED}")
        if len(set(seeds)) != len(seeds):
            raise ValueError("a seed is listed twice")
        return seeds


class CriterionUse(_Strict):
    """One criterion as an assignment uses it: its options and its threshold."""

    name: str
    params: dict[str, Any] = {}
    min: float | None = None
    max: float | None = None

    @model_validator(mode="after")
    def _one_threshold(self) -> CriterionUse:
        if (self.min is None) == (self.max is None):
            raise ValueError("give exactly one threshold: min (the figure must be >= it) or max (<=)")
        threshold = self.min if self.min is not None else self.max
        if threshold is not None and not math.isfinite(threshold):
            raise ValueError("the threshold must be a finite number")
        return self

    @property
    def spec(self) -> CriterionSpec:
        return CRITERIA[self.name]

    @property
    def threshold(self) -> float:
        return self.min if self.min is not None else self.max  # type: ignore[return-value]

    @property
    def comparison(self) -> str:
        return ">=" if self.min is not None else "<="

    def passes(self, value: float) -> bool:
        """Whether ``value`` meets the threshold (a figure that could not be measured never does)."""
        if not math.isfinite(value):
            return False
        return value >= self.threshold if self.min is not None else value <= self.threshold

    def options(self) -> Options:
        """The criterion's options, checked by its own model."""
        return self.spec.params.model_validate(self.params)


class Assignment(_Strict):
    """A checked assignment file (see the module docstring)."""

    assignment: str = Field(pattern=r"^[a-z][a-z0-9_]*$", max_length=64)
    title: str = ""
    world: str
    options: dict[str, int | float] = {}
    duration_s: float = Field(gt=0, le=MAX_DURATION_S)
    nodes: list[str] = []
    parameters: dict[str, bool | int | float | str] = {}
    seeds: Seeds
    reference: str = ""
    criteria: list[CriterionUse] = Field(min_length=1)

    @field_validator("world")
    @classmethod
    def _known_world(cls, world: str) -> str:
        from sim_server.worlds import WORLDS

        if world not in WORLDS:
            raise ValueError(f"no world {world!r}: the worlds are {', '.join(WORLDS)}")
        return world

    @field_validator("nodes")
    @classmethod
    def _known_nodes(cls, nodes: list[str]) -> list[str]:
        from services.builtin_nodes import BUILTIN_NODES

        for node in nodes:
            if node not in BUILTIN_NODES or node == "sim":
                raise ValueError(f"{node!r} is not a built-in node (they are {', '.join(n for n in BUILTIN_NODES if n != 'sim')})")
        return nodes

    @field_validator("criteria")
    @classmethod
    def _known_criteria(cls, criteria: list[CriterionUse]) -> list[CriterionUse]:
        names = [c.name for c in criteria]
        for index, use in enumerate(criteria):
            if use.name not in CRITERIA:
                raise ValueError(f"[{index}] no criterion {use.name!r}: they are {', '.join(CRITERIA)}")
            try:
                use.options()
            except ValidationError as error:
                problem = error.errors()[0]
                where = ".".join(str(part) for part in problem["loc"])
                raise ValueError(f"[{index}] {use.name}: params.{where}: {problem['msg']}") from None
            if names.count(use.name) > 1:
                raise ValueError(f"[{index}] {use.name} is listed twice")
        return criteria

    @model_validator(mode="after")
    def _fits_world(self) -> Assignment:
        from sim_server.worlds import WORLDS

        settings = WORLDS[self.world].settings_type()
        own = settings.own_options()
        for name, value in self.options.items():
            if name not in own:
                takes = ", ".join(own) or "none"
                raise ValueError(f"options.{name}: not an option of the {self.world} world (its options: {takes})")
            try:
                settings.model_validate({name: value})
            except ValidationError as error:
                raise ValueError(f"options.{name}: {error.errors()[0]['msg']}") from None
        for index, use in enumerate(self.criteria):
            if use.spec.world != self.world:
                raise ValueError(f"criteria[{index}] {use.name} scores the {use.spec.world} world, not {self.world}")
        return self

    def seeds_for(self, kind: SeedKind, *, secret: str = "") -> list[int]:
        """The seeds of ``kind``; hidden ones need the instructor's secret."""
        if kind == "visible":
            return list(self.seeds.visible)
        if self.seeds.hidden == 0:
            raise AssignmentError(f"{self.assignment} has no hidden seeds (seeds.hidden is 0)")
        if not secret:
            raise AssignmentError(
                "hidden seeds come from the instructor's secret: set SKYDECK_GRADE_SECRET "
                "(students run --seeds visible)"
            )
        return [hidden_seed(secret, self.assignment, index) for index in range(self.seeds.hidden)]


def hidden_seed(secret: str, assignment: str, index: int) -> int:
    """The ``index``-th hidden seed of ``assignment`` under ``secret`` (a 32-bit number)."""
    digest = hmac.new(secret.encode(), f"{assignment}:{index}".encode(), hashlib.sha256).digest()
    return int.from_bytes(digest[:4], "big")


def load_assignment(path: Path) -> Assignment:
    """Read and check an assignment file; AssignmentError names the file and the field."""
    text = read_text_file(path, "assignment file", lambda reason: AssignmentError(f"{path}: {reason}"))
    data = parse_yaml(text, lambda reason: AssignmentError(f"{path}: {reason}"))
    if not isinstance(data, dict):
        raise AssignmentError(f"{path}: an assignment is a mapping of fields (assignment, world, criteria...)")
    try:
        return Assignment.model_validate(data)
    except ValidationError as error:
        problem = error.errors(include_url=False)[0]
        where = ".".join(str(part) for part in problem["loc"]) or "the file"
        message = problem["msg"].removeprefix("Value error, ")
        if problem["type"] == "extra_forbidden":
            message = "not a field of an assignment"
        elif problem["type"] == "missing":
            message = "missing"
        raise AssignmentError(f"{path}: {where}: {message}") from None
