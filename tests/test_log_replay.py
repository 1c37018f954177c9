"""lcm-logger records the project's publishers; lcm-logplayer replays the log
to another URL; the project's reader decodes every event with its types."""

from __future__ import annotations

import subprocess
import time
from collections import Counter

import lcm
from conftest import c_program
from lcm_proc import lcm_tool, pump, stop

from auv import actuators_t, depth_t, nav_solution_t
from auvlcm.log import LogStats, read_events
from auvlcm.rx import Receiver

COUNT = 30
CHANNELS = {"AUV5.NAV": nav_solution_t, "AUV5.DEPTH": depth_t, "AUV5.ACTUATORS": actuators_t}


WARMUP = "TEST.WARMUP"  # published until the logger has it: then it listens


def logged_count(path, channels) -> int:
    """Events on channels in the log so far (the logger flushes every 100 ms)."""
    try:
        return sum(1 for ev in read_events(path) if ev.channel in channels)
    except Exception:  # a half-written last event while the logger writes
        return -1


def without_warmup(counter: Counter) -> Counter:
    return Counter({ch: n for ch, n in counter.items() if ch != WARMUP})


def record(url: str, path, child_env) -> None:
    """Log what the probe publishes. Waits on the file's contents, not on
    sleeps, so a loaded machine is slower but never loses the end of the run."""
    logger = subprocess.Popen(
        [lcm_tool("lcm-logger"), f"--lcm-url={url}", "--quiet", str(path)], stderr=subprocess.PIPE, text=True
    )
    try:
        lc = lcm.LCM(url)
        deadline = time.monotonic() + 30
        while logged_count(path, {WARMUP}) < 1:
            assert time.monotonic() < deadline and logger.poll() is None, "lcm-logger did not start"
            lc.publish(WARMUP, depth_t().encode())
            time.sleep(0.1)
        pub = subprocess.run(
            [
                c_program("bin/auv-lcm-probe"),
                "publish-track",
                "--lcm-url",
                url,
                "--vehicle",
                "AUV5",
                "--count",
                str(COUNT),
                "--rate",
                "100",
            ],
            env=child_env,
            timeout=30,
        )
        assert pub.returncode == 0
        deadline = time.monotonic() + 30
        while logged_count(path, CHANNELS) < 3 * COUNT and time.monotonic() < deadline:
            lc.publish(WARMUP, depth_t().encode())  # the logger flushes when it writes
            time.sleep(0.1)
    finally:
        assert stop(logger) == 0, logger.stderr.read()


def test_logger_records_and_reader_decodes_everything(tmp_path, lcm_url, child_env):
    log = tmp_path / "run.lcmlog"
    record(lcm_url, log, child_env)
    stats = LogStats()
    events = list(read_events(log, stats))
    warmups = stats.per_channel[WARMUP]
    assert warmups >= 1
    assert stats.events == 3 * COUNT + warmups and stats.decoded == stats.events and stats.undecodable == 0
    assert without_warmup(stats.per_channel) == Counter({ch: COUNT for ch in CHANNELS})
    events = [ev for ev in events if ev.channel != WARMUP]
    for ev in events:
        assert isinstance(ev.msg, CHANNELS[ev.channel])
    navs = [ev.msg for ev in events if ev.channel == "AUV5.NAV"]
    assert [n.utime for n in navs] == [round(i / 100 * 1e6) for i in range(COUNT)]


def test_logplayer_replays_to_another_url(tmp_path, lcm_url, child_env):
    log = tmp_path / "run.lcmlog"
    record(lcm_url, log, child_env)
    logged = {(ev.channel, ev.msg.encode()) for ev in read_events(log) if ev.channel in CHANNELS}

    port = int(lcm_url.rsplit(":", 1)[1].split("?")[0])
    replay_url = lcm_url.replace(f":{port}?", f":{port + 1000}?")  # another port: another world
    assert replay_url != lcm_url
    lc = lcm.LCM(replay_url)
    rx = Receiver(lc)
    got = []
    for ch, cls in CHANNELS.items():
        rx.subscribe(ch, cls, lambda c, m: got.append((c, m.encode())), queue_capacity=500)
    player = subprocess.Popen(
        [lcm_tool("lcm-logplayer"), f"--lcm-url={replay_url}", "--speed=4", str(log)], stderr=subprocess.PIPE, text=True
    )
    try:
        assert pump(lc, lambda: len(got) == 3 * COUNT, timeout=20), f"{len(got)} replayed"
        assert player.wait(10) == 0
    finally:
        stop(player)
    assert set(got) == logged and rx.decode_errors == 0


def test_reader_counts_undecodable_events(tmp_path):
    path = tmp_path / "mixed.lcmlog"
    log = lcm.EventLog(str(path), "w")
    good = depth_t()
    good.depth_m = 3.0
    log.write_event(1, "AUV1.DEPTH", good.encode())
    log.write_event(2, "AUV1.DEPTH", good.encode()[:-2])
    log.write_event(3, "OTHER", b"not an lcm message")
    log.write_event(4, "LCM_SELF_TEST", b"lcm self test")  # liblcm's own: skipped
    log.close()
    stats = LogStats()
    events = list(read_events(path, stats))
    assert [e.msg is not None for e in events] == [True, False, False]
    assert (stats.decoded, stats.undecodable, stats.internal) == (1, 2, 1)
    assert events[2].error == "unknown fingerprint"
