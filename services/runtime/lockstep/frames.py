"""The lockstep wire: JSON frames between a coordinator and each process of a run.

A process connects to the coordinator's WebSocket (``SKYDECK_LOCKSTEP_URL``) and says
``hello``; from then on the coordinator asks and the process answers, one request at a time:

    coordinator -> process                      process -> coordinator
    {"op": "step", "id": 8, "what": "advance"}  {"op": "stepped", "id": 8, "time_s": 0.0333,
                                                 "nodes": [{"name": "/sim", "sent": [...]}]}
    {"op": "settle", "id": 9, "max_wait_s": 2,  {"op": "report", "id": 9, "settled": true,
     "clock_s": 0.0333, "expect": [...]}         "nodes": [{"name": "/estop", "sent": [...],
                                                            "received": [...]}]}

``sent`` lists, per topic and reader, the messages a node's endpoint has handed to a reader that
is in the run; ``received``, per topic and publisher, those its links delivered. Only the
process that simulates the world (``stepper``) takes ``step``. A ``settle`` with ``expect``
and ``clock_s`` (the first after a step) is answered once the process has received what the
step published to its nodes (``expect``: their ``received`` counts to reach) and handled it,
then moved its nodes' sim clocks to ``clock_s`` and handled that too (timers fire): every node
has the step's sensor messages before its timers see the new time.
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

StepWhat = Literal["start", "advance"]
"""``start``: publish the world as it is; ``advance``: step one publishing period and publish."""


class _Frame(BaseModel):
    model_config = ConfigDict(extra="forbid")


ChannelCount = tuple[str, str, int]
"""Messages on one topic between one publisher and one reader, counted at one end: (topic, the
node at the other end (the reader for ``sent``, the publisher for ``received``), count). Tuples,
not objects: a run sends thousands of reports."""


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
    nodes: list[NodeCounts] = []
    """What the simulator's nodes have sent, once the step is published."""


# -- coordinator -> process --------------------------------------------------------------------


class SettleFrame(_Frame):
    op: Literal["settle"] = "settle"
    id: int
    max_wait_s: float = Field(gt=0, le=3600)
    clock_s: float | None = Field(default=None, ge=0)
    """Move the nodes' sim clocks here once what ``expect`` names has arrived and is handled."""
    expect: list[NodeCounts] = []
    """Per node of the process: ``received`` counts to wait for first."""


class StepFrame(_Frame):
    op: Literal["step"] = "step"
    id: int
    what: StepWhat


ProcessFrame = Annotated[HelloFrame | ReportFrame | SteppedFrame, Field(discriminator="op")]
CoordinatorFrame = Annotated[SettleFrame | StepFrame, Field(discriminator="op")]

process_frames: TypeAdapter[HelloFrame | ReportFrame | SteppedFrame] = TypeAdapter(ProcessFrame)
coordinator_frames: TypeAdapter[SettleFrame | StepFrame] = TypeAdapter(CoordinatorFrame)
