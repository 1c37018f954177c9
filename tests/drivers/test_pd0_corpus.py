"""The hostile PD0 corpus (tests/drivers/corpus/pd0/: truncated, bad checksum,
length past the buffer, offsets outside, zero length, a cell count past the
data, garbage between ensembles, and the shapes of real instruments written by
python/sim/devices/pd0_shapes.py: WinRiver II's 68 data types and 132 cells,
waves packets, an Ocean Surveyor's short leaders, a Sentinel V, a restarted
count, a recording that starts inside an ensemble) through the driver's framer
and decoder (build/bin/auv-pd0-dump), in both builds, whole and a byte at a
time: each file gives exactly the ensembles and refusals listed, never a
crash."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

CORPUS = Path(__file__).parent / "corpus" / "pd0"
EXPECTED = {
    "valid.pd0": ["ok"],
    "truncated.pd0": ["truncated ensemble"],
    "bad_checksum.pd0": ["bad checksum"],
    "length_past_buffer.pd0": ["truncated ensemble"],
    "offset_outside.pd0": ["offset outside ensemble"],
    "zero_length.pd0": ["bad length"],
    "huge_cells.pd0": ["data type cut short"],
    "garbage_between.pd0": ["ok", "bad length", "ok"],  # 7F 7F 7A 7A 7F: a 24-bit length of 8 MB
    "winriver_many_types.pd0": ["ok"],
    "waves_between.pd0": ["ok"] * 2,
    "ocean_surveyor.pd0": ["ok"],
    "sentinel_v.pd0": ["ok"] * 2,
    "count_restarted.pd0": ["ok"] * 3,
    "starts_inside_an_ensemble.pd0": ["ok"] * 2,
}
# the summary's figures of the real instruments' shapes: nothing but the
# waves packets skipped, the count restarted and the half ensemble first
SUMMARY = {
    "winriver_many_types.pd0": {"garbage_bytes": 0},
    "waves_between.pd0": {"garbage_bytes": 0, "waves_packets": 3},
    "ocean_surveyor.pd0": {"garbage_bytes": 0},
    "sentinel_v.pd0": {"garbage_bytes": 0},
    "count_restarted.pd0": {"garbage_bytes": 0, "restarts": 1, "repeats": 0},
}


def dump(exe: Path, path: Path, env: dict[str, str], *args: str) -> list[dict]:
    p = subprocess.run([str(exe), *args, str(path)], env=env, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    return [json.loads(line) for line in p.stdout.splitlines()]


def test_every_corpus_file_has_an_expectation():
    assert sorted(EXPECTED) == sorted(p.name for p in CORPUS.iterdir())


@pytest.mark.parametrize("chunk", ["4096", "1"])
@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_corpus_file(name, chunk, variant_dir, child_env):
    exe = variant_dir / "bin" / "auv-pd0-dump"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    lines = dump(exe, CORPUS / name, child_env, "--chunk", chunk)
    *events, summary = lines
    assert summary["summary"]
    assert [e["reason"] if not e["ok"] else "ok" for e in events] == EXPECTED[name]
    assert summary["ensembles"] == EXPECTED[name].count("ok")
    if name in ("garbage_between.pd0", "starts_inside_an_ensemble.pd0"):
        assert summary["garbage_bytes"] > 0
    for key, value in SUMMARY.get(name, {}).items():
        assert summary[key] == value, (key, summary)


def test_the_real_shapes_are_what_the_generator_writes(tmp_path):
    """The shapes in the corpus are python/sim/devices/pd0_shapes.py's bytes
    (regenerate with `python -m sim.devices.pd0_shapes tests/drivers/corpus/pd0`)."""
    from sim.devices.pd0_shapes import SHAPES, main

    assert main([str(tmp_path)]) == 0
    for name, (_, ensembles) in SHAPES.items():
        assert (tmp_path / name).read_bytes() == (CORPUS / name).read_bytes(), name
        assert EXPECTED[name] == ["ok"] * ensembles


def test_the_fuzz_target_survives_the_corpus(child_env):
    """A short seeded run of the mutation fuzzer on the corpus (make fuzz runs it long)."""
    from conftest import c_program

    exe = c_program("bin/drivers_fuzz_pd0", sanitized=True)
    p = subprocess.run(
        [str(exe), "--no-dict", "--runs", "3000", "--seed", "31", str(CORPUS)],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-4000:]
