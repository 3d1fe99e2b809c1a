"""services.bag.mcap_file packs the message and message index records by hand: byte for byte
what the mcap library's own record classes write for the same values."""

from __future__ import annotations

import io

import zstandard
from mcap.data_stream import RecordBuilder
from mcap.records import Chunk, Message, MessageIndex
from mcap.stream_reader import StreamReader

from services.bag.mcap_file import McapFile


def _library_bytes(record: Message | MessageIndex) -> bytes:
    builder = RecordBuilder()
    record.write(builder)
    return builder.end()  # type: ignore[no-any-return]


def test_a_chunk_holds_the_librarys_message_records_and_index() -> None:
    stream = io.BytesIO()
    file = McapFile(stream)
    file.start(profile="", library="test")
    schema = file.register_schema("T", "jsonschema", b"{}")
    first, second = (file.register_channel(topic, "json", schema, {}) for topic in ("/a", "/b"))
    sent = [
        Message(channel_id=first, sequence=7, log_time=100, publish_time=90, data=b'{"x":1}'),
        Message(channel_id=second, sequence=2**32 + 5, log_time=101, publish_time=101, data=b""),
        Message(channel_id=first, sequence=8, log_time=99, publish_time=95, data=b'{"x":2}' * 40),
    ]
    for message in sent:
        file.add_message(message.channel_id, message.log_time, message.publish_time, message.sequence, message.data)
    file.finish()
    stream.seek(0)
    records = list(StreamReader(stream, emit_chunks=True).records)
    (chunk,) = [record for record in records if isinstance(record, Chunk)]
    sent[1].sequence = 5  # MCAP's sequence is 32 bits: a larger header.seq wraps
    expected = [_library_bytes(message) for message in sent]
    assert zstandard.decompress(chunk.data) == b"".join(expected)
    assert (chunk.message_start_time, chunk.message_end_time) == (99, 101)
    offsets = [sum(len(e) for e in expected[:i]) for i in range(len(expected))]
    indexes = [_library_bytes(record) for record in records if isinstance(record, MessageIndex)]
    assert indexes == [
        _library_bytes(MessageIndex(first, [(100, offsets[0]), (99, offsets[2])])),
        _library_bytes(MessageIndex(second, [(101, offsets[1])])),
    ]


def test_a_chunk_is_written_once_full_and_never_empty() -> None:
    stream = io.BytesIO()
    file = McapFile(stream, chunk_size=1000)
    file.start(profile="", library="test")
    channel = file.register_channel("/a", "json", file.register_schema("T", "jsonschema", b"{}"), {})
    file.write_chunk()
    before = stream.tell()
    for i in range(10):
        file.add_message(channel, i, i, i, b"x" * 100)  # 131 bytes a record: the 8th fills it
    assert stream.tell() > before
    written = stream.tell()
    file.write_chunk()
    file.write_chunk()
    file.finish()
    stream.seek(0)
    chunks = [record for record in StreamReader(stream, emit_chunks=True).records if isinstance(record, Chunk)]
    assert [len(zstandard.decompress(c.data)) for c in chunks] == [8 * 131, 2 * 131] and written > before
