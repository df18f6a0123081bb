#!/usr/bin/env python3
"""make_corpus.py — (re)write the seed corpus of fuzz/corpus/ from fixtures/ and the known
reproductions. Run from anywhere: python3 fuzz/make_corpus.py. Idempotent; only writes files
named seed-*, so entries added by hand or kept from fuzzing runs (other names) are left alone.

corpus/fixture_reader/  fixture files (bytes of a JSON file)
corpus/fast_engine/     fuzz_fast_engine's format (fuzz_fast_engine.cpp): header byte, then 24
                        little-endian doubles (raw mode) or a base index and 4-byte operations
                        (structured mode).
"""
import glob
import json
import math
import os
import struct

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIX = os.path.join(ROOT, "fixtures")
OUT_R = os.path.join(ROOT, "fuzz", "corpus", "fixture_reader")
OUT_F = os.path.join(ROOT, "fuzz", "corpus", "fast_engine")

NEEDLE = {"name": "needle",
          "A": [[0, 0, 0], [9, 0, 9], [1.0000000000000002, 1, 1], [1, 1, 1]],
          "B": [[0, -10, 0], [0, 0, 0], [0, 0, 0.3], [0.01, 1, 0]]}
SLIVER = {"name": "sliver",
          "A": [[9, 5, 9], [0, 9, 0], [1, 1, 1], [1.0000000000000002, 1, 1]],
          "B": [[2.333, 4, 2.333], [5.333, 4, 2.333], [2.333, 7, 2.333], [2.333, 4, 5.333]]}
SCALES = [("1e300", 1e300), ("2p260", 2.0**260), ("2p170", 2.0**170), ("2p180", 2.0**180),
          ("2m137", 2.0**-137), ("2m300", 2.0**-300), ("2m450", 2.0**-450)]
# fuzz_fast_engine.cpp's structured bases, in order
BASE_INDEX = {"needle": 0, "sliver": 1}
POW2 = {"2p260": 260, "2p170": 170, "2p180": 180, "2m137": -137, "2m300": -300, "2m450": -450}


def write(path, data):
    if isinstance(data, str):
        data = data.encode()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


def fixture_text(pairs):
    return json.dumps({"pairs": pairs}, allow_nan=False) + "\n"


def raw(pair, header=0):
    xs = [x for v in pair["A"] + pair["B"] for x in v]
    return bytes([header]) + struct.pack("<24d", *[float(x) for x in xs])


def structured(base, ops):
    return bytes([1, base]) + b"".join(bytes(op) for op in ops)


def scaled(pair, s):
    return {"name": pair["name"],
            "A": [[x * s for x in v] for v in pair["A"]],
            "B": [[x * s for x in v] for v in pair["B"]]}


def slug(name):
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in name)


