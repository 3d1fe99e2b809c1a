"""Reading a recording: its summary (``bag info``) and its messages in time order (``bag play``).

    with BagReader("run.mcap") as bag:
        print(bag.summary.message_count)
        for message in bag.messages(topics={"/drone/pose"}):
            ...

A finished file is read through its summary and index (MCAP's seeking reader). A file whose
recorder was killed has neither: it is read from the start, chunk by chunk, up to the last
chunk that is whole and passes its checksum (MCAP's recovery); ``summary.recovered`` says so
and ``summary.ignored_bytes`` how much was left behind. Only a file with nothing readable (not
MCAP, or cut before its first whole chunk) is an error.
"""

from __future__ import annotations

import io
import os
import struct
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO

import zstandard
from mcap.exceptions import McapError
from mcap.reader import SeekingReader
from mcap.records import Channel, Chunk, Message, Metadata, Schema
from mcap.stream_reader import StreamReader, breakup_chunk

from services.bag.cdr import CDR_ENCODING, frame_decoder, skydeck_type_name
from services.bag.cdr import SCHEMA_ENCODING as CDR_SCHEMA_ENCODING
from services.bag.errors import BagFileError
from services.bag.schemas import MESSAGE_ENCODING

__all__ = ["BagMessage", "BagReader", "BagSummary", "TopicSummary"]

_MAGIC = b"\x89MCAP0\r\n"
# What a cut or damaged record raises inside the mcap library (lz4 raises RuntimeError).
_DAMAGE = (McapError, struct.error, ValueError, EOFError, zstandard.ZstdError, RuntimeError, UnicodeDecodeError)


@dataclass(frozen=True)
class TopicSummary:
    """One topic of a recording."""

    topic: str
    type_name: str
    count: int
    encoding: str = MESSAGE_ENCODING
    latched: bool = False


@dataclass(frozen=True)
class BagSummary:
    """What ``bag info`` prints; times are MCAP log times (receive times), ns since the epoch."""

    path: Path
    size_bytes: int
    start_ns: int
    end_ns: int
    message_count: int
    topics: tuple[TopicSummary, ...]
    metadata: dict[str, dict[str, str]] = field(default_factory=dict)
    recovered: bool = False
    ignored_bytes: int = 0

    @property
    def duration_s(self) -> float:
        return max(self.end_ns - self.start_ns, 0) / 1e9

    def topic(self, name: str) -> TopicSummary | None:
        return next((t for t in self.topics if t.topic == name), None)


@dataclass(frozen=True, slots=True)
class BagMessage:
    """One recorded message: its JSON frame as received, and its times."""

    topic: str
    type_name: str
    frame: str
    log_time_ns: int
    publish_time_ns: int
    sequence: int


