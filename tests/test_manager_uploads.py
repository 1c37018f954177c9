"""Plugin uploads to a running manager over real LCM, with the hostile corpus
of tests/chasm/plugin_corpus.py: every file is allowlisted, so only the
loader's own checks stand between it and the mission. Each upload is
answered FAILED with its reason, the mission goes on, nothing is left in
--plugin-dir, and the manager restarts on that directory. The allowlist's
name column and the plugin-name rule are enforced. Both builds."""

from __future__ import annotations

import hashlib
import signal
from pathlib import Path

import pytest
from conftest import BUILD
from lcm_proc import pump, stop
from plugin_corpus import built_cases, byte_cases
from test_manager import HERE, World, start_manager

from auv import mission_ack_t, plugin_upload_t

# dive.chasm with a plugin test handler, so uploads of test_basic hot-load.
PLAN = (
    (HERE / "dive.chasm")
    .read_text()
    .replace('mission "manager test"', 'mission "manager test"\nuse test_basic')
    .replace(
        "    when deep -> hold\n",
        "    test very_deep : above(x = nav.depth_m, limit = 50 m)\n"
        "    when very_deep -> hold\n    when deep -> hold\n",
        1,
    )
)


def _digest(b: bytes) -> str:
    return hashlib.sha256(b).hexdigest()


class Uploader:
    def __init__(self, w: World) -> None:
        self.w = w
        self.seq = 100

    def __call__(self, name: str, data: bytes, digest: str | None = None) -> mission_ack_t:
        self.seq += 1
        up = plugin_upload_t()
        up.utime, up.vehicle, up.seq, up.plugin_name, up.plugin_version = self.w.utime, "AUV1", self.seq, name, "9"
        up.sha256_hex, up.n_bytes, up.data = digest or _digest(data), len(data), data
        self.w.lc.publish("AUV1.PLUGIN_UPLOAD", up.encode())
        assert pump(self.w.lc, lambda: any(a.seq == self.seq for a in self.w.acks), timeout=20), f"no ack {self.seq}"
        return next(a for a in self.w.acks if a.seq == self.seq)


