#!/usr/bin/env python3
"""Writes gradient.png (18x10 RGB) and alpha.png (12x8 RGBA), the sources of the KTX2 test files."""
import struct
import zlib


def png(path, w, h, px, channels):
    raw = b"".join(b"\0" + bytes(c for x in range(w) for c in px(x, y)) for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    colour = {3: 2, 4: 6}[channels]
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, colour, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


png("gradient.png", 18, 10, lambda x, y: (x * 14, y * 25, 128 if (x // 3 + y // 3) % 2 else 40), 3)
png("alpha.png", 12, 8, lambda x, y: (200, 60 + x * 10, 30 + y * 20, 255 if x < 6 else 64), 4)
