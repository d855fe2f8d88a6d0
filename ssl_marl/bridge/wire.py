"""Protobuf varint framing: the length prefix of the lock-step TCP stream.

A frame is ``varint(len(payload)) + payload`` (the game controller's TCP ports use
the same delimiting). Varints are little-endian base-128, 7 bits per byte, the high
bit set on every byte but the last.
"""

from __future__ import annotations

#: largest payload (bytes) a reader accepts; longer frames are a protocol error
MAX_FRAME_BYTES = 1 << 20


class FrameError(ValueError):
    """A malformed varint or an oversized frame."""


def encode_varint(value: int) -> bytes:
    """The unsigned varint encoding of ``value`` (>= 0)."""
    if value < 0:
        raise ValueError(f"varint: value must be >= 0, got {value}")
    out = bytearray()
    while True:
        byte = value & 0x7F
        value >>= 7
        if value:
            out.append(byte | 0x80)
        else:
            out.append(byte)
            return bytes(out)


def decode_varint(data: bytes, pos: int = 0) -> tuple[int, int] | None:
    """(value, position after it) of the varint at ``pos``, or None when ``data`` ends
    inside it. FrameError for a varint longer than 10 bytes."""
    value, shift = 0, 0
    for i in range(pos, min(len(data), pos + 10)):
        byte = data[i]
        value |= (byte & 0x7F) << shift
        if not byte & 0x80:
            return value, i + 1
        shift += 7
    if len(data) - pos >= 10:
        raise FrameError("varint longer than 10 bytes")
    return None


def encode_frame(payload: bytes) -> bytes:
    """``payload`` with its varint length prefix."""
    return encode_varint(len(payload)) + payload


class FrameReader:
    """Reassembles length-prefixed frames from stream chunks (TCP reads)."""

    def __init__(self, max_bytes: int = MAX_FRAME_BYTES) -> None:
        self.max_bytes = max_bytes
        self._buf = bytearray()

    def feed(self, chunk: bytes) -> list[bytes]:
        """Add ``chunk``; return the frames completed by it (in order). FrameError for
        a bad prefix or a frame above ``max_bytes`` (the stream cannot be resynchronised)."""
        self._buf.extend(chunk)
        frames = []
        while True:
            head = decode_varint(self._buf)
            if head is None:
                return frames
            size, start = head
            if size > self.max_bytes:
                raise FrameError(f"frame of {size} bytes exceeds the limit of {self.max_bytes}")
            if len(self._buf) < start + size:
                return frames
            frames.append(bytes(self._buf[start:start + size]))
            del self._buf[:start + size]