def _start(lcm_url, env, sanitized, plan: Path, pdir: Path, allow: Path):
    variant = BUILD / "san" if sanitized else BUILD
    return start_manager(
        lcm_url,
        env,
        sanitized,
        plan=plan,
        extra=["--plugin-path", variant / "plugins", "--plugin-dir", pdir, "--allowlist", allow],
    )


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_hostile_uploads_fail_and_leave_nothing(lcm_url, child_env, tmp_path, sanitized):
    plugins = (BUILD / "san" if sanitized else BUILD) / "plugins"
    good = (plugins / "chasm_test_basic.so").read_bytes()
    v2 = (plugins / "chasm_test_basic_v2.so").read_bytes()
    noschema = (plugins / "chasm_test_basic_noschema.so").read_bytes()
    cases = [c for c in byte_cases(good) + built_cases(plugins) if c.data]
    plan, pdir, allow = tmp_path / "plan.chasm", tmp_path / "uploads", tmp_path / "allowlist"
    plan.write_text(PLAN)
    pdir.mkdir()
    child_env["TMPDIR"] = str(tmp_path)
    allow.write_text(
        "# digest name\n"
        + "".join(f"{_digest(c.data)} test_basic\n" for c in cases)
        + f"{_digest(good)} test_basic\n{_digest(v2)} other_name\n{_digest(noschema)}\n"
    )
    w = World(lcm_url)
    mgr = _start(lcm_url, child_env, sanitized, plan, pdir, allow)
    up = Uploader(w)
    try:
        w.wait_for_first_cycle()
        for c in cases:
            ack = up("test_basic", c.data)
            assert ack.result == mission_ack_t.RESULT_FAILED, (c.name, ack.message)
            assert "not loaded, mission unchanged" in ack.message and c.reason in ack.message, (c.name, ack.message)
            assert ".upload-" not in ack.message, ack.message  # errors name the file it would have become
            assert list(pdir.iterdir()) == [], c.name
            assert mgr.poll() is None, c.name
        # refusals before anything is written
        refusals = [
            (("test_basic", b""), "0 bytes"),
            (("", good), "is not a plugin name: it is empty"),
            (("../evil", good), "is not a plugin name"),
            (("a.b", good), "is not a plugin name"),
            (("Test_basic", good), "is not a plugin name"),
            (("x" * 64, good), "longer than 63"),
            (("test_basic", v2), "in the allowlist for plugin 'other_name', not for 'test_basic'"),
            (("test_basic", noschema), "without a plugin name"),
            (("test_basic", b"not allowlisted"), "digest not in the allowlist"),
        ]
        for (name, data), reason in refusals:
            ack = up(name, data)
            assert ack.result == mission_ack_t.RESULT_REJECTED and reason in ack.message, (name, ack.message)
        ack = up("test_basic", good, "0" * 64)
        assert ack.result == mission_ack_t.RESULT_REJECTED and "does not match" in ack.message
        # allowlisted for its name, but the file holds another plugin
        ack = up("other_name", v2)
        assert ack.result == mission_ack_t.RESULT_FAILED
        assert "holds plugin 'test_basic', not 'other_name'" in ack.message, ack.message
        assert list(pdir.iterdir()) == []
        # the mission went on all along
        n = len(w.status)
        for _ in range(3):
            w.tick(0.1, depth=0.0)
        assert len(w.status) > n and w.leaf() == "dive"
        # a good upload is loaded and only then appears
        ack = up("test_basic", good)
        assert ack.result == mission_ack_t.RESULT_OK and "loaded" in ack.message, ack.message
        assert sorted(p.name for p in pdir.iterdir()) == ["chasm_test_basic.so"]
        assert (pdir / "chasm_test_basic.so").read_bytes() == good
        # the loaded code is a private copy: truncating the file in place
        # (what makes a mapped .so fault) changes nothing for the mission
        with open(pdir / "chasm_test_basic.so", "r+b") as f:
            f.truncate(len(good) // 3)
        n = len(w.status)
        for _ in range(3):
            w.tick(0.1, depth=0.0)
        assert len(w.status) > n and mgr.poll() is None
        (pdir / "chasm_test_basic.so").write_bytes(good)
    finally:
        assert stop(mgr, signal.SIGTERM) == 0, mgr.stderr.read()
    # the manager starts again on that plugin directory
    w2 = World(lcm_url)
    mgr = _start(lcm_url, child_env, sanitized, plan, pdir, allow)
    try:
        w2.wait_for_first_cycle()
        assert w2.leaf() == "dive"
    finally:
        assert stop(mgr, signal.SIGTERM) == 0, mgr.stderr.read()


def test_a_bad_file_in_the_plugin_dir_is_a_load_error_not_a_crash(lcm_url, child_env, tmp_path):
    good = (BUILD / "plugins" / "chasm_test_basic.so").read_bytes()
    plan, pdir, allow = tmp_path / "plan.chasm", tmp_path / "uploads", tmp_path / "allowlist"
    plan.write_text(PLAN)
    pdir.mkdir()
    allow.write_text("")
    child_env["TMPDIR"] = str(tmp_path)
    # not used by the plan: never opened, the manager starts
    (pdir / "chasm_unused.so").write_bytes(good[:1000])
    w = World(lcm_url)
    mgr = _start(lcm_url, child_env, False, plan, pdir, allow)
    try:
        w.wait_for_first_cycle()
    finally:
        assert stop(mgr, signal.SIGTERM) == 0
    # used by the plan: a clear load error at the plan's `use`, exit without a signal
    (pdir / "chasm_test_basic.so").write_bytes(good[: len(good) // 2])
    mgr = _start(lcm_url, child_env, False, plan, pdir, allow)
    try:
        err = mgr.stderr.read()
        rc = mgr.wait(timeout=30)
    finally:
        stop(mgr, signal.SIGKILL)
    assert rc > 0, (rc, err)
    assert "plan.chasm:3:5: error: plugin 'test_basic': cannot load plugin file" in err and "truncated" in err, err


def test_an_upload_not_used_by_the_plan_is_checked_then_kept(lcm_url, child_env, tmp_path):
    """A plugin for a later LOAD_PLAN: kept only once it has loaded and passed."""
    plugins = BUILD / "plugins"
    other = (plugins / "chasm_test_other.so").read_bytes()
    bad = (plugins / "chasm_test_nosym.so").read_bytes()
    pdir, allow = tmp_path / "uploads", tmp_path / "allowlist"
    pdir.mkdir()
    (pdir / ".chasm_x.so.upload-AbC123").write_bytes(b"left by a crash")
    allow.write_text(f"{_digest(other)} test_other\n{_digest(bad)} test_other\n")
    child_env["TMPDIR"] = str(tmp_path)
    w = World(lcm_url)
    mgr = start_manager(lcm_url, child_env, extra=["--plugin-dir", pdir, "--allowlist", allow])
    up = Uploader(w)
    try:
        w.wait_for_first_cycle()
        assert list(pdir.iterdir()) == [], "an interrupted upload's temporary file is removed at start"
        ack = up("test_other", bad)
        assert ack.result == mission_ack_t.RESULT_FAILED and "does not export" in ack.message, ack.message
        assert list(pdir.iterdir()) == []
        ack = up("test_other", other)
        assert ack.result == mission_ack_t.RESULT_OK and "does not use it" in ack.message, ack.message
        assert [p.name for p in pdir.iterdir()] == ["chasm_test_other.so"]
    finally:
        assert stop(mgr, signal.SIGTERM) == 0
