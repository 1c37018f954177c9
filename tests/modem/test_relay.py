"""The link-impairment relay over real LCM: delay and jitter, loss,
duplication, reordering (seeded, so repeatable), channel filter, both
directions without loops, statistics, and bad arguments. Delays are wall
time, so timing checks have a strict lower bound and a generous upper one."""

from __future__ import annotations

import re
import statistics
import struct
import subprocess
import sys
import time

import lcm
import pytest
from conftest import _ports
from lcm_proc import stop, wait_for_line

from auv import link_stats_t
from auvlcm.rx import Receiver

RELAY = ("-m", "tools.bridges.lcm_relay")


@pytest.fixture
def urls():
    return tuple(f"udpm://239.255.76.67:{next(_ports)}?ttl=0" for _ in range(2))


def message(seq: int, sent: float) -> bytes:
    return struct.pack(">id", seq, sent) + bytes(20)


class Side:
    """One LCM URL: publishes numbered messages, records what arrives."""

    def __init__(self, url: str, pattern: str = ".*") -> None:
        self.lc = lcm.LCM(url)
        self.got: list[tuple[str, int, float, float]] = []  # channel, seq, sent, received
        self.lc.subscribe(pattern, self._on).set_queue_capacity(100_000)
        self.stats: dict[str, link_stats_t] = {}
        Receiver(self.lc).subscribe("SIM.LINK_STATS.*", link_stats_t, lambda ch, m: self.stats.__setitem__(ch, m), 100)

    def _on(self, channel: str, data: bytes) -> None:
        if channel.startswith("SIM.LINK_STATS") or channel == "LCM_SELF_TEST":
            return
        seq, sent = struct.unpack(">id", data[:12])
        self.got.append((channel, seq, sent, time.monotonic()))

    def send(self, channel: str, seq: int, stamp: bool = True) -> None:
        self.lc.publish(channel, message(seq, time.monotonic() if stamp else 0.0))

    def pump(self, seconds: float) -> None:
        """Handle everything waiting, then keep handling for the given time."""
        end = time.monotonic() + seconds
        while True:
            while self.lc.handle_timeout(0) > 0:
                pass
            left = end - time.monotonic()
            if left <= 0:
                return
            self.lc.handle_timeout(max(1, min(10, int(left * 1e3))))


def relay_received(out: str, direction: str = "AB") -> int:
    """Messages the relay took in (the kernel may drop some before it, under load)."""
    m = re.search(rf"relay LINK\.{direction}: (\d+) received", out)
    assert m, out
    return int(m.group(1))


