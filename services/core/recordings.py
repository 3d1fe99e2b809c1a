"""Recording from the dashboard: the core records topics into MCAP files in one folder.

    POST /api/recordings            start (body: {"topics": [...]} or {} for every topic)
    POST /api/recordings/stop       stop; the file is finished (summary and index written)
    GET  /api/recordings            the folder's recordings, and the one in progress
    GET  /api/recordings/NAME.mcap  download one

The core records as ``skydeck bag record -a`` does, through its own node: each topic is read
with a raw tap on the core node's endpoint (one link per publisher, frames as received), so
recording costs the publishers nothing more than one more reader. Files go to
``SKYDECK_RECORDINGS_DIR`` (default ``$XDG_DATA_HOME/skydeck/recordings``, else
``~/.local/share/skydeck/recordings``). Starting and stopping need the token when one is set;
listing and downloading are reads, open as reading topics is.

In a class (docs/security.md), a student records only topics they may read (naming them), stops
only their own recording, and lists and downloads only the files they made; the instructor
does everything.
"""

from __future__ import annotations

import asyncio
import contextlib
import re
import time
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

from fastapi import APIRouter, Body, Depends, HTTPException, Request
from fastapi.responses import FileResponse
from pydantic import BaseModel, Field

from services.access import Pass, Role, Verb
from services.bag.errors import BagError
from services.bag.recording import Limits, Recording, TopicSelection
from services.bag.writer import BagWriter
from services.core.core_node import CoreNode
from services.core.registry import Registry
from services.core.visitors import FENCED, VisitorDep, require
from services.runtime.subscription import RawSubscription
from shared_models import Message, resolve_name

__all__ = ["Recordings", "router"]

_DISCOVERY_PERIOD_S = 0.2
_FLUSH_PERIOD_S = 1.0
_QUEUE_SIZE = 10_000
_FILE_NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]*\.mcap$")


class StartRecording(BaseModel):
    """What to record: the named topics, or every topic (also those that appear later)."""

    topics: list[str] = Field(default_factory=list, description="empty: every topic")
    exclude: str = Field(default="", description="leave out topics this regular expression matches")
    max_duration_s: float | None = Field(default=None, gt=0)


