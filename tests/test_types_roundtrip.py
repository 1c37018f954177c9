"""Every LCM type encodes and decodes losslessly in Python and in C, and a
truncated or mistyped payload is refused rather than misread."""

from __future__ import annotations

import random
import struct
import subprocess

import pytest
from conftest import c_program
from lcm_samples import random_message, same

from auvlcm.decode import DecodeError, decode_strict
from auvlcm.types import all_types, full_name

SAMPLES_PER_TYPE = 25


def samples(cls, seed: int = 1):
    rng = random.Random(f"{cls.__name__}:{seed}")
    msgs = [random_message(cls, rng, max_len=0)]  # one with every array empty
    msgs += [random_message(cls, rng) for _ in range(SAMPLES_PER_TYPE - 1)]
    return msgs


def test_the_type_set_is_complete():
    # The generated package must hold one class per lcmtypes/*.lcm file.
    from conftest import ROOT

    files = {p.stem for p in (ROOT / "lcmtypes").glob("*.lcm")}
    assert files == {cls.__name__ for cls in all_types()}


@pytest.mark.parametrize("cls", all_types(), ids=lambda c: c.__name__)
def test_python_round_trip(cls):
    for msg in samples(cls):
        data = msg.encode()
        back = decode_strict(cls, data)
        assert same(msg, back), f"{cls.__name__} changed in a round trip"
        assert back.encode() == data


@pytest.mark.parametrize("cls", all_types(), ids=lambda c: c.__name__)
def test_python_refuses_truncated_and_mistyped(cls):
    data = samples(cls)[-1].encode()
    for cut in range(len(data)):
        with pytest.raises(DecodeError):
            decode_strict(cls, data[:cut])
    with pytest.raises(DecodeError) as info:
        decode_strict(cls, data + b"\0")
    assert info.value.kind == "malformed"
    wrong = bytes([data[0] ^ 0xFF]) + data[1:]
    with pytest.raises(DecodeError) as info:
        decode_strict(cls, wrong)
    assert info.value.kind == "wrong_fingerprint"


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_c_round_trip_of_python_encoded_messages(tmp_path, sanitized):
    """C decodes what Python encoded and re-encodes it byte for byte."""
    for cls in all_types():
        with open(tmp_path / f"{full_name(cls)}.bin", "wb") as f:
            for msg in samples(cls, seed=2):
                data = msg.encode()
                f.write(struct.pack(">I", len(data)) + data)
    probe = c_program("bin/auv-lcm-probe", sanitized)
    run = subprocess.run([probe, "roundtrip", tmp_path], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    lines = dict(line.split(" ", 1)[::-1] for line in run.stdout.split("\n") if line)
    expected = {f"{full_name(c)} {SAMPLES_PER_TYPE}" for c in all_types()}
    assert set(lines) == expected
    assert set(lines.values()) == {"ok"}


def test_c_reports_a_missing_or_corrupt_sample_file(tmp_path):
    cls = all_types()[0]
    data = random_message(cls, random.Random(3)).encode()
    (tmp_path / f"{full_name(cls)}.bin").write_bytes(struct.pack(">I", len(data)) + data[:-1])
    run = subprocess.run(
        [c_program("bin/auv-lcm-probe"), "roundtrip", tmp_path], capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 1
    assert f"FAIL {full_name(cls)}" in run.stdout
    assert "no samples" in run.stderr  # every other type has no file
