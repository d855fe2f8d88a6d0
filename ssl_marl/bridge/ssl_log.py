"""SSL's standard log file (the format of SSL's log recorder and log player).

Layout, integers big-endian: the 12-byte header ``SSL_LOG_FILE``, a 32-bit version
(1), then messages, each a 64-bit receive timestamp (ns), a 32-bit message type
(:data:`MESSAGE_TYPES`), a 32-bit size and the serialised message
(docs/references.md, "SSL network protocols"; RoboCup-SSL/ssl-go-tools, ``pkg/persistence``).
"""

from __future__ import annotations

import os
import struct
from dataclasses import dataclass
from typing import BinaryIO, Iterator

HEADER = b"SSL_LOG_FILE"
VERSION = 1
MESSAGE_TYPES = {"blank": 0, "unknown": 1, "vision_2010": 2, "referee_2013": 3, "vision_2014": 4,
                 "vision_tracker_2020": 5, "index_2021": 6}
_ENTRY = struct.Struct(">qii")


@dataclass(frozen=True)
class LogMessage:
    """One logged message: receive time (ns), type code, serialised payload."""

    timestamp_ns: int
    message_type: int
    payload: bytes


class LogWriter:
    """Writes an SSL log file (``path``; the header at once)."""

    def __init__(self, path: str | os.PathLike) -> None:
        self._file: BinaryIO = open(path, "wb")
        self._file.write(HEADER + struct.pack(">i", VERSION))

    def write(self, timestamp_ns: int, message_type: int, payload: bytes) -> None:
        self._file.write(_ENTRY.pack(int(timestamp_ns), int(message_type), len(payload)) + payload)

    def write_vision(self, timestamp_ns: int, payload: bytes) -> None:
        """A serialised ``SSL_WrapperPacket``."""
        self.write(timestamp_ns, MESSAGE_TYPES["vision_2014"], payload)

    def write_referee(self, timestamp_ns: int, payload: bytes) -> None:
        """A serialised ``Referee``."""
        self.write(timestamp_ns, MESSAGE_TYPES["referee_2013"], payload)

    def write_tracker(self, timestamp_ns: int, payload: bytes) -> None:
        """A serialised ``TrackerWrapperPacket``."""
        self.write(timestamp_ns, MESSAGE_TYPES["vision_tracker_2020"], payload)

    def close(self) -> None:
        self._file.close()

    def __enter__(self) -> "LogWriter":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def read_log(path: str | os.PathLike) -> Iterator[LogMessage]:
    """The messages of an SSL log file in order. ValueError for a file without the
    header or a version other than 1; a truncated last message ends the iteration."""
    with open(path, "rb") as f:
        head = f.read(16)
        if len(head) < 16 or head[:12] != HEADER:
            raise ValueError(f"{path}: not an SSL log file (header {head[:12]!r})")
        (version,) = struct.unpack(">i", head[12:16])
        if version != VERSION:
            raise ValueError(f"{path}: SSL log version {version} is not supported (expected {VERSION})")
        while True:
            entry = f.read(_ENTRY.size)
            if len(entry) < _ENTRY.size:
                return
            ts, kind, size = _ENTRY.unpack(entry)
            if size < 0:
                return
            payload = f.read(size)
            if len(payload) < size:
                return
            yield LogMessage(ts, kind, payload)


def replay(path: str | os.PathLike, vision_sender, referee_sender, speed: float = 1.0, sleep=None) -> int:
    """Send a log's vision and referee messages out again (``*.send(payload)``), paced by
    their timestamps divided by ``speed`` (0 = as fast as possible); messages sent."""
    import time

    sleep = sleep or time.sleep
    first, start, sent = None, time.monotonic(), 0
    for msg in read_log(path):
        if msg.message_type not in (MESSAGE_TYPES["vision_2014"], MESSAGE_TYPES["referee_2013"]):
            continue
        if first is None:
            first = msg.timestamp_ns
        if speed > 0:
            due = start + (msg.timestamp_ns - first) / 1e9 / speed
            wait = due - time.monotonic()
            if wait > 0:
                sleep(wait)
        (vision_sender if msg.message_type == MESSAGE_TYPES["vision_2014"] else referee_sender).send(msg.payload)
        sent += 1
    return sent