class BagReader:
    """An open recording; BagFileError if ``path`` cannot be read as one."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self._decoders: dict[int, tuple[str, Callable[[bytes], str]]] = {}
        try:
            self._file: IO[bytes] = open(self.path, "rb")  # noqa: SIM115 - closed by close()
        except FileNotFoundError:
            raise BagFileError(self.path, "no such file") from None
        except IsADirectoryError:
            raise BagFileError(self.path, "is a folder, not a recording") from None
        except OSError as error:
            raise BagFileError(self.path, f"cannot be read: {error.strerror or error}") from None
        try:
            self.summary = self._read_summary()
        except BaseException:
            self._file.close()
            raise

    def __enter__(self) -> BagReader:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        self._file.close()

    # -- messages ------------------------------------------------------------------------------

    def messages(self, topics: Iterable[str] | None = None, *, start_ns: int | None = None) -> Iterator[BagMessage]:
        """The messages of ``topics`` (default all) from ``start_ns`` on, in receive-time order."""
        wanted = set(topics) if topics is not None else None
        if self.summary.recovered:
            source = self._recovered_messages()
        else:
            self._file.seek(0)
            source = SeekingReader(self._file).iter_messages(topics=wanted, log_time_order=True, starting_at=start_ns)
        for schema, channel, message in source:
            if wanted is not None and channel.topic not in wanted:
                continue
            if start_ns is not None and message.log_time < start_ns:
                continue
            if channel.message_encoding == CDR_ENCODING:
                type_name, decode = self._cdr_decoder(channel, schema)
                frame = decode(message.data)
            else:
                type_name, frame = (schema.name if schema else ""), message.data.decode("utf-8", errors="replace")
            yield BagMessage(channel.topic, type_name, frame, message.log_time, message.publish_time, message.sequence)

    def _cdr_decoder(self, channel: Channel, schema: Schema | None) -> tuple[str, Callable[[bytes], str]]:
        """A CDR channel's Skydeck type and decoder, made once (:mod:`services.bag.cdr`)."""
        found = self._decoders.get(channel.id)
        if found is None:
            if schema is None or schema.encoding != CDR_SCHEMA_ENCODING:
                raise BagFileError(self.path, f"has CDR messages on {channel.topic} without a ros2msg schema")
            found = self._decoders[channel.id] = frame_decoder(channel.topic, schema.name, schema.data)
        return found

    # -- reading the file ----------------------------------------------------------------------

    def _read_summary(self) -> BagSummary:
        size = os.fstat(self._file.fileno()).st_size
        head = self._file.read(len(_MAGIC))
        if head != _MAGIC:
            raise BagFileError(self.path, "is not an MCAP recording (its first bytes are not MCAP's magic)")
        if size >= 2 * len(_MAGIC):
            self._file.seek(-len(_MAGIC), io.SEEK_END)
            if self._file.read(len(_MAGIC)) == _MAGIC:
                finished = self._finished_summary(size)
                if finished is not None:
                    return finished
        return self._recover(size)

    def _finished_summary(self, size: int) -> BagSummary | None:
        """From the summary section; None if the file has none (or it is damaged)."""
        try:
            self._file.seek(0)
            reader = SeekingReader(self._file)
            summary = reader.get_summary()
            if summary is None or summary.statistics is None:
                return None
            metadata = {record.name: dict(record.metadata) for record in reader.iter_metadata()}
        except _DAMAGE:
            return None
        stats = summary.statistics
        topics = tuple(
            _topic_summary(channel, summary.schemas.get(channel.schema_id), stats.channel_message_counts.get(channel.id, 0))
            for channel in summary.channels.values()
        )
        return BagSummary(
            path=self.path,
            size_bytes=size,
            start_ns=stats.message_start_time,
            end_ns=stats.message_end_time,
            message_count=stats.message_count,
            topics=tuple(sorted(topics, key=lambda t: t.topic)),
            metadata=metadata,
        )

    def _recover(self, size: int) -> BagSummary:
        """Read from the start up to the last whole chunk: counts, times, channels, metadata."""
        schemas: dict[int, Schema] = {}
        channels: dict[int, Channel] = {}
        counts: dict[int, int] = {}
        metadata: dict[str, dict[str, str]] = {}
        start_ns, end_ns, total = 0, 0, 0
        for record in self._records_until_damage(schemas, channels, metadata, size):
            if isinstance(record, Message):
                counts[record.channel_id] = counts.get(record.channel_id, 0) + 1
                start_ns = record.log_time if total == 0 else min(start_ns, record.log_time)
                end_ns = max(end_ns, record.log_time)
                total += 1
        if total == 0:
            raise BagFileError(
                self.path, "was not finished and holds no complete chunk of messages: nothing to read"
            )
        topics = tuple(
            _topic_summary(channel, schemas.get(channel.schema_id), counts.get(channel_id, 0))
            for channel_id, channel in channels.items()
        )
        return BagSummary(
            path=self.path,
            size_bytes=size,
            start_ns=start_ns,
            end_ns=end_ns,
            message_count=total,
            topics=tuple(sorted(topics, key=lambda t: t.topic)),
            metadata=metadata,
            recovered=True,
            ignored_bytes=size - self._good_end,
        )

    def _records_until_damage(
        self, schemas: dict[int, Schema], channels: dict[int, Channel], metadata: dict[str, dict[str, str]], size: int
    ) -> Iterator[Schema | Channel | Message | Metadata]:
        """Every record of whole chunks (and outside them), stopping at the first damaged one."""
        self._file.seek(0)
        stream = StreamReader(self._file, emit_chunks=True, record_size_limit=size)
        self._good_end = len(_MAGIC)
        records = stream.records
        while True:
            try:
                record = next(records)
                inner = breakup_chunk(record, validate_crc=True) if isinstance(record, Chunk) else [record]
            except StopIteration:
                return
            except _DAMAGE:
                return
            self._good_end = self._file.tell()
            for item in inner:
                if isinstance(item, Schema):
                    schemas[item.id] = item
                elif isinstance(item, Channel):
                    channels[item.id] = item
                elif isinstance(item, Metadata):
                    metadata[item.name] = dict(item.metadata)
                if isinstance(item, Schema | Channel | Message | Metadata):
                    yield item

    def _recovered_messages(self) -> Iterator[tuple[Schema | None, Channel, Message]]:
        schemas: dict[int, Schema] = {}
        channels: dict[int, Channel] = {}
        for record in self._records_until_damage(schemas, channels, {}, self.summary.size_bytes):
            if isinstance(record, Message) and record.channel_id in channels:
                channel = channels[record.channel_id]
                yield schemas.get(channel.schema_id), channel, record


def _topic_summary(channel: Channel, schema: Schema | None, count: int) -> TopicSummary:
    type_name = schema.name if schema is not None else ""
    if channel.message_encoding == CDR_ENCODING and type_name:  # a ROS 2 type: Skydeck's name
        parts = type_name.split("/")
        type_name = skydeck_type_name(channel.topic, f"{parts[0]}/msg/{parts[-1]}")
    return TopicSummary(
        topic=channel.topic,
        type_name=type_name,
        count=count,
        encoding=channel.message_encoding,
        latched=channel.metadata.get("latching") == "true",
    )
