"""C and Python team-link codecs write and read the same bits.

Random messages (in range, on the bounds, out of range, NaN) are encoded by the
generated C codec (bin/team-codec-probe) and by auvlcm.team_codec: same bytes,
same refusals. Each side decodes the other's frames to the same values. A
hostile corpus (random bytes, truncations, bit flips) never crashes either
decoder (the sanitized probe checks every read) and both stop at the same
place for the same reason."""

from __future__ import annotations

import math
import random
import subprocess

import pytest
from conftest import c_program

from auvlcm.team_codec import EncodeError, TeamCodec

VARIANTS = pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
C_FAULTS = {-3: "truncated", -4: "unknown_id", -5: "corrupt"}
FRAME_BYTES = 32


@pytest.fixture(scope="module")
def codec() -> TeamCodec:
    return TeamCodec()


def probe(args: list[str], lines: list[str], sanitized: bool, env: dict) -> list[str]:
    r = subprocess.run(
        [c_program("bin/team-codec-probe", sanitized), *args],
        input="".join(line + "\n" for line in lines),
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
    )
    assert r.returncode == 0, r.stderr[-3000:]
    out = r.stdout.splitlines()
    assert len(out) == len(lines)
    return out


def random_value(f, rng: random.Random):
    roll = rng.random()
    if f.is_int:
        lo, hi = int(f.lo), int(f.hi)
        if roll < 0.05:
            return rng.choice([lo - 1, hi + 1, lo - 1000, hi + 1000])
        if roll < 0.15:
            return rng.choice([lo, hi])
        return rng.randint(lo, hi)
    if roll < 0.03:
        return rng.choice([math.nan, math.inf, -math.inf, f.lo - 1e-9, f.hi + 1e-9, f.hi + f.step])
    if roll < 0.13:
        return rng.choice([f.lo, f.hi])
    if roll < 0.23:  # halfway between steps: the rounding rule must agree
        return min(f.hi, f.lo + (rng.randint(0, f.steps) + 0.5) * f.step)
    return rng.uniform(f.lo, f.hi)


def random_frames(codec: TeamCodec, rng: random.Random, n: int):
    frames = []
    for _ in range(n):
        msgs = []
        for _ in range(rng.randint(1, 5)):
            m = rng.choice(codec.schema.messages)
            msgs.append((m.name, {f.name: random_value(f, rng) for f in m.fields}))
        frames.append(msgs)
    return frames


def text_of(msgs) -> str:
    return ";".join(
        " ".join([name] + [repr(float(v)) if isinstance(v, float) else str(v) for v in values.values()])
        for name, values in msgs
    )


def python_encode(codec: TeamCodec, msgs) -> tuple[bytes, int]:
    w = codec.writer(FRAME_BYTES)
    refused = 0
    for name, values in msgs:
        try:
            w.add(name, values)
        except EncodeError:
            refused += 1
    return w.to_bytes(), refused


def parse_c_decode(codec: TeamCodec, line: str):
    body, _, tail = line.rpartition("|")
    rc, left = (int(x) for x in tail.split())
    msgs = []
    for part in filter(None, body.split(";")):
        name, *vals = part.split()
        fields = codec.schema.by_name(name).fields
        msgs.append((name, {f.name: int(v) if f.is_int else float(v) for f, v in zip(fields, vals)}))
    return msgs, rc, left


@VARIANTS
def test_c_and_python_encode_the_same_bytes_and_decode_each_other(codec, sanitized, child_env):
    rng = random.Random(2024)
    frames = random_frames(codec, rng, 400)
    c_out = probe(["encode", str(FRAME_BYTES)], [text_of(f) for f in frames], sanitized, child_env)
    refused_total = 0
    py_frames = []
    for msgs, line in zip(frames, c_out):
        hexpart, refused = line.split()
        data, py_refused = python_encode(codec, msgs)
        assert (hexpart if hexpart != "-" else "") == data.hex(), text_of(msgs)
        assert int(refused) == py_refused, text_of(msgs)
        refused_total += py_refused
        py_frames.append(data)
    assert refused_total > 20  # the corpus did exercise refusals (range, NaN, full frames)
    # Python's frames decoded by C, and C's (the same bytes) by Python: same values.
    c_dec = probe(["decode"], [d.hex() for d in py_frames], sanitized, child_env)
    for data, line in zip(py_frames, c_dec):
        msgs, rc, left = parse_c_decode(codec, line)
        py = codec.decode_frame(data)
        assert rc == 0 and left == 0 and py.ok
        assert msgs == [(m.name, m.values) for m in py.messages]


def hostile_corpus(codec: TeamCodec, rng: random.Random) -> list[bytes]:
    corpus: list[bytes] = [b"", b"\x00", b"\xff", b"\x10", b"\xf0" * 3]
    for _ in range(300):
        corpus.append(bytes(rng.getrandbits(8) for _ in range(rng.randint(1, 40))))
    good = [python_encode(codec, f)[0] for f in random_frames(codec, rng, 60)]
    for g in good:
        corpus += [g[:n] for n in range(len(g))]
        for _ in range(3):
            flipped = bytearray(g)
            if flipped:
                i = rng.randrange(8 * len(g))
                flipped[i // 8] ^= 0x80 >> (i % 8)
            corpus.append(bytes(flipped))
    return corpus


@VARIANTS
def test_hostile_frames_stop_both_decoders_at_the_same_place(codec, sanitized, child_env):
    rng = random.Random(77)
    corpus = hostile_corpus(codec, rng)
    c_dec = probe(["decode"], [d.hex() for d in corpus], sanitized, child_env)
    faults = set()
    for data, line in zip(corpus, c_dec):
        msgs, rc, left = parse_c_decode(codec, line)
        py = codec.decode_frame(data)
        assert msgs == [(m.name, m.values) for m in py.messages], data.hex()
        assert C_FAULTS.get(rc) == py.fault, data.hex()
        assert left == py.undecodable_bits, data.hex()
        faults.add(py.fault)
    assert faults == {None, "truncated", "unknown_id", "corrupt"}


def test_probe_usage_is_exit_2(child_env):
    r = subprocess.run([c_program("bin/team-codec-probe")], capture_output=True, text=True, timeout=30, env=child_env)
    assert r.returncode == 2 and "usage" in r.stderr
