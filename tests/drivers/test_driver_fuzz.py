"""Each protocol's hostile corpus (tests/drivers/corpus/NAME/) replayed and
mutated briefly through its fuzz target (c/drivers/fuzz/fuzz_NAME.c), in both
builds: no input crashes a parser or trips a sanitizer. `make fuzz` runs the
long version."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TARGETS = sorted(p.stem.removeprefix("fuzz_") for p in (ROOT / "c" / "drivers" / "fuzz").glob("fuzz_*.c"))


CORPUS = ROOT / "tests" / "drivers" / "corpus"


def corpus_of(name: str) -> Path:
    """A target's hostile corpus; `protocols` (every registered protocol at once) takes them all."""
    return CORPUS if name == "protocols" else CORPUS / name


def test_every_fuzz_target_has_a_corpus():
    assert {"nmea", "digiquartz", "protocols"} <= set(TARGETS), TARGETS
    for name in TARGETS:
        corpus = corpus_of(name)
        assert corpus.is_dir() and len(list(corpus.rglob("*"))) >= 3, f"{name}: a hostile corpus of at least 3 files"


# Mutations per target: the sanitized build is the one that sees a bad read or an
# overflow, so it gets most; the normal build (-O2's code) a few. 100 000 each took
# 6 min of the suite's 2 cores; `make fuzz` is the long run (FUZZ_SECONDS each).
RUNS = {"sanitized": 20_000, "normal": 3_000}
# A radio input writes its chunks to a spool (files, renames): 5 times the cost of a
# parser's; its long run is `make fuzz`.
RUNS_OF = {"radio": {"sanitized": 4_000, "normal": 1_000}}


@pytest.mark.parametrize("name", TARGETS)
def test_corpus_and_mutations_do_not_crash(name, variant_dir, child_env, tmp_path):
    exe = variant_dir / "bin" / f"drivers_fuzz_{name}"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    corpus = corpus_of(name)
    p = subprocess.run(
        [
            str(exe),
            "--no-dict",
            "--runs",
            str(RUNS_OF.get(name, RUNS)["sanitized" if variant_dir.name == "san" else "normal"]),
            "--seed",
            "7",
            str(corpus),
        ],
        env=child_env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert p.returncode == 0, p.stdout + p.stderr
    assert "no crash" in p.stdout
    assert not list(tmp_path.glob("*crash*"))
