"""auv-recorder (c/recorder): over real LCM it records every message it
receives, where lcm-logger loses some; its log is an ordinary LCM log that
lcm.EventLog reads and lcm-logplayer replays; SIGINT/SIGTERM write out
everything received; in a lockstep world time waits for it; it says what it
counted (stats file, exit line, SIM.HEALTH). Both build variants."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time

import lcm
import pytest
from lcm_proc import lcm_tool, stop

from auv import ground_truth_t, lockstep_t, process_health_t, sim_clock_t

VEHICLES = 16
PER_VEHICLE = 120  # one burst: 16 vehicles' TRUTH, 1920 messages at once
WARMUP = "TEST.WARMUP"


def recorder_cmd(variant_dir, url, log, stats, *extra):
    return [str(variant_dir / "bin" / "auv-recorder"), "--lcm-url", url, "-f", str(log), "--stats", str(stats), *extra]


def truth(vid: int, i: int) -> bytes:
    m = ground_truth_t()
    m.utime = i
    m.vehicle = f"AUV{vid}"
    return m.encode()


def events(path) -> list[tuple[str, bytes]]:
    """Every event of a log, read with the lcm package's own reader."""
    log = lcm.EventLog(str(path), "r")
    try:
        return [(ev.channel, ev.data) for ev in log]
    finally:
        log.close()


def wait_logged(path, channel: str, lc: lcm.LCM, proc, what: str, timeout: float = 30.0) -> None:
    """Publish a warm-up message until the recorder's file holds one: it listens."""
    deadline = time.monotonic() + timeout
    while True:
        lc.publish(channel, b"warm")
        try:
            if any(ch == channel for ch, _ in events(path)):
                return
        except (OSError, ValueError):
            pass  # not created yet, or a half-written event
        assert proc.poll() is None, f"{what} exited: {proc.communicate()}"
        assert time.monotonic() < deadline, f"{what} never recorded a message"
        time.sleep(0.1)


def burst(lc: lcm.LCM) -> None:
    for i in range(PER_VEHICLE):
        for v in range(1, VEHICLES + 1):
            lc.publish(f"AUV{v}.TRUTH", truth(v, i))


def truths(evs) -> dict[str, list[int]]:
    out: dict[str, list[int]] = {}
    for ch, data in evs:
        if ch.endswith(".TRUTH"):
            out.setdefault(ch, []).append(ground_truth_t.decode(data).utime)
    return out


