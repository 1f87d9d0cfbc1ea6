# corpus.d/images.sh — images given to `diff` and maps: non-regular files,
# unreadable or huge images, channel layouts, outputs that cannot be
# written; sourced by corpus.sh.
if wanted images; then
P="$SRC/docs/img/pom.png"                 # a valid 320x180 RGBA PNG
P2="$SRC/docs/img/normal.png"             # another of the same size
I="$SRC/tests/data/images"                # the same pixels in several channel layouts
IM="$OUT/images"; mkdir -p "$IM"

# ---- inputs that are not regular files: refused at once, never read ----
ln -sf /dev/zero "$IM/zero.png"; ln -sf /dev/zero "$IM/zero.exr"
rm -f "$IM/fifo.png"; mkfifo "$IM/fifo.png"   # no writer: opening it would block
hcase images/diff-dev-zero 2 "diff: cannot read /dev/zero: not a regular file" -- "$BIN" diff "$P" /dev/zero
hcase images/diff-symlink-zero 2 "not a regular file" -- "$BIN" diff "$IM/zero.png" "$P"
hcase images/diff-symlink-zero-exr 2 "not a regular file" -- "$BIN" diff "$P" "$IM/zero.exr"
hcase images/diff-fifo 2 "not a regular file" -- "$BIN" diff "$P" "$IM/fifo.png"
hcase images/diff-directory 2 "not a regular file" -- "$BIN" diff "$IM" "$P"
hcase images/compare-dev-zero 2 "not a regular file" -- "$BIN" compare /dev/zero "$OUT/ok/latest/results.json"
hcase images/compare-fifo 2 "not a regular file" -- "$BIN" compare "$IM/fifo.png" "$OUT/ok/latest/results.json"
f=$(sweep mapfifo "sweep:" "  technique: [pom]" "scene:" "  material: { height: $IM/fifo.png }")
hcase images/map-fifo 2 "is not a regular file" -- "$BIN" run "$f" --out "$NEVER"
hcase images/mesh-fifo 2 "not a regular file" -- "$BIN" render "mesh=file:$IM/fifo.png" --png "$IM/x.png"

# ---- channel layouts: grey+alpha is grey in RGB and its alpha in A ----
hcase images/grey-alpha 0 "" -- "$BIN" diff "$I/grey-alpha.png" "$I/rgba.png"
if [ "$case_ok" = 1 ] && [ -z "${CORPUS_PROBE:-}" ] && wanted images/grey-alpha; then
  # two opaque images have no silhouette to compare: it is left out, with the reason
  for pair in "grey-alpha.png rgba.png 0" "grey-alpha16.png rgba16.png 0" "grey.png rgba-opaque.png left-out"; do
    read -r a b sil <<<"$pair"
    got=$("$BIN" diff "$I/$a" "$I/$b" --json | python3 -c \
      'import json,sys; d=json.load(sys.stdin); print(d["RMSE"], d.get("SilhouetteError", "left-out" if d.get("SilhouetteErrorLeftOut") else "missing"), d["FLIP"])')
    if [ "$got" = "0 $sil 0" ]; then pass=$((pass+1))
    else echo "FAIL: images/grey-alpha: $a vs $b: RMSE, silhouette, FLIP = $got, want 0 $sil 0"; fail=$((fail+1)); fi
  done
fi

# ---- an address-space limit: the pixels cannot be allocated (was SIGFPE) ----
if wanted images/ulimit-v; then
  python3 - "$IM" <<'EOF'
import struct, sys, zlib
def png(path, n):   # an n x n 8-bit grey PNG of one colour, compressed fast
    c = zlib.compressobj(1); row = b"\x00" + b"\x80" * n
    data = b"".join(c.compress(row) for _ in range(n)) + c.flush()
    def chunk(kind, d):
        return struct.pack(">I", len(d)) + kind + d + struct.pack(">I", zlib.crc32(kind + d))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, 0, 0, 0, 0))
                + chunk(b"IDAT", data) + chunk(b"IEND", b""))
