#!/usr/bin/env python3
"""corpus_gen.py DIR — writes the large or binary cases of the hostile corpus
(tests/e2e/corpus.sh) into DIR at test time, so none is committed as a big
file.  Each file is small to write (under a second in all) and named for the
case that uses it."""
import os
import struct
import sys
import zlib


def png(width, height, rows=None):
    """A PNG whose header claims width x height (8-bit grey); the image data
    is rows (raw scanlines) or none at all."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
    if rows is not None:
        out += chunk(b"IDAT", zlib.compress(rows))
    return out + chunk(b"IEND", b"")


def write(d, name, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(d, name), mode) as f:
        f.write(data)


def sweep(maps=None, mesh=None):
    """A one-configuration sweep using a user map or mesh."""
    text = "name: corpus\nresolution: [16, 16]\nsweep:\n"
    if mesh:
        text += f"  mesh: [file:{mesh}]\n  technique: [normal]\n"
    else:
        text += f"  technique: [pom]\nscene:\n  material: {{ height: {maps} }}\n"
    return text


def main(d):
    # maps: huge header dimensions, truncated data, not an image at all
    write(d, "huge.png", png(1 << 30, 1 << 30))
    write(d, "wide.png", png(2_000_000_000, 1))
    write(d, "zero.png", png(0, 0))
    good = png(4, 4, b"".join(b"\x00" + bytes([i * 16] * 4) for i in range(4)))
    write(d, "truncated.png", good[: len(good) // 2])
    write(d, "empty.png", b"")
    write(d, "text.png", "this is not an image\n")
    write(d, "random.png", bytes((i * 197 + 11) % 256 for i in range(4096)))
    exr = b"\x76\x2f\x31\x01\x02\x00\x00\x00channels\x00chlist\x00\x37\x00\x00\x00Y\x00"
    write(d, "truncated.exr", exr)
    for name in ["huge.png", "wide.png", "zero.png", "truncated.png", "empty.png", "text.png",
                 "random.png", "truncated.exr"]:
        write(d, "map-" + name.replace(".", "-") + ".yaml", sweep(maps=os.path.join(d, name)))
    # meshes: truncated, empty, faces past the vertices, non-finite, binary
    write(d, "truncated.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2")
    write(d, "empty.obj", "")
    write(d, "badindex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999\n")
    write(d, "nan.obj", "v nan 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n")
    write(d, "nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    write(d, "binary.obj", bytes((i * 31 + 7) % 256 for i in range(8192)))
    write(d, "garbage.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000\n"
          "property float x\nend_header\n\x01\x02")
    for name in ["truncated.obj", "empty.obj", "badindex.obj", "nan.obj", "nofaces.obj",
                 "binary.obj", "garbage.ply"]:
        write(d, "mesh-" + name.replace(".", "-") + ".yaml", sweep(mesh=os.path.join(d, name)))
    # sweep files: UTF-16 (both byte orders), binary, one 2 MB line, an alias bomb
    text = "name: x\nsweep:\n  technique: [normal]\n"
    write(d, "utf16le.yaml", b"\xff\xfe" + text.encode("utf-16-le"))
    write(d, "utf16be.yaml", b"\xfe\xff" + text.encode("utf-16-be"))
    write(d, "binary.yaml", bytes((i * 131 + 3) % 256 for i in range(4096)))
    write(d, "longline.yaml", "name: " + "x" * (2 << 20) + "\nsweep:\n  technique: [normal]\n")
    bomb = "name: x\na0: &a0 [x, x, x, x, x, x, x, x, x, x]\n"
    for i in range(1, 12):
        bomb += f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 10) + "]\n"
    write(d, "aliasbomb.yaml", bomb + "sweep:\n  technique: [normal]\n")
    many = "name: x\nsweep:\n" + "".join(
        f"  {ax}: [{', '.join(str(v) for v in vals)}]\n" for ax, vals in
        [("tess_level", range(1, 65)), ("tess_inner", range(1, 65)),
         ("height_scale", [i / 100 for i in range(1, 101)]), ("technique", ["normal", "pom", "phong"])])
    write(d, "toomany.yaml", many)
    # CSV tables for fit --data: 10^5 columns, a binary file, ragged rows
    cols = 100_000
    write(d, "wide.csv", ",".join(f"c{i}" for i in range(cols)) + ",WallTime\n" +
          "".join(",".join([str(r)] * cols) + f",{2 * r}\n" for r in range(1, 5)))
    write(d, "binary.csv", bytes((i * 89 + 5) % 256 for i in range(4096)))
    write(d, "longcell.csv", "x,WallTime\n" + "1" * (1 << 20) + ",2\n")
    # results.json: deep nesting, UTF-16, truncated, wrong types
    write(d, "deep.json", "[" * 100_000 + "]" * 100_000)
    write(d, "deepobj.json", '{"a":' * 50_000 + "1" + "}" * 50_000)
    write(d, "utf16.json", b"\xff\xfe" + '{"runs": []}'.encode("utf-16-le"))
    write(d, "truncated.json", '{"id": "r", "configs": [{"key": "k", "counters": [')


if __name__ == "__main__":
    main(sys.argv[1])
