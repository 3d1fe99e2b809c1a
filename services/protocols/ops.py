"""One way for every endpoint to read a JSON op and to refuse it.

A protocol's text frame is one op: a JSON object whose ``"op"`` names it (rosbridge's
``subscribe``, Foxglove's ``getParameters``). An endpoint lists its ops once, each with the
pydantic model that reads it and the handler that carries it out (:class:`JsonOps`), and reads
every frame in two steps, so that a reply can carry the op's ``id`` even when its fields are bad:

    frame = ops.parse(text)        # Refused: not JSON, not an object, no "op"
    await ops.dispatch(frame)      # Refused: an unknown op, or a bad field (named); the handler's own

Anything an op cannot do raises :class:`Refused` (or another ``SkydeckError``); the endpoint
answers it with its protocol's error (rosbridge's ``status``, Foxglove's ``status``) for that op
alone, and the connection and everyone else carry on.
"""

from __future__ import annotations

import inspect
import json
from collections.abc import Awaitable, Callable, Mapping
from typing import Any

from pydantic import BaseModel, ConfigDict, ValidationError

from shared_models.errors import SkydeckError

__all__ = ["JsonOps", "Op", "Refused", "describe_error"]


class Refused(SkydeckError):
    """An op (or frame) that cannot be carried out: answered with the protocol's error reply,
    nothing else happens."""

    http_status = 400


class Op(BaseModel):
    """An op's fields: those a model names are checked, the rest ignored (clients send more,
    e.g. roslibjs's ``latch``), and a bad one is named in the refusal."""

    model_config = ConfigDict(extra="ignore", strict=True)

    op: str


Handler = Callable[[Any], Awaitable[None] | None]


class JsonOps:
    """A protocol's ops: name -> (model, handler). ``protocol`` names it in refusals."""

    def __init__(self, protocol: str, ops: Mapping[str, tuple[type[Op], Handler]]) -> None:
        self.protocol = protocol
        self._ops = dict(ops)

    @property
    def names(self) -> list[str]:
        return list(self._ops)

    def parse(self, text: str) -> dict[str, Any]:
        """The op object of one text frame; Refused if it is not a JSON object with an "op"."""
        try:
            frame = json.loads(text)
        except ValueError as error:
            raise Refused(f"not JSON: {error}") from None
        if not isinstance(frame, dict) or not isinstance(frame.get("op"), str):
            raise Refused(f'a {self.protocol} message is a JSON object with an "op"')
        return frame

    async def dispatch(self, frame: dict[str, Any]) -> None:
        """Read ``frame`` with its op's model and carry it out; Refused for an unknown op or a
        bad field."""
        name = frame["op"]
        found = self._ops.get(name)
        if found is None:
            raise Refused(f"unknown op {name!r}: this endpoint speaks {', '.join(self._ops)}")
        model, handler = found
        try:
            op = model.model_validate(frame)
        except ValidationError as error:
            raise Refused(describe_error(name, error)) from None
        result = handler(op)
        if inspect.isawaitable(result):
            await result


def describe_error(op: str, error: ValidationError) -> str:
    """One line naming the first bad field of an op (``subscribe: topic: Field required``)."""
    first = error.errors(include_url=False)[0]
    where = ".".join(str(part) for part in first["loc"]) or "(op)"
    return f"{op}: {where}: {first['msg']}"
