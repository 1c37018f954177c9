"""The team-link codec (docs/modem.md, "The team-link codec"): the schema
parser and generator refuse bad schemas as file:line:col, the Python codec's
rules, and the generated C codec's unit tests in both builds."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest
from conftest import c_program

from auvlcm.team_codec import EncodeError, FrameFull, TeamCodec
from auvlcm.team_schema import DEFAULT_SCHEMA, SchemaError, load, parse_text

GEN = ("-m", "tools.codegen.gen_team_codec")

STATUS = dict(
    vehicle=3,
    time_s=1234,
    north_m=-512.4,
    east_m=1999.6,
    depth_m=12.34,
    heading=6.28318,
    speed=1.54,
    next_line=63,
    state=5,
)


@pytest.fixture(scope="module")
def codec() -> TeamCodec:
    return TeamCodec()


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_c_unit_tests(sanitized, child_env):
    r = subprocess.run(
        [c_program("bin/test_team_codec", sanitized)], capture_output=True, text=True, timeout=120, env=child_env
    )
    assert r.returncode == 0, r.stdout + r.stderr
    assert "all checks passed" in r.stdout


def test_declared_sizes_hold():
    """The sizes the team mission is planned around (a 32-byte fsk80 frame
    holds a status, a contact and an ack)."""
    s = load()
    assert s.by_name("status").nbytes <= 12
    assert s.by_name("contact").nbytes <= 16
    assert s.by_name("ack").nbytes <= 4
    assert s.by_name("ident").nbytes <= 12
    assert sum(s.by_name(n).bits for n in ("status", "contact", "ack")) <= 8 * 32
    # a front summary (docs/sampling.md) beside a status in the team link's 32-byte frame (docs/team.md)
    assert s.by_name("front").nbytes <= 16
    assert math.ceil((s.by_name("status").bits + s.by_name("front").bits) / 8) <= 32
    for m in s.messages:
        assert m.bits == 4 + sum(f.bits for f in m.fields)
        for f in m.fields:
            assert f.bits == math.ceil(math.log2((f.hi - f.lo) / f.step + 1 - 1e-9))


def test_known_bits(codec):
    # id 0011, to 0011, number 0000000101, then zero padding
    assert codec.encode("ack", {"to": 3, "number": 5}) == bytes([0x33, 0x01, 0x40])


def test_round_trip_rounds_to_the_step(codec):
    frame = codec.encode_frame([("status", STATUS), ("ack", {"to": 1, "number": 2})], 32)
    out = codec.decode_frame(frame)
    assert out.ok and out.undecodable_bits == 0
    (st, ack) = out.messages
    assert (st.name, ack.name) == ("status", "ack")
    assert st.values["north_m"] == -512.0 and st.values["east_m"] == 2000.0
    assert st.values["depth_m"] == pytest.approx(12.3, abs=1e-9)
    assert st.values["heading"] == pytest.approx(6.275, abs=1e-9)
    assert st.values["next_line"] == 63 and isinstance(st.values["state"], int)
    assert ack.values == {"to": 1, "number": 2}
    # the decoded values encode to the same bits
    again = codec.encode_frame([(m.name, m.values) for m in out.messages], 32)
    assert again == frame


def test_max_decodes_as_max_and_reencodes(codec):
    v = dict(STATUS, depth_m=102.3)
    got = codec.decode_frame(codec.encode("status", v)).messages[0].values
    assert got["depth_m"] == 102.3
    assert codec.encode("status", got) == codec.encode("status", v)


@pytest.mark.parametrize(
    "field,value",
    [
        ("depth_m", float("nan")),
        ("depth_m", 102.31),
        ("north_m", -math.inf),
        ("heading", -1e-9),
        ("state", 8),
        ("vehicle", -1),
        ("time_s", 1.5),
        ("speed", "fast"),
        ("state", True),
    ],
)
def test_out_of_range_is_refused_not_clamped(codec, field, value):
    w = codec.writer(32)
    with pytest.raises(EncodeError, match=field):
        w.add("status", dict(STATUS, **{field: value}))
    assert w.bits == 0 and w.to_bytes() == b""


def test_unknown_message_and_missing_field_are_refused(codec):
    with pytest.raises(EncodeError, match="no message 'hello'"):
        codec.encode("hello", {})
    with pytest.raises(EncodeError, match="status.state: missing"):
        codec.encode("status", {k: v for k, v in STATUS.items() if k != "state"})
    with pytest.raises(EncodeError, match="no field"):
        codec.encode("ack", {"to": 1, "number": 2, "extra": 3})


def test_a_full_frame_refuses_and_keeps_what_it_holds(codec):
    w = codec.writer(16)
    w.add("status", STATUS)
    before = w.to_bytes()
    with pytest.raises(FrameFull):
        w.add("status", STATUS)
    assert w.to_bytes() == before and w.count == 1
    w.add("ack", {"to": 1, "number": 2})
    assert w.count == 2


def test_decode_stops_at_truncation_unknown_id_and_corrupt_values(codec):
    frame = codec.encode_frame([("ack", {"to": 2, "number": 9}), ("status", STATUS)], 32)
    out = codec.decode_frame(frame[:6])
    assert [m.name for m in out.messages] == ["ack"]
    assert "truncated status at bit 18" in out.error and out.undecodable_bits == 48 - 18
    out = codec.decode_frame(bytes([0xF0, 0x00]))
    assert out.messages == [] and "unknown message id 15" in out.error
    assert out.undecodable_bits == 16
    bad = bytearray(codec.encode("status", STATUS))
    bad[2] |= 0x03
    bad[3] = 0xFF  # north_m raw 4095 > 4000
    bad[4] |= 0xF0
    out = codec.decode_frame(bytes(bad))
    assert out.messages == [] and "north_m" in out.error and "above MAX" in out.error
    assert codec.decode_frame(b"").ok and codec.decode_frame(b"\x00" * 8).messages == []


# ---------------------------------------------------------------- schema faults
GOOD = "message a 1 max_bytes 4\n  x int 0 15\n"


@pytest.mark.parametrize(
    "text,where,message",
    [
        ("message 9a 1 max_bytes 4\n  x int 0 1\n", "1:9", "'9a' is not a name"),
        ("message a 1 max_bytes 4\n  x-y int 0 1\n", "2:3", "'x-y' is not a name"),
        ("message a 1 max_bytes 4\n  int int 0 1\n", "2:3", "keyword"),
        (GOOD + "message b 1 max_bytes 4\n  y int 0 1\n", "3:11", "message id 1 repeats message 'a'"),
        (GOOD + "message a 2 max_bytes 4\n  y int 0 1\n", "3:9", "declared twice"),
        ("message a 16 max_bytes 4\n  x int 0 1\n", "1:11", "1..15"),
        ("message a 0 max_bytes 4\n  x int 0 1\n", "1:11", "1..15"),
        ("message a 1 max_bytes 4\n  x int 5 5\n", "2:11", "MAX 5 must be above MIN 5"),
        ("message a 1 max_bytes 4\n  x fixed 0 -1 0.5\n", "2:13", "MAX -1 must be above MIN 0"),
        ("message a 1 max_bytes 4\n  x fixed 0 1 0\n", "2:15", "STEP 0 must be above 0"),
        ("message a 1 max_bytes 4\n  x fixed 0 1 -0.1\n", "2:15", "STEP -0.1 must be above 0"),
        ("message a 1 max_bytes 4\n  x fixed 0 1 0.3\n", "2:15", "not a whole number of steps"),
        ("message a 1 max_bytes 1\n  x int 0 15\n  y int 0 1\n", "1:9", "over its max_bytes 1"),
        ("message a 1 max_bytes 4\n  x int 0 1.5\n", "2:11", "whole numbers"),
        ("message a 1 max_bytes 4\n  x int 0 ten\n", "2:11", "'ten' is not a number"),
        ("message a 1 max_bytes 4\n  x float 0 1\n", "2:5", "expected 'int MIN MAX'"),
        ("message a 1 max_bytes 4\n  x int 0 1 2\n", "2:13", "expected 'int MIN MAX'"),
        ("  x int 0 1\n", "1:3", "needs a 'message NAME ID max_bytes N' line"),
        ("message a 1 bytes 4\n  x int 0 1\n", "1:1", "expected 'message NAME ID max_bytes N'"),
        ("message a 1 max_bytes 4\n", "1:9", "has no fields"),
        ("message a 1 max_bytes 4\n  x int 0 1\n  x int 0 1\n", "3:3", "repeats in message 'a'"),
        ("# nothing\n", "1:1", "declares no message"),
    ],
)
def test_schema_faults_are_file_line_col(text, where, message):
    with pytest.raises(SchemaError) as e:
        parse_text(text, "s.schema")
    assert any(err.startswith(f"s.schema:{where}: ") and message in err for err in e.value.errors), e.value.errors


def test_every_fault_is_reported_at_once():
    text = "message a 1 max_bytes 4\n  x int 0 0\n  y fixed 0 1 0\nmessage b 1 max_bytes 4\n  z int 0 1\n"
    with pytest.raises(SchemaError) as e:
        parse_text(text, "s.schema")
    assert [err.split(": ")[0] for err in e.value.errors] == ["s.schema:2:11", "s.schema:3:15", "s.schema:4:11"]


def test_generator_refuses_a_bad_schema_with_exit_2_and_writes_nothing(tmp_path):
    bad = tmp_path / "bad.schema"
    bad.write_text("message status 1 max_bytes 2\n  a int 0 1000\n  b fixed 0 1 0\n")
    r = subprocess.run([sys.executable, *GEN, bad, tmp_path / "out"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2
    assert "Traceback" not in r.stderr
    lines = r.stderr.splitlines()
    assert any(line.startswith(f"{bad}:3:15: ") for line in lines), r.stderr
    assert not (tmp_path / "out").exists()
    r = subprocess.run(
        [sys.executable, *GEN, tmp_path / "missing.schema", tmp_path / "out"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert r.returncode == 2 and "cannot read the schema" in r.stderr
    r = subprocess.run([sys.executable, *GEN], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "usage" in r.stderr


def test_generator_output_is_the_build_one(tmp_path, build_dir):
    r = subprocess.run([sys.executable, *GEN, DEFAULT_SCHEMA, tmp_path], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    for name in ("team_codec.h", "team_codec.c"):
        assert (tmp_path / name).read_text() == (build_dir / "gen" / "team" / name).read_text()
