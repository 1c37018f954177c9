"""A short deterministic fuzz run of the Loader (ASan+UBSan) over the corpus
of example plans; `make fuzz` runs the long one."""

from __future__ import annotations

from chasm_common import HERE, run


def test_fuzz_loader_short(build_dir, child_env, tmp_path):
    exe = build_dir / "san" / "bin" / "chasm_fuzz"
    assert exe.exists(), f"{exe} is not built: run `make sanitize`"
    corpus = [HERE / "fuzz_corpus", HERE / "plans", HERE / "bad_plans"]
    # 50 000 inputs (2 s): the suite is on a time budget; `make fuzz` is the long run
    p = run([exe, "--runs", "50000", "--seed", "7", *corpus], child_env, cwd=tmp_path, timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "no crash" in p.stdout
    assert not list(tmp_path.glob("chasm-crash-*"))


def test_fuzz_plugin_file_check_short(build_dir, child_env, tmp_path):
    """The plugin loader's file check on mutated plugins (ASan+UBSan); every
    input it accepts is opened for real (probe process, dlopen)."""
    exe = build_dir / "san" / "bin" / "chasm_fuzz_plugin"
    assert exe.exists(), f"{exe} is not built: run `make sanitize`"
    seeds = [build_dir / "san" / "plugins" / f"chasm_{n}.so" for n in ("test_basic", "test_other", "test_nosym")]
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    child_env["TMPDIR"] = str(tmp)
    p = run([exe, "--no-dict", "--runs", "400", "--seed", "7", *seeds], child_env, cwd=tmp_path, timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "no crash" in p.stdout
    assert not list(tmp_path.glob("chasm-crash-*"))
    assert list(tmp.iterdir()) == [], "the fuzzer or the loader left files behind"
