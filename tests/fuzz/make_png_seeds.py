#!/usr/bin/python3
"""Writes the small PNG seeds of corpus/png/: one tiny image per colour type and bit depth libpng
converts to RGBA8 in render/png_io.cpp (grey 1-16 bit, grey+alpha, RGB, RGBA, palettes with
and without tRNS, Adam7 interlacing), so the fuzzer starts from every path of the reader.

usage: tests/fuzz/make_png_seeds.py tests/fuzz/corpus/png
"""
import os
import struct
import sys
import zlib

ADAM7 = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]
CHANNELS = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def sample(x, y, c, depth):
    return (x * 7 + y * 13 + c * 5) % (1 << depth)


def row_bytes(xs, y, color, depth):
    bits = []
    for x in xs:
        for c in range(CHANNELS[color]):
            bits.append(sample(x, y, c, depth))
    if depth == 16:
        return b"".join(struct.pack(">H", v) for v in bits)
    out, acc, n = bytearray(), 0, 0
    for v in bits:
        acc = (acc << depth) | v
        n += depth
        if n == 8:
            out.append(acc)
            acc, n = 0, 0
    if n:
        out.append(acc << (8 - n))
    return bytes(out)


def png(width, height, color, depth, interlace=False, extra=b""):
    raw = b""
    passes = ADAM7 if interlace else [(0, 0, 1, 1)]
    for x0, y0, dx, dy in passes:
        xs = list(range(x0, width, dx))
        if not xs:
            continue
        for y in range(y0, height, dy):
            raw += b"\x00" + row_bytes(xs, y, color, depth)
    return header(width, height, color, depth, interlace) + extra + idat_iend(raw)


def header(width, height, color, depth, interlace=False):
    ihdr = struct.pack(">IIBBBBB", width, height, depth, color, 0, 0, 1 if interlace else 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr)


def idat_iend(raw):
    return chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def main():
    out = sys.argv[1]
    plte = chunk(b"PLTE", bytes(range(48)))  # 16 entries
    seeds = {
        "grey1.png": png(5, 3, 0, 1),
        "grey2.png": png(5, 3, 0, 2),
        "grey4.png": png(5, 3, 0, 4),
        "grey8_trns.png": png(4, 3, 0, 8, extra=chunk(b"tRNS", b"\x00\x07")),
        "grey16.png": png(4, 3, 0, 16),
        "grey_alpha8.png": png(4, 3, 4, 8),
        "grey_alpha16.png": png(4, 3, 4, 16),
        "rgb8.png": png(4, 3, 2, 8),
        "rgb16_trns.png": png(4, 3, 2, 16, extra=chunk(b"tRNS", b"\x00\x01\x00\x02\x00\x03")),
        "rgba8.png": png(4, 3, 6, 8),
        "rgba16.png": png(4, 3, 6, 16),
        "palette1.png": png(5, 3, 3, 1, extra=plte),
        "palette4_trns.png": png(5, 3, 3, 4, extra=plte + chunk(b"tRNS", bytes([0, 128, 255]))),
        "palette8.png": png(4, 3, 3, 8, extra=plte),
        "rgb8_interlaced.png": png(9, 9, 2, 8, interlace=True),
        "grey2_interlaced.png": png(9, 9, 0, 2, interlace=True),
        # The largest side the reader accepts (kMaxImageSide), in a file far too short to hold it.
        "side16384_truncated.png": header(16384, 16384, 6, 8) + idat_iend(b"\x00" * 64),
        # A zTXt chunk claiming 1.5 GB (0x5A5A5A5A bytes) in a 52-byte file: libpng allocated it.
        "ztxt_claiming_1500MB.png": header(4, 3, 0, 8) + struct.pack(">I", 0x5A5A5A5A) + b"zTXt" + b"t\x00\x00xxxxxxxx",
    }
    for name, data in seeds.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