png(sys.argv[1] + "/map16384.png", 16384)   # 4 GB as float RGBA: past the limit at once
EOF
fi
hcase images/ulimit-v-diff 4 "address-space limit" -- "${LIMIT[@]}" "-v 3000000" "$BIN" diff "$IM/map16384.png" "$IM/map16384.png"
f=$(sweep bigmap "resolution: [16, 16]" "sweep:" "  technique: [pom]" "scene:" "  material: { height: $IM/map16384.png }")
hcase images/ulimit-v-map 4 "address-space limit" -- "${LIMIT[@]}" "-v 3000000" "$BIN" run "$f" --dry-run --out "$NEVER"

# ---- output files: a disk that refuses the write is 4, and nothing partial is left ----
# nothing_left ID FILE: after case ID refused the write, neither FILE nor a
# temp file beside it (FILE.tmp.PID) is there.
nothing_left() {
  if [ -z "${CORPUS_PROBE:-}" ] && [ -n "${RAN[$1]+x}" ]; then
    if compgen -G "$2*" >/dev/null; then echo "FAIL: $1 left $(compgen -G "$2*" | head -3)"; fail=$((fail+1))
    else pass=$((pass+1)); fi
  fi
}
rm -rf "$IM/ulf-rep" "$IM/ulf-map.png"*
hcase images/ulimit-f-report 4 "report.html: cannot write: File too large" -- \
  "${LIMIT[@]}" "-f 40" "$BIN" report "$OUT/ok/latest" --out "$IM/ulf-rep"   # report.html is past 40 KB
nothing_left images/ulimit-f-report "$IM/ulf-rep/report.html"
hcase images/ulimit-f-diff-map 4 "File too large" -- "${LIMIT[@]}" "-f 4" "$BIN" diff "$P" "$P2" -o "$IM/ulf-map.png"
nothing_left images/ulimit-f-diff-map "$IM/ulf-map.png"
R1="$OUT/ok/latest/results.json"
hcase images/ulimit-f-compare-json 4 "compare: cannot write $IM/ulf-c.json: File too large" -- \
  "${LIMIT[@]}" "-f 1" "$BIN" compare "$R1" "$R1" --json "$IM/ulf-c.json"
nothing_left images/ulimit-f-compare-json "$IM/ulf-c.json"
hcase images/diff-map-no-dir 2 "cannot write the map $IM/none/m.png: No such file or directory" -- \
  "$BIN" diff "$P" "$P" -o "$IM/none/m.png"
hcase images/diff-map-format 2 "end it in .png, .exr or .tif" -- "$BIN" diff "$P" "$P" -o "$IM/m.bogus"
# A full file system (a 64 KB tmpfs; only where mounting is allowed: root).
if wanted images/full-disk && [ "$(id -u)" = 0 ] && mkdir -p "$IM/full" && mount -t tmpfs -o size=64k tmpfs "$IM/full" 2>/dev/null; then
  hcase images/full-disk-report 4 "No space left on device" -- "$BIN" report "$OUT/ok/latest" --out "$IM/full/rep"
  nothing_left images/full-disk-report "$IM/full/rep/report.html"
  head -c 1M /dev/zero > "$IM/full/filler" 2>/dev/null
  hcase images/full-disk-diff-map 4 "No space left on device" -- "$BIN" diff "$P" "$P2" -o "$IM/full/m.png"
  nothing_left images/full-disk-diff-map "$IM/full/m.png"
  umount "$IM/full"
fi

# ---- control bytes in paths reach neither stdout nor stderr ----
E="$IM/"$'\e]0;pwned\a\e[31m'"red.png"
cp "$P" "$E"
hcase images/diff-ansi-missing 2 "cannot read $IM/?]0;pwned??[31mred-none.png" -- "$BIN" diff "$P" "${E%.png}-none.png"
if wanted images/diff-ansi && [ -z "${CORPUS_PROBE:-}" ]; then
  for other in "$E" "${E%.png}-none.png" "$I/grey.png"; do   # same, missing, another size
    all=$("$BIN" diff "$E" "$other" 2>&1)
    if [[ $all == *$'\e'* || $all == *$'\a'* ]]; then echo "FAIL: diff printed a control byte of a path: $(cat -v <<<"$all" | head -3)"; fail=$((fail+1))
    else pass=$((pass+1)); fi
  done
fi
fi
