#!/usr/bin/env python3
"""Writes the height-map fuzzer's seed corpus (tests/fuzz/corpus): small valid PNG, OpenEXR
and TIFF maps and damaged ones. PNGs are built here byte by byte; the EXR and TIFF maps
come from microrelief-make-map and oiiotool. Usage: make_corpus.py BUILD_DIR [OUT_DIR]"""
import os
import struct
import subprocess
import sys
import zlib

build = sys.argv[1]
out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "corpus")
os.makedirs(out, exist_ok=True)


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def png(width, height, depth, color, rows, interlace=0, extra=b"", plte=b""):
    ihdr = struct.pack(">IIBBBBB", width, height, depth, color, 0, 0, interlace)
    body = chunk(b"IHDR", ihdr) + extra + (chunk(b"PLTE", plte) if plte else b"")
    return b"\x89PNG\r\n\x1a\n" + body + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


def write(name, data):
    with open(os.path.join(out, name), "wb") as f:
        f.write(data)


# Valid PNGs: 8-bit grey 4x4 (filter types 0 to 4), 16-bit grey 3x2, RGBA 2x2, palette 1-bit,
# an Adam7 interlaced 3x3 grey map.
grey = b"".join(bytes([f]) + bytes([(17 * (f + k)) & 255 for k in range(4)]) for f in range(4))
write("grey8_4x4.png", png(4, 4, 8, 0, grey))
write("grey16_3x2.png", png(3, 2, 16, 0, b"\0" + bytes(range(6)) + b"\0" + bytes(range(6, 12))))
write("rgba8_2x2.png", png(2, 2, 8, 6, (b"\0" + bytes(range(8))) * 2))
write("palette1_8x2.png", png(8, 2, 1, 3, b"\0\xa5\0\x5a", plte=b"\0\0\0\xff\xff\xff"))
# Adam7 on 3x3: passes 1 (1x1), 4 (1x1: column 2), 5 (2x1: row 2), 6 (1x2: column 1), 7 (3x1: row 1).
adam7 = b"\0\x10" + b"\0\x20" + b"\0\x30\x40" + b"\0\x50\0\x60" + b"\0\x70\x80\x90"
write("adam7_3x3.png", png(3, 3, 8, 0, adam7, interlace=1))
write("text_chunk.png", png(2, 1, 8, 0, b"\0\1\2", extra=chunk(b"tEXt", b"Title\0map")))

# Damaged PNGs: truncated, a bad CRC on IDAT, a bad filter type, too little data, a header
# that claims 65535 x 40000 (the case) and one of 100000 x 100000.
whole = png(4, 4, 8, 0, grey)
write("truncated_in_idat.png", whole[: len(whole) - 20])
write("truncated_in_ihdr.png", whole[:20])
bad_crc = bytearray(whole)
bad_crc[-14] ^= 0x55
write("bad_idat_crc.png", bytes(bad_crc))
write("bad_filter.png", png(4, 1, 8, 0, b"\x07abcd"))
write("short_data.png", png(4, 4, 8, 0, grey[:10]))
write("claims_65535x40000.png", png(65535, 40000, 8, 0, b"\0" * 64))
write("claims_100000x100000.png", png(100000, 100000, 8, 0, b"\0" * 64))
write("palette_without_plte.png", png(8, 2, 1, 3, b"\0\xa5\0\x5a"))

# OpenEXR and TIFF maps from the programs, and truncated copies.
tmp = os.path.join(out, ".tmp")
os.makedirs(tmp, exist_ok=True)
make_map = os.path.join(build, "bin", "microrelief-make-map")
for name, args in [("noise_4x4.exr", ["noise", "--size", "4x4"]),
                   ("noise_3x5.tif", ["noise", "--size", "3x5"])]:
    subprocess.run([make_map] + args + ["--out", os.path.join(tmp, name)], check=True,
                   stdout=subprocess.DEVNULL)
subprocess.run(["oiiotool", os.path.join(tmp, "noise_4x4.exr"), "-d", "half", "-o",
                os.path.join(tmp, "half_4x4.exr")], check=True)
subprocess.run(["oiiotool", os.path.join(tmp, "noise_3x5.tif"), "-d", "float", "--tile", "16", "16",
                "-o", os.path.join(tmp, "float_tiled_3x5.tif")], check=True)
for name in ["noise_4x4.exr", "half_4x4.exr", "noise_3x5.tif", "float_tiled_3x5.tif"]:
    data = open(os.path.join(tmp, name), "rb").read()
    write(name, data)
    write("truncated_" + name, data[: len(data) * 2 // 3])
for name in os.listdir(tmp):
    os.remove(os.path.join(tmp, name))
os.rmdir(tmp)

# Not images at all.
write("empty.img", b"")
write("text.img", b"height map\n")