def start_relay(env, a, b, *args):
    proc = subprocess.Popen(
        [sys.executable, *RELAY, "--in", a, "--out", b, "--name", "LINK", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env=env,
    )
    wait_for_line(proc, "running", timeout=30)
    return proc


def send_one(a: Side, b: Side, seq: int) -> None:
    a.send("AUV1.DATA", seq)


def run_traffic(env, urls, n, *relay_args, send=send_one):
    """n rounds of send(a, b, seq) about 1 ms apart through a relay; (a, b, its output)."""
    a, b = Side(urls[0]), Side(urls[1])
    relay = start_relay(env, urls[0], urls[1], *relay_args)
    try:
        for seq in range(n):
            send(a, b, seq)
            a.pump(0.001)
            b.pump(0.0)
        b.pump(0.5)
        a.pump(0.3)
    finally:
        assert stop(relay) == 0
    out = relay.stdout.read()
    a.pump(0.2)
    return a, b, out


def test_delay_and_jitter(child_env, urls):
    a, b, out = run_traffic(child_env, urls, 300, "--delay-ms", "20", "--jitter-ms", "5")
    seqs = [s for _, s, _, _ in b.got]
    received = relay_received(out)
    assert received >= 270  # the rest: kernel drops
    assert len(seqs) == len(set(seqs)) == received  # nothing lost or added
    delays_ms = [(rx - tx) * 1e3 for _, _, tx, rx in b.got]
    assert min(delays_ms) >= 15.0 - 0.5  # never earlier than asked
    assert statistics.median(delays_ms) < 25.0 + 200.0  # a loaded machine adds, only
    st = a.stats["SIM.LINK_STATS.LINK.AB"]
    assert st.forwarded == received and st.dropped == st.duplicated == 0
    # the scheduled delays: uniform on [15, 25] ms, mean 20 +- 4 sigma of the mean
    assert abs(st.mean_delay_ms - 20.0) < 4 * (10 / 12**0.5) / received**0.5
    assert f"{received} forwarded" in out


def test_loss_duplication_reordering_statistics_and_repeatability(child_env, urls):
    n, loss, dup, reorder = 600, 0.2, 0.1, 0.1
    args = (
        "--delay-ms",
        "2",
        "--jitter-ms",
        "1",
        "--loss",
        str(loss),
        "--duplicate",
        str(dup),
        "--reorder",
        str(reorder),
        "--reorder-delay-ms",
        "15",
        "--seed",
        "7",
    )
    a, b, out = run_traffic(child_env, urls, n, *args)
    st = a.stats["SIM.LINK_STATS.LINK.AB"]
    sigma = lambda p, m: 4 * (m * p * (1 - p)) ** 0.5  # noqa: E731
    received = relay_received(out)
    assert received >= 0.9 * n
    assert abs(st.dropped - received * loss) < sigma(loss, received)
    kept = received - st.dropped
    assert abs(st.duplicated - kept * dup) < sigma(dup, kept)
    assert st.forwarded == kept + st.duplicated == len(b.got)
    seqs = [s for _, s, _, _ in b.got]
    assert len(seqs) - len(set(seqs)) == st.duplicated
    assert len(set(seqs)) == kept
    # reordered as the relay counts it: sent after something that arrived later
    out_of_order = sum(1 for i, s in enumerate(seqs) if i and s < max(seqs[:i]))
    assert out_of_order == st.reordered > kept * reorder * 0.5


def test_a_message_meets_the_same_fate_on_every_run(child_env, urls):
    """The fate of a message is a function of the seed and the message: the test
    predicts it from the relay's own draw function, whatever reached the relay."""
    from tools.bridges.lcm_relay import draws, message_digest

    def send(a, b, seq):
        a.send("AUV1.DATA", seq, stamp=False)  # the same bytes on every run

    _, b, out = run_traffic(child_env, urls, 300, "--loss", "0.3", "--duplicate", "0.1", "--seed", "11", send=send)
    fate = {}
    for seq in range(300):
        u = draws(11, "AB", "AUV1.DATA", message_digest("AUV1.DATA", message(seq, 0.0)), 0)
        fate[seq] = 0 if u[0] < 0.3 else (2 if u[1] < 0.1 else 1)  # copies delivered
    got = [s for _, s, _, _ in b.got]
    assert all(got.count(s) == fate[s] for s in set(got))
    assert 180 < sum(1 for c in fate.values() if c) < 240  # about 70 % kept
    if relay_received(out) == 300:  # nothing lost before it
        assert sorted(got) == sorted(s for s, c in fate.items() for _ in range(c))


def test_channel_filter(child_env, urls):
    def send(a, b, seq):
        for channel in ("AUV1.NAV", "AUV2.NAV", "XAUV1.NAV"):
            a.send(channel, seq)

    _, b, _ = run_traffic(child_env, urls, 20, "--channel", r"AUV1\..*", send=send)
    assert {ch for ch, *_ in b.got} == {"AUV1.NAV"} and len(b.got) == 20


def test_both_directions_without_loops(child_env, urls):
    def send(a, b, seq):
        a.send("AUV1.DATA", seq)
        b.send("AUV2.DATA", 1000 + seq)

    a, b, out = run_traffic(child_env, urls, 50, "--both", "--delay-ms", "1", send=send)
    by = lambda side, ch: sorted(s for c, s, _, _ in side.got if c == ch)  # noqa: E731
    # each side hears its own 50 once (no echo back) and the other side's 50 once
    assert by(a, "AUV1.DATA") == list(range(50)) and by(b, "AUV1.DATA") == list(range(50))
    assert by(b, "AUV2.DATA") == list(range(1000, 1050)) and by(a, "AUV2.DATA") == by(b, "AUV2.DATA")
    assert "LINK.AB: 50 received, 50 forwarded" in out and "LINK.BA: 50 received, 50 forwarded" in out
    assert "50 echoes ignored" in out


@pytest.mark.parametrize(
    "args, message",
    [
        (["--loss", "1.5"], "--loss must be a probability in [0, 1]"),
        (["--channel", "AUV1.("], "--channel 'AUV1.(':"),
        (["--delay-ms", "-1"], "--delay-ms must be >= 0"),
        (["--name", "x y"], "--name: upper-case"),
    ],
)
def test_bad_arguments_exit_non_zero_with_the_reason(child_env, urls, args, message):
    res = subprocess.run(
        [sys.executable, *RELAY, "--in", urls[0], "--out", urls[1], *args],
        capture_output=True,
        text=True,
        env=child_env,
        timeout=60,
    )
    assert res.returncode == 2 and message in res.stderr, res.stderr


def test_urls_must_stay_on_this_host(child_env, urls):
    far = "udpm://239.255.76.67:7667?ttl=5"
    res = subprocess.run(
        [sys.executable, *RELAY, "--in", urls[0], "--out", far],
        capture_output=True,
        text=True,
        env=child_env,
        timeout=60,
    )
    assert res.returncode == 2 and "ttl=5 would send beyond this host" in res.stderr
    res = subprocess.run(
        [sys.executable, *RELAY, "--in", urls[0], "--out", urls[0]],
        capture_output=True,
        text=True,
        env=child_env,
        timeout=60,
    )
    assert res.returncode == 2 and "same URL" in res.stderr