class Recordings:
    """One recording at a time, made by the core's node, into ``folder``."""

    def __init__(self, folder: Path, core_node: CoreNode, registry: Registry, *, command_line: str = "dashboard") -> None:
        self.folder = folder
        self._core = core_node
        self._registry = registry
        self._command_line = command_line
        self._current: Recording | None = None
        self._taps: list[tuple[str, RawSubscription]] = []
        self._task: asyncio.Task[None] | None = None
        self._stopped: dict[str, Any] | None = None
        self._owners: dict[str, str] = {}  # file name -> the subject who recorded it (this core's)

    # -- starting and stopping -----------------------------------------------------------------

    def start(self, request: StartRecording, *, owner: str = "") -> dict[str, Any]:
        """Start recording (for ``owner``, a subject's name); BagError (answered 400/409) if one
        is running or the request is wrong."""
        if self._current is not None:
            raise _Busy(f"already recording to {self._current.writer.path.name}: stop it first")
        try:
            exclude = re.compile(request.exclude) if request.exclude else None
        except re.error as error:
            raise BagError(f"exclude {request.exclude!r} is not a regular expression: {error}") from None
        topics = frozenset(resolve_name(name) for name in request.topics)
        selection = TopicSelection(all_topics=not topics, topics=topics, exclude=exclude)
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
        except OSError as error:
            raise BagError(f"cannot make the recordings folder {self.folder}: {error.strerror or error}") from None
        path = self.folder / time.strftime("skydeck_%Y_%m_%d-%H_%M_%S.mcap")
        suffix = 1
        while path.exists():
            suffix += 1
            path = self.folder / time.strftime(f"skydeck_%Y_%m_%d-%H_%M_%S_{suffix}.mcap")
        writer = BagWriter.create(path, metadata=self._metadata())
        self._owners[path.name] = owner
        self._current = Recording(writer, selection, self._subscribe, limits=Limits(duration_s=request.max_duration_s))
        self._current.update(self._registry.graph()["topics"])
        self._task = asyncio.get_running_loop().create_task(self._run())
        return self.status()

    async def stop(self) -> dict[str, Any]:
        """Stop and finish the file; BagError (409) if nothing is being recorded."""
        if self._current is None:
            raise _Busy("nothing is being recorded")
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._task
        return self._finish()

    def close(self) -> None:
        """The core stops: finish a recording in progress, so its file is whole."""
        if self._task is not None:
            self._task.cancel()
        if self._current is not None:
            self._finish()

    def _finish(self) -> dict[str, Any]:
        recording = self._current
        if recording is None:
            return self._stopped or {}
        for topic, tap in self._taps:
            self._core.stop_reading(topic, tap)
        self._taps.clear()
        recording.writer.close()
        self._current, self._task = None, None
        self._stopped = self._describe(recording, recording_now=False)
        return self._stopped

    def _subscribe(self, topic: str, msg_type: type[Message], on_frame: Callable[[str], None]) -> None:
        tap = RawSubscription(topic, msg_type, on_frame, _QUEUE_SIZE)
        self._core.start_reading(topic, tap)
        self._taps.append((topic, tap))

    async def _run(self) -> None:
        recording = self._current
        if recording is None:
            return
        flushed = time.monotonic()
        while True:
            await asyncio.sleep(_DISCOVERY_PERIOD_S)
            recording.update(self._registry.graph()["topics"])
            duration_s = recording.limits.duration_s
            if duration_s is not None and time.monotonic() - recording.started_s >= duration_s:
                self._finish()
                return
            if time.monotonic() - flushed >= _FLUSH_PERIOD_S:
                recording.check_limits()
                flushed = time.monotonic()

    def _metadata(self) -> dict[str, str]:
        from importlib.metadata import PackageNotFoundError, version

        try:
            skydeck_version = version("skydeck")
        except PackageNotFoundError:
            skydeck_version = "unknown"
        metadata = {"skydeck_version": skydeck_version, "command_line": self._command_line}
        world = self._core.endpoint("/simulator/world")
        latest = world.latest_frame if world is not None else None
        if latest:
            import json

            with contextlib.suppress(ValueError, AttributeError):
                fields = json.loads(latest)
                metadata["world_seed"], metadata["world_id"] = str(fields.get("seed", "")), str(fields.get("id", ""))
        return metadata

    # -- what there is -------------------------------------------------------------------------

    def status(self) -> dict[str, Any]:
        """The recording in progress (or the last one stopped), as the API answers it."""
        if self._current is not None:
            return self._describe(self._current, recording_now=True)
        return self._stopped or {"recording": False}

    @staticmethod
    def _describe(recording: Recording, *, recording_now: bool) -> dict[str, Any]:
        writer = recording.writer
        return {
            "recording": recording_now,
            "name": writer.path.name,
            "url": f"/api/recordings/{writer.path.name}",
            "messages": writer.message_count,
            "topics": writer.counts(),
            "elapsed_s": round(time.monotonic() - recording.started_s, 3),
        }

    def owner_of(self, name: str) -> str:
        """Who recorded the file ``name`` in this core's life (``""``: nobody known)."""
        return self._owners.get(name, "")

    @property
    def recording_owner(self) -> str | None:
        """Who the recording in progress is for (None: none is in progress)."""
        return None if self._current is None else self.owner_of(self._current.writer.path.name)

    def files(self) -> list[dict[str, Any]]:
        """Every ``.mcap`` file of the folder, newest first."""
        if not self.folder.is_dir():
            return []
        found = []
        for path in self.folder.iterdir():
            if path.is_file() and _FILE_NAME.match(path.name):
                stat = path.stat()
                found.append({
                    "name": path.name,
                    "size_bytes": stat.st_size,
                    "modified": stat.st_mtime,
                    "url": f"/api/recordings/{path.name}",
                    "recording": self._current is not None and self._current.writer.path == path,
                })
        return sorted(found, key=lambda item: item["modified"], reverse=True)

    def path_of(self, name: str) -> Path:
        """The file called ``name`` in the folder; 404 for anything else (no path tricks)."""
        path = self.folder / name
        if not _FILE_NAME.match(name) or not path.is_file():
            raise HTTPException(404, f"no recording {name!r}: see GET /api/recordings")
        return path


