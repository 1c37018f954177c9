"""The hostile PD0 corpus (tests/drivers/corpus/pd0/: truncated, bad checksum,
length past the buffer, offsets outside, zero length, a huge cell count,
garbage between ensembles) through the driver's framer and decoder
(build/bin/auv-pd0-dump), in both builds, whole and a byte at a time: each
file gives exactly the ensembles and refusals listed, never a crash."""

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
    "huge_cells.pd0": ["too many cells"],
    "garbage_between.pd0": ["ok", "bad length", "ok"],
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
    if name == "garbage_between.pd0":
        assert summary["garbage_bytes"] > 0


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
