"""Writing a recording: frames as received, into an MCAP file, without serialising them again.

    writer = BagWriter.create("run.mcap", metadata={"command_line": "skydeck bag record -a"})
    pose = writer.add_topic("/drone/pose", "geometry_msgs/msg/PoseStamped")
    writer.write(pose, frame, time.time_ns())
    writer.close()

Each message keeps its receive time (MCAP's ``log_time``) and its header stamp (``publish_time``,
the receive time for types without a header), and its ``header.seq`` as MCAP's sequence. The
stamp is read from the frame's text, not by parsing it: Skydeck's publishers write the header
first and without spaces, and anything else falls back to a JSON parse.

The records are laid out by :mod:`services.bag.mcap_file` (a message costs a third of what the
``mcap`` library's writer spends on it); schemas and channels go to disk when a topic is added.
Chunks (zstd) are written when they reach ``CHUNK_SIZE`` bytes or when ``flush`` is called (the
recorder does every second), so a recorder that is killed loses at most the chunk in progress:
what was written before is readable (see :mod:`services.bag.reader`). ``close`` writes the
summary and index, which make the file quick to open.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Literal

from services.bag.cdr import CDR_ENCODING, CDR_PROFILE, cdr_schema, frame_encoder
from services.bag.cdr import SCHEMA_ENCODING as CDR_SCHEMA_ENCODING
from services.bag.errors import BagError
from services.bag.mcap_file import McapFile
from services.bag.schemas import (
    MESSAGE_ENCODING,
    PROFILE,
    SCHEMA_ENCODING,
    message_type,
    schema_bytes,
)

__all__ = ["METADATA_NAME", "BagWriter", "Encoding", "bag_path"]

Encoding = Literal["json", "cdr"]

METADATA_NAME = "skydeck"
"""The name of the metadata record every recording starts with (version, command line, world)."""
CHUNK_SIZE = 1024 * 1024
LIBRARY = "skydeck"

# The header as Skydeck's publishers serialise it: first, compact, seq before stamp.
_HEADER = re.compile(rb'\{"header":\{"seq":(\d+),"stamp":\{"sec":(-?\d+),"nanosec":(\d+)\}')


def bag_path(text: str | Path) -> Path:
    """The file a recording named ``text`` goes to: ``.mcap`` added if missing."""
    path = Path(text)
    return path if path.suffix == ".mcap" else path.with_name(path.name + ".mcap")


@dataclass
class _Channel:
    id: int
    topic: str
    type_name: str
    stamped: bool  # the type has a top-level header
    count: int = 0
    encode: Callable[[bytes], bytes] | None = None  # a CDR recording's: frame -> CDR


class BagWriter:
    """One MCAP recording being written; make it with :meth:`create`.

    ``encoding`` ``"json"`` (the default: frames as received, JSON schemas) or ``"cdr"`` (ROS 2's:
    the ``ros2`` profile, ``ros2msg`` schemas, each frame written as CDR; :mod:`services.bag.cdr`).
    """

    def __init__(
        self, stream: IO[bytes], path: Path, metadata: dict[str, str], *, encoding: Encoding = "json"
    ) -> None:
        self.path = path
        self.encoding = encoding
        self._stream = stream
        self._mcap = McapFile(stream, chunk_size=CHUNK_SIZE)
        self._mcap.start(profile=CDR_PROFILE if encoding == "cdr" else PROFILE, library=LIBRARY)
        self._mcap.add_metadata(METADATA_NAME, metadata)
        self._stream.flush()
        self._schemas: dict[str, int] = {}
        self._channels: dict[str, _Channel] = {}
        self._by_id: dict[int, _Channel] = {}
        self._pending = 0  # messages not yet in a written chunk
        self.message_count = 0
        self.closed = False

    @classmethod
    def create(cls, path: str | Path, *, metadata: dict[str, str], encoding: Encoding = "json") -> BagWriter:
        """Start a new recording at ``path``; BagError if it exists or cannot be written."""
        target = Path(path)
        try:
            stream = open(target, "xb")  # noqa: SIM115 - owned by the writer until close()
        except FileExistsError:
            raise BagError(f"{target} already exists: choose another -o or remove it") from None
        except FileNotFoundError:
            raise BagError(f"cannot write {target}: the folder {target.parent} does not exist") from None
        except IsADirectoryError:
            raise BagError(f"cannot write {target}: it is a folder") from None
        except OSError as error:
            raise BagError(f"cannot write {target}: {error.strerror or error}") from None
        return cls(stream, target, metadata, encoding=encoding)

    # -- topics and messages -------------------------------------------------------------------

    def add_topic(self, topic: str, type_name: str, *, latched: bool = False) -> int:
        """The channel id of ``topic`` (added on first use); BagError for an unknown type."""
        channel = self._channels.get(topic)
        if channel is not None:
            if channel.type_name != type_name:
                raise BagError(f"{topic} is recorded as {channel.type_name}, not {type_name}")
            return channel.id
        msg_type = message_type(type_name)
        if self.encoding == "cdr":
            schema_name, schema = cdr_schema(topic, type_name)
            schema_encoding, message_encoding = CDR_SCHEMA_ENCODING, CDR_ENCODING
            encode = frame_encoder(type_name)
        else:
            schema_name, schema = type_name, b""
            schema_encoding, message_encoding, encode = SCHEMA_ENCODING, MESSAGE_ENCODING, None
        schema_id = self._schemas.get(schema_name)
        if schema_id is None:
            schema_id = self._schemas[schema_name] = self._mcap.register_schema(
                schema_name, schema_encoding, schema or schema_bytes(type_name)
            )
        channel_id = self._mcap.register_channel(
            topic, message_encoding, schema_id, {"latching": "true" if latched else "false"}
        )
        self._stream.flush()  # on disk before any chunk that names it
        stamped = next(iter(msg_type.model_fields), None) == "header"
        channel = self._channels[topic] = self._by_id[channel_id] = _Channel(
            channel_id, topic, type_name, stamped, encode=encode
        )
        return channel.id

    def write(self, channel_id: int, frame: str | bytes, receive_ns: int) -> None:
        """Add one message as received; ``receive_ns`` is the wall clock, ns since the epoch."""
        data = frame.encode() if isinstance(frame, str) else frame
        channel = self._by_id[channel_id]
        sequence, publish_ns = _seq_and_stamp(data) if channel.stamped else (0, receive_ns)
        if channel.encode is not None:
            data = channel.encode(data)
        self._mcap.add_message(channel_id, receive_ns, publish_ns if publish_ns >= 0 else receive_ns, sequence, data)
        channel.count += 1
        self.message_count += 1
        self._pending += 1

    def counts(self) -> dict[str, int]:
        """Messages written so far, per topic."""
        return {channel.topic: channel.count for channel in self._channels.values()}

    @property
    def size_bytes(self) -> int:
        """Bytes on disk so far (chunks in progress are not counted until written)."""
        return self._stream.tell()

    # -- life ----------------------------------------------------------------------------------

    def flush(self) -> None:
        """Write the chunk in progress, so a killed recorder keeps it."""
        if self._pending and not self.closed:
            self._mcap.write_chunk()
            self._stream.flush()
            self._pending = 0

    def close(self) -> None:
        """Write the last chunk, the summary and the index, and close the file (twice is fine)."""
        if self.closed:
            return
        self.closed = True
        try:
            self._mcap.finish()
        finally:
            self._stream.close()


def _seq_and_stamp(data: bytes) -> tuple[int, int]:
    match = _HEADER.match(data)
    if match is not None:
        seq, sec, nanosec = match.groups()
        return int(seq), int(sec) * 1_000_000_000 + int(nanosec)
    try:  # a frame from another client: any spacing, any key order
        header = json.loads(data)["header"]
        return int(header.get("seq", 0)), int(header["stamp"]["sec"]) * 1_000_000_000 + int(header["stamp"]["nanosec"])
    except (ValueError, KeyError, TypeError):
        return 0, -1
