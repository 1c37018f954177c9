"""A short deterministic fuzz run of the Loader (ASan+UBSan) over the corpus
of example plans; `make fuzz` runs the long one."""

from __future__ import annotations

from chasm_common import HERE, run


def test_fuzz_loader_short(build_dir, child_env, tmp_path):
    exe = build_dir / "san" / "bin" / "chasm_fuzz"
    assert exe.exists(), f"{exe} is not built: run `make sanitize`"
    corpus = [HERE / "fuzz_corpus", HERE / "plans", HERE / "bad_plans"]
    p = run([exe, "--runs", "200000", "--seed", "7", *corpus], child_env, cwd=tmp_path, timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "no crash" in p.stdout
    assert not list(tmp_path.glob("chasm-crash-*"))