def test_a_stalled_recorder_loses_nothing_where_lcm_logger_does(tmp_path, lcm_url, child_env, variant_dir):
    """Both are descheduled (SIGSTOP) while 16 vehicles' TRUTH arrives in one
    burst - what a busy machine does to them for a moment. The kernel buffers
    the burst for both (a large receive buffer); on waking, lcm-logger's
    30-message subscription queue overflows, the recorder's deep one does not."""
    url = lcm_url + "&recv_buf_size=4194304"
    rec_log, lg_log, stats = tmp_path / "rec.lcmlog", tmp_path / "logger.lcmlog", tmp_path / "stats.json"
    rec = subprocess.Popen(
        recorder_cmd(variant_dir, url, rec_log, stats),
        env=child_env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    logger = subprocess.Popen(
        [lcm_tool("lcm-logger"), f"--lcm-url={url}", "--quiet", str(lg_log)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    lc = lcm.LCM(url)
    try:
        wait_logged(rec_log, WARMUP, lc, rec, "auv-recorder")
        wait_logged(lg_log, WARMUP, lc, logger, "lcm-logger")
        for p in (rec, logger):
            os.kill(p.pid, signal.SIGSTOP)
        burst(lc)
        for p in (rec, logger):
            os.kill(p.pid, signal.SIGCONT)
    finally:
        for p in (rec, logger):
            os.kill(p.pid, signal.SIGCONT)
        rc_rec = stop(rec, signal.SIGTERM)
        out, err = rec.communicate()
        stop(logger)
    assert rc_rec == 0, out + err
    assert err == "", err  # no sanitizer report, no complaint about the signal that stopped it
    expected = list(range(PER_VEHICLE))
    got = truths(events(rec_log))
    assert got == {f"AUV{v}.TRUTH": expected for v in range(1, VEHICLES + 1)}  # every one, in order
    counts = json.loads(stats.read_text())
    assert counts["dropped"] == 0 and counts["missed"] == 0 and counts["write_errors"] == 0, counts
    assert counts["written"] == counts["received"] == len(events(rec_log)), counts
    assert f"written {counts['written']}, dropped 0" in out and "missed 0" in out, out
    assert counts["recv_buf_granted"] >= 4194304, counts  # the kernel granted what was asked (and reports it)
    lost_by_logger = VEHICLES * PER_VEHICLE - sum(len(v) for v in truths(events(lg_log)).values())
    print(f"lcm-logger lost {lost_by_logger} of {VEHICLES * PER_VEHICLE}; auv-recorder lost 0")
    assert lost_by_logger > 0, "lcm-logger kept up this time: the burst did not test the difference"


def test_the_recorder_hears_whatever_is_sent_once_its_file_exists(tmp_path, lcm_url, child_env, variant_dir):
    """The launcher writes its note `logger` as soon as the log file exists
    (tools/launch/launcher.py, start_logger). The recorder once created the
    file before it opened its socket: a note sent in between was lost on a
    loaded machine, and two runs of one scenario differed by that one event
    (tests/tools/test_report_deterministic.py). Stopped (SIGSTOP) the moment
    its file shows up, the recorder must already be listening."""
    lc = lcm.LCM(lcm_url)
    for i in range(40):
        log, stats = tmp_path / f"r{i}.lcmlog", tmp_path / f"r{i}.json"
        rec = subprocess.Popen(
            recorder_cmd(variant_dir, lcm_url, log, stats, "--quiet"),
            env=child_env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        try:
            deadline = time.monotonic() + 30
            while not log.exists():  # no sleep: catch the file as early as can be
                assert rec.poll() is None, rec.communicate()
                assert time.monotonic() < deadline, "auv-recorder never created its file"
            os.kill(rec.pid, signal.SIGSTOP)
            lc.publish("TEST.FIRST", b"first")
        finally:
            os.kill(rec.pid, signal.SIGCONT)
            # until the message is written (a deadline, not a guess of how long it takes)
            until = time.monotonic() + 10
            while ("TEST.FIRST", b"first") not in events(log) and time.monotonic() < until:
                time.sleep(0.01)
            rc = stop(rec, signal.SIGTERM)
            out, err = rec.communicate()
        assert rc == 0, out + err
        assert ("TEST.FIRST", b"first") in events(log), f"run {i}: the first message was lost"


def test_lcm_logplayer_replays_the_recorders_log(tmp_path, lcm_url, child_env, build_dir):
    url = lcm_url + "&recv_buf_size=4194304"
    log, stats = tmp_path / "rec.lcmlog", tmp_path / "stats.json"
    rec = subprocess.Popen(
        recorder_cmd(build_dir, url, log, stats),
        env=child_env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    lc = lcm.LCM(url)
    try:
        wait_logged(log, WARMUP, lc, rec, "auv-recorder")
        for i in range(50):
            for v in (1, 2):
                lc.publish(f"AUV{v}.TRUTH", truth(v, i))
            time.sleep(0.002)
    finally:
        assert stop(rec, signal.SIGINT) == 0
    recorded = truths(events(log))
    assert recorded == {"AUV1.TRUTH": list(range(50)), "AUV2.TRUTH": list(range(50))}

    other = lcm_url.replace("239.255.76.67", "239.255.76.68") + "&recv_buf_size=4194304"  # another world
    rx = lcm.LCM(other)
    got: list[tuple[str, int]] = []
    sub = rx.subscribe(r"AUV\d\.TRUTH", lambda ch, data: got.append((ch, ground_truth_t.decode(data).utime)))
    sub.set_queue_capacity(10000)
    player = subprocess.Popen(
        [lcm_tool("lcm-logplayer"), f"--lcm-url={other}", str(log)],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    deadline = time.monotonic() + 30
    while len(got) < 100 and time.monotonic() < deadline:
        rx.handle_timeout(50)
    player.wait(30)
    assert player.returncode == 0, player.stdout.read()
    assert sorted(got) == sorted((f"AUV{v}.TRUTH", i) for v in (1, 2) for i in range(50))


def test_in_lockstep_time_waits_for_the_recorder(tmp_path, lcm_url, child_env, variant_dir):
    """It registers as SIM.RECORDER, reports each step after it has taken in
    everything received before that step's clock, reports nothing while it is
    stopped, and leaves when it ends. It also publishes its health."""
    log, stats = tmp_path / "rec.lcmlog", tmp_path / "stats.json"
    rec = subprocess.Popen(
        recorder_cmd(variant_dir, lcm_url, log, stats, "--health-period", "0.2"),
        env=child_env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    lc = lcm.LCM(lcm_url)
    seen: list[tuple[int, int]] = []  # (kind, step) from SIM.RECORDER
    health: list = []

    def on_lockstep(_ch, data):
        m = lockstep_t.decode(data)
        if m.participant == "SIM.RECORDER":
            seen.append((m.kind, m.step))

    lc.subscribe("SIM.LOCKSTEP", on_lockstep)
    lc.subscribe("SIM.HEALTH", lambda _ch, data: health.append(process_health_t.decode(data)))

    def clock(step: int) -> None:
        c = sim_clock_t()
        c.utime, c.server_id, c.mode, c.step, c.step_us = step * 50000, "test", sim_clock_t.MODE_LOCKSTEP, step, 50000
        lc.publish("SIM.CLOCK", c.encode())

    def wait(cond, timeout=30.0) -> bool:
        deadline = time.monotonic() + timeout
        while not cond() and time.monotonic() < deadline:
            lc.handle_timeout(50)
        return cond()

    try:
        assert wait(lambda: (lockstep_t.KIND_REGISTER, 0) in seen), "no REGISTER from SIM.RECORDER"
        for step in (1, 2):
            clock(step)
            assert wait(lambda: (lockstep_t.KIND_STEP_DONE, step) in seen), seen
        os.kill(rec.pid, signal.SIGSTOP)
        clock(3)
        lc.handle_timeout(500)
        assert (lockstep_t.KIND_STEP_DONE, 3) not in seen  # time waits for it
        os.kill(rec.pid, signal.SIGCONT)
        assert wait(lambda: (lockstep_t.KIND_STEP_DONE, 3) in seen), seen
        assert wait(lambda: any(h.process == "recorder" for h in health))
    finally:
        os.kill(rec.pid, signal.SIGCONT)
        rc = stop(rec, signal.SIGINT)
    assert rc == 0, rec.communicate()
    assert wait(lambda: any(k == lockstep_t.KIND_LEAVE for k, _ in seen), 10), seen
    h = [h for h in health if h.process == "recorder"][-1]
    assert h.vehicle == "" and h.pid == rec.pid and h.messages_received > 0 and h.queue_overflows == 0
    clocks = [sim_clock_t.decode(d).step for ch, d in events(log) if ch == "SIM.CLOCK"]
    assert clocks == [1, 2, 3]


@pytest.mark.parametrize(
    "args, code, message",
    [
        ([], 2, "-f FILE is required"),
        (["-f", "x.lcmlog", "--queue-mb", "zero"], 2, "--queue-mb: 'zero' is not a number"),
        (["-f", "x.lcmlog", "--bogus"], 2, "--bogus: unknown option"),
        (["-f", "/nonexistent-dir/x.lcmlog"], 1, "/nonexistent-dir/x.lcmlog"),
    ],
)
def test_bad_usage_is_a_clear_error(tmp_path, variant_dir, child_env, args, code, message):
    run = subprocess.run(
        [str(variant_dir / "bin" / "auv-recorder"), *args],
        cwd=tmp_path,
        env=child_env,
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert run.returncode == code, run.stderr
    assert message in run.stderr and "Sanitizer" not in run.stderr