def main():
    for d in (OUT_R, OUT_F):
        for f in glob.glob(os.path.join(d, "seed-*")):
            os.remove(f)

    # Shipped fixtures: as files for the reader, pair by pair for the engine.
    files = sorted(glob.glob(os.path.join(FIX, "*.json")) + glob.glob(os.path.join(FIX, "*", "*.json")))
    for path in files:
        rel = os.path.relpath(path, FIX).replace(os.sep, "-")
        with open(path, "rb") as f:
            data = f.read()
        write(os.path.join(OUT_R, "seed-fixture-" + rel), data)
        try:
            pairs = json.loads(data)["pairs"]
        except Exception:
            continue
        for i, p in enumerate(pairs):
            try:
                blob = raw(p)
            except Exception:
                continue  # malformed entries of fixtures/bad
            stem = rel[:-len(".json")]
            write(os.path.join(OUT_F, "seed-fixture-%s-%02d-%s" % (stem, i, slug(str(p.get("name"))))), blob)

    # The reproductions: needle and sliver.
    for p in (NEEDLE, SLIVER):
        write(os.path.join(OUT_R, "seed-%s.json" % p["name"]), fixture_text([p]))
        write(os.path.join(OUT_F, "seed-%s-raw" % p["name"]), raw(p))
        write(os.path.join(OUT_F, "seed-%s-structured" % p["name"]), structured(BASE_INDEX[p["name"]], []))
        for tag, e in POW2.items():  # op 1: scale by 2^e, e = int16(a | b << 8)
            u = e & 0xFFFF
            write(os.path.join(OUT_F, "seed-%s-structured-scale-%s" % (p["name"], tag)),
                  structured(BASE_INDEX[p["name"]], [(1, u & 0xFF, u >> 8, 0)]))
        # op 0: nudge coordinate 6 (s2.x) by -1 ulp: s2 == s3, A flat (must be rejected)
        write(os.path.join(OUT_F, "seed-%s-structured-flat" % p["name"]),
              structured(BASE_INDEX[p["name"]], [(0, 9 if p is SLIVER else 6, 0xFF, 0xFF)]))

    # smoke.json scaled.
    with open(os.path.join(FIX, "smoke.json")) as f:
        smoke = json.load(f)["pairs"]
    for tag, s in SCALES:
        sp = [scaled(p, s) for p in smoke]
        write(os.path.join(OUT_R, "seed-smoke-x%s.json" % tag), fixture_text(sp))
        for i, p in enumerate(sp):
            write(os.path.join(OUT_F, "seed-smoke-x%s-%02d-%s" % (tag, i, slug(p["name"]))), raw(p))

    # Non-finite input to the engine (definitions §1: rejected): NaN and inf coordinates.
    nested = smoke[0]
    for tag, bad in (("nan", float("nan")), ("inf", float("inf")), ("minus-inf", float("-inf"))):
        for k in (0, 23):
            p = json.loads(json.dumps(nested))
            p["A" if k < 12 else "B"][(k % 12) // 3][k % 3] = bad
            write(os.path.join(OUT_F, "seed-nonfinite-%s-coord%d" % (tag, k)), raw(p))

    # JSON oddities for the reader.
    A = "[[0,0,0],[10,0,0],[0,10,0],[0,0,10]]"
    B = "[[2,2,2],[2.5,2,2],[2,2.5,2],[2,2,2.5]]"
    odd = {
        "name-1e400.json": '{"pairs": [{"name": 1e400, "A": %s, "B": %s}]}\n' % (A, B),
        "coord-string-overflow.json":
            '{"pairs": [{"name": "s", "A": [["pdd:overflow:7",0,0],[10,0,0],[0,10,0],[0,0,10]], "B": %s}]}\n' % B,
        "coord-1.e400.json": '{"pairs": [{"name": "d", "A": [[1.e400,0,0],[10,0,0],[0,10,0],[0,0,10]], "B": %s}]}\n' % B,
        "coord-1e400e5.json": '{"pairs": [{"name": "e", "A": [[1e400e5,0,0],[10,0,0],[0,10,0],[0,0,10]], "B": %s}]}\n' % B,
        "coord-minus01e400.json": '{"pairs": [{"name": "z", "A": [[-01e400,0,0],[10,0,0],[0,10,0],[0,0,10]], "B": %s}]}\n' % B,
        "coord-1e400.json": '{"pairs": [{"name": "big", "A": [[1e400,0,0],[10,0,0],[0,10,0],[0,0,10]], "B": %s}]}\n' % B,
        "duplicate-key-pairs.json":
            '{"pairs": [{"name": "one", "A": %s, "B": %s}], "pairs": [{"name": "two", "A": %s, "B": %s}]}\n' % (A, B, A, B),
        "duplicate-key-entry.json":
            '{"pairs": [{"name": "one", "name": "two", "A": %s, "A": %s, "B": %s}]}\n' % (A, B, B),
        "nul-in-name.json": '{"pairs": [{"name": "a\\u0000b", "A": %s, "B": %s}]}\n' % (A, B),
        "nul-byte-raw.json": '{"pairs": [{"name": "a\x00b", "A": %s, "B": %s}]}\n' % (A, B),
        "nul-byte-after.json": '{"pairs": [{"name": "a", "A": %s, "B": %s}]}\x00\n' % (A, B),
        "empty.json": "",
    }
    for name, text in odd.items():
        write(os.path.join(OUT_R, "seed-odd-" + name), text)


if __name__ == "__main__":
    main()
