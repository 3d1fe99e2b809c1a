"""The lockstep wire: JSON frames between a coordinator and each process of a run.

A process connects to the coordinator's WebSocket (``SKYDECK_LOCKSTEP_URL``) and says
``hello``; from then on the coordinator asks and the process answers, one request at a time:

    coordinator -> process                      process -> coordinator
    {"op": "settle", "id": 7, "max_wait_s": 5}  {"op": "report", "id": 7, "settled": true,
                                                 "nodes": [{"name": "/sim", "sent": [...],
                                                            "received": [...]}]}
    {"op": "step", "id": 8, "what": "advance"}  {"op": "stepped", "id": 8, "time_s": 0.0333}

``sent`` lists, per topic and reader, the messages a node's endpoint has handed to a reader that
is in the run; ``received``, per topic and publisher, those its links delivered. Only the
process that simulates the world (``stepper``) takes ``step``.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter

__all__ = [
    "ChannelCount",
    "CoordinatorFrame",
    "HelloFrame",
    "NodeCounts",
    "ProcessFrame",
    "ReportFrame",
    "SettleFrame",
    "StepFrame",
    "SteppedFrame",
    "StepWhat",
    "coordinator_frames",
    "process_frames",
]

StepWhat = Literal["start", "advance", "clock"]
"""``start``: publish the world as it is (clock included); ``advance``: step one publishing
period and publish what the world's sensors say (not the clock); ``clock``: publish the clock."""


class _Frame(BaseModel):
    model_config = ConfigDict(extra="forbid")


class ChannelCount(_Frame):
    """Messages on one topic between one publisher and one reader, counted at one end."""

    topic: str
    peer: str
    """The node at the other end: the reader (for ``sent``) or the publisher (``received``)."""
    count: int


class NodeCounts(_Frame):
    name: str
    sent: list[ChannelCount] = []
    received: list[ChannelCount] = []


# -- process -> coordinator --------------------------------------------------------------------


class HelloFrame(_Frame):
    op: Literal["hello"] = "hello"
    pid: int
    stepper: bool = False


class ReportFrame(_Frame):
    op: Literal["report"] = "report"
    id: int
    settled: bool
    """False: still busy when ``max_wait_s`` ran out."""
    stepper: bool = False
    nodes: list[NodeCounts] = []


class SteppedFrame(_Frame):
    op: Literal["stepped"] = "stepped"
    id: int
    time_s: float


# -- coordinator -> process --------------------------------------------------------------------


class SettleFrame(_Frame):
    op: Literal["settle"] = "settle"
    id: int
    max_wait_s: float = Field(gt=0, le=3600)


class StepFrame(_Frame):
    op: Literal["step"] = "step"
    id: int
    what: StepWhat


ProcessFrame = Annotated[HelloFrame | ReportFrame | SteppedFrame, Field(discriminator="op")]
CoordinatorFrame = Annotated[SettleFrame | StepFrame, Field(discriminator="op")]

process_frames: TypeAdapter[HelloFrame | ReportFrame | SteppedFrame] = TypeAdapter(ProcessFrame)
coordinator_frames: TypeAdapter[SettleFrame | StepFrame] = TypeAdapter(CoordinatorFrame)