class _Busy(BagError):
    """A recording is already running (or none is, to stop)."""

    http_status = 409


# -- routes -------------------------------------------------------------------------------------

router = APIRouter(prefix="/api/recordings", tags=["recordings"])


def _recordings(request: Request) -> Recordings:
    return request.app.state.recordings  # type: ignore[no-any-return]


RecordingsDep = Annotated[Recordings, Depends(_recordings)]


def _owns(visitor: Pass, owner: str | None) -> bool:
    """Whether ``visitor`` may see and stop a recording made for ``owner``: its own, or anyone's
    for whoever may record everything (the instructor; anyone with no class)."""
    return visitor.unlimited or (visitor.subject.role is Role.STUDENT and owner == visitor.subject.name)


def _require_reading(visitor: Pass) -> None:
    """401 for a visitor a class shuts out (no token); reading recordings is open otherwise."""
    if visitor.subject.role is Role.ANONYMOUS:
        require(visitor, Verb.READ, "/api/recordings")


@router.get("", responses=FENCED)
async def list_recordings(recordings: RecordingsDep, visitor: VisitorDep) -> dict[str, Any]:
    """The recordings folder: its files (newest first) and the recording in progress, if any (a
    student sees their own)."""
    _require_reading(visitor)
    files = recordings.files()
    current = recordings.status()
    if visitor.subject.role is Role.STUDENT:
        files = [item for item in files if _owns(visitor, recordings.owner_of(item["name"]))]
        if current.get("name") and not _owns(visitor, recordings.owner_of(current["name"])):
            current = {"recording": current.get("recording", False)}
    return {"folder": str(recordings.folder), "current": current, "files": files}


@router.post(
    "", responses=FENCED | {404: {"description": "A topic is not a ROS name"}, 409: {"description": "Already recording"}}
)
async def start_recording(
    recordings: RecordingsDep, visitor: VisitorDep, request: Annotated[StartRecording | None, Body()] = None
) -> dict[str, Any]:
    """Start recording every topic (or the ones named) into a new MCAP file."""
    request = request or StartRecording()
    for topic in [resolve_name(topic) for topic in request.topics] or ["/**"]:  # /**: every topic
        require(visitor, Verb.RECORD, topic)
    return recordings.start(request, owner=visitor.subject.name)


@router.post("/stop", responses=FENCED | {409: {"description": "Nothing to stop"}})
async def stop_recording(recordings: RecordingsDep, visitor: VisitorDep) -> dict[str, Any]:
    """Stop the recording in progress and finish its file."""
    if visitor.subject.role is Role.ANONYMOUS:
        require(visitor, Verb.RECORD, "/**")  # 401 where a token is needed
    owner = recordings.recording_owner
    if owner is not None and not _owns(visitor, owner):
        whose = f"{owner}'s" if owner else "not yours"
        raise HTTPException(403, f"the recording in progress is {whose}: only its owner or the instructor may stop it")
    return await recordings.stop()


@router.get("/{name}", response_class=FileResponse, responses=FENCED | {404: {"description": "No such recording"}})
async def download_recording(name: str, recordings: RecordingsDep, visitor: VisitorDep) -> FileResponse:
    """Download one recording (an MCAP file: `skydeck bag info`, Foxglove, Lichtblick)."""
    _require_reading(visitor)
    path = recordings.path_of(name)
    if visitor.subject.role is Role.STUDENT and not _owns(visitor, recordings.owner_of(name)):
        raise HTTPException(403, f"{visitor.subject} may download only the recordings they made: not {name}")
    return FileResponse(path, media_type="application/octet-stream", filename=name)
