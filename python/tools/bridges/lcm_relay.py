#!/usr/bin/env python3
"""Link-impairment relay: LCM in on one URL, LCM out on another, with the
delay, jitter, loss, duplication and reordering of a bad network link.

    python python/tools/bridges/lcm_relay.py --in URL_A --out URL_B \\
        --channel 'SIM\\..*' --delay-ms 2 --jitter-ms 1 --loss 0.05 [--both]

It stands in for kernel netem (which needs privileges that tests and many
machines do not have). Every message whose channel matches --channel (a
regex, whole name) is dropped with probability --loss, or else sent after
--delay-ms +- --jitter-ms (uniform), plus --reorder-delay-ms with probability
--reorder (so later messages overtake it), and with probability --duplicate
a second copy follows with its own delay. The decisions are drawn from a
hash of --seed, the direction, the channel and the message's own bytes (and
how many identical messages came before it), so a message meets the same fate
on every run, whatever else was on the link. Delays are wall time: this is a
network, not a simulation.

--both relays B -> A as well, with the same impairment. Loop prevention: a
relay hears what it publishes (LCM loops multicast back), so every message it
forwards is remembered by (channel, payload hash) for a few seconds, and the
same message heard on that side again is an echo, not new traffic.

Statistics (auv.link_stats_t) go to the --in side every --stats-period
seconds and at exit, on SIM.LINK_STATS.<NAME>.AB (and .BA with --both).
"""

from __future__ import annotations

import argparse
import hashlib
import heapq
import re
import select
import signal
import sys
import time
from collections import OrderedDict, deque
from dataclasses import dataclass

import lcm

from auvlcm.url import check_local

ECHO_MEMORY_S = 5.0
OCCURRENCE_MEMORY = 100_000  # identical messages remembered, to vary their fate
QUEUE_CAPACITY = 100_000


@dataclass
class Impairment:
    delay_ms: float = 0.0
    jitter_ms: float = 0.0
    loss: float = 0.0
    duplicate: float = 0.0
    reorder: float = 0.0
    reorder_delay_ms: float = 10.0


class Echoes:
    """Messages we published on one side, so that hearing them there is no news."""

    def __init__(self) -> None:
        self.count: dict[tuple[str, bytes], int] = {}
        self.log: deque[tuple[float, tuple[str, bytes]]] = deque()

    @staticmethod
    def key(channel: str, data: bytes) -> tuple[str, bytes]:
        return channel, hashlib.blake2b(data, digest_size=16).digest()

    def published(self, channel: str, data: bytes, now: float) -> None:
        k = self.key(channel, data)
        self.count[k] = self.count.get(k, 0) + 1
        self.log.append((now, k))

    def is_echo(self, channel: str, data: bytes, now: float) -> bool:
        while self.log and now - self.log[0][0] > ECHO_MEMORY_S:  # never heard back
            _, k = self.log.popleft()
            self._take(k)
        k = self.key(channel, data)
        if not self.count.get(k):
            return False
        self._take(k)
        return True

    def _take(self, k: tuple[str, bytes]) -> None:
        n = self.count.get(k, 0)
        if n <= 1:
            self.count.pop(k, None)
        else:
            self.count[k] = n - 1


def message_digest(channel: str, data: bytes) -> bytes:
    return hashlib.blake2b(channel.encode() + b"\0" + data, digest_size=16).digest()


def draws(seed: int, direction: str, channel: str, digest: bytes, occurrence: int) -> list[float]:
    """Five numbers in [0, 1) fixed by the message itself (and how many identical
    ones came before it): its fate does not depend on what else the link carried,
    so a message is impaired the same way on every run even if others were lost
    before they reached the relay."""
    key = f"{seed}|{direction}|{channel}|{occurrence}|".encode() + digest
    h = hashlib.blake2b(key, digest_size=40).digest()
    return [int.from_bytes(h[8 * i : 8 * i + 8], "big") / 2.0**64 for i in range(5)]


class Direction:
    """One way through the relay: decisions, the send queue, statistics."""

    def __init__(self, name: str, imp: Impairment, seed: int) -> None:
        self.name = name
        self.imp = imp
        self.seed = seed
        self.occurrences: OrderedDict[bytes, int] = OrderedDict()  # of identical messages
        self.arrivals = 0
        self.max_sent_index = -1
        self.received = self.forwarded = self.dropped = self.duplicated = 0
        self.reordered = self.echoes = 0
        self.delay_sum_ms = 0.0

    def decide(self, channel: str, data: bytes) -> list[float]:
        """Delays [ms] of the copies to send of this message (none: lost)."""
        imp = self.imp
        digest = message_digest(channel, data)
        n = self.occurrences.pop(digest, 0)
        self.occurrences[digest] = n + 1
        if len(self.occurrences) > OCCURRENCE_MEMORY:
            self.occurrences.popitem(last=False)
        u_loss, u_dup, u_reorder, j0, j1 = draws(self.seed, self.name, channel, digest, n)
        jitters = (2.0 * j0 - 1.0, 2.0 * j1 - 1.0)
        if u_loss < imp.loss:
            self.dropped += 1
            return []
        copies = 2 if u_dup < imp.duplicate else 1
        self.duplicated += copies - 1
        extra = imp.reorder_delay_ms if u_reorder < imp.reorder else 0.0
        return [max(0.0, imp.delay_ms + imp.jitter_ms * jitters[i]) + (extra if i == 0 else 0.0) for i in range(copies)]

    def sent(self, index: int, delay_ms: float) -> None:
        self.forwarded += 1
        self.delay_sum_ms += delay_ms
        if index < self.max_sent_index:
            self.reordered += 1  # something that arrived after it went out before it
        self.max_sent_index = max(self.max_sent_index, index)

    def stats(self, relay: str):
        from auv import link_stats_t

        m = link_stats_t()
        m.utime = int(time.time() * 1e6)
        m.relay = f"{relay}.{self.name}"
        m.forwarded, m.dropped, m.duplicated, m.reordered = (
            self.forwarded,
            self.dropped,
            self.duplicated,
            self.reordered,
        )
        m.mean_delay_ms = self.delay_sum_ms / self.forwarded if self.forwarded else 0.0
        return m


class Relay:
    def __init__(self, args: argparse.Namespace) -> None:
        self.name = args.name
        self.lcm = {"A": lcm.LCM(args.url_in), "B": lcm.LCM(args.url_out)}
        self.echoes = {"A": Echoes(), "B": Echoes()}
        imp = Impairment(args.delay_ms, args.jitter_ms, args.loss, args.duplicate, args.reorder, args.reorder_delay_ms)
        self.dirs = {"AB": Direction("AB", imp, args.seed)}
        if args.both:
            self.dirs["BA"] = Direction("BA", imp, args.seed)
        self.pattern = re.compile(args.channel)
        self.stats_prefix = f"SIM.LINK_STATS.{self.name}."
        self.queue: list[tuple[float, int, str, str, bytes, int, float]] = []
        self.order = 0
        self.stop = False
        for d in self.dirs:
            sub = self.lcm[d[0]].subscribe(args.channel, lambda ch, data, d=d: self.on_message(d, ch, data))
            sub.set_queue_capacity(QUEUE_CAPACITY)  # liblcm's default of 30 drops bursts

    def on_message(self, d: str, channel: str, data: bytes) -> None:
        now = time.monotonic()
        if channel.startswith(self.stats_prefix) or channel == "LCM_SELF_TEST":
            return  # our own statistics, liblcm's start-up probe
        direction = self.dirs[d]
        if self.echoes[d[0]].is_echo(channel, data, now):
            direction.echoes += 1
            return
        direction.received += 1
        index = direction.arrivals
        direction.arrivals += 1
        for delay_ms in direction.decide(channel, data):
            self.order += 1
            heapq.heappush(self.queue, (now + delay_ms / 1e3, self.order, d, channel, data, index, delay_ms))

    def _send_due(self, now: float) -> None:
        while self.queue and self.queue[0][0] <= now:
            _, _, d, channel, data, index, delay_ms = heapq.heappop(self.queue)
            dst = d[1]
            if f"{dst}{d[0]}" in self.dirs and self.pattern.fullmatch(channel):
                self.echoes[dst].published(channel, data, now)  # we will hear it there
            self.lcm[dst].publish(channel, data)
            self.dirs[d].sent(index, delay_ms)

    def publish_stats(self) -> None:
        for d in self.dirs.values():
            self.lcm["A"].publish(f"{self.stats_prefix}{d.name}", d.stats(self.name).encode())

    def run(self, stats_period: float, duration: float) -> int:
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, lambda *_: setattr(self, "stop", True))
        fds = {lc.fileno(): lc for lc in self.lcm.values()}
        start = time.monotonic()
        next_stats = start + stats_period
        print(f"relay {self.name}: running ({' and '.join(self.dirs)})", flush=True)
        while not self.stop and (duration <= 0 or time.monotonic() - start < duration):
            now = time.monotonic()
            due = min([next_stats] + ([self.queue[0][0]] if self.queue else []))
            try:
                ready, _, _ = select.select(list(fds), [], [], max(0.0, min(due - now, 0.2)))
            except InterruptedError:
                continue
            while ready:  # everything that is waiting, then send
                for fd in ready:
                    fds[fd].handle()
                ready, _, _ = select.select(list(fds), [], [], 0.0)
            now = time.monotonic()
            self._send_due(now)
            if now >= next_stats:
                next_stats += stats_period
                self.publish_stats()
        self.publish_stats()
        for d in self.dirs.values():
            print(
                f"relay {self.name}.{d.name}: {d.received} received, {d.forwarded} forwarded, "
                f"{d.dropped} dropped, {d.duplicated} duplicated, {d.reordered} reordered, "
                f"{d.echoes} echoes ignored, mean delay "
                f"{d.delay_sum_ms / d.forwarded if d.forwarded else 0.0:.3f} ms",
                flush=True,
            )
        print(f"relay {self.name}: stopped with {len(self.queue)} messages in flight", flush=True)
        return 0


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="lcm_relay", description=__doc__.split("\n\n")[0])
    ap.add_argument("--in", dest="url_in", required=True, help="LCM URL to read (side A)")
    ap.add_argument("--out", dest="url_out", required=True, help="LCM URL to write (side B)")
    ap.add_argument("--channel", default=".*", help="regex of channels to relay (whole name)")
    ap.add_argument("--both", action="store_true", help="also relay B -> A")
    ap.add_argument("--delay-ms", type=float, default=0.0)
    ap.add_argument("--jitter-ms", type=float, default=0.0, help="uniform +- around the delay")
    ap.add_argument("--loss", type=float, default=0.0, help="probability a message is dropped")
    ap.add_argument("--duplicate", type=float, default=0.0, help="probability of a second copy")
    ap.add_argument(
        "--reorder", type=float, default=0.0, help="probability a message is held back by --reorder-delay-ms"
    )
    ap.add_argument("--reorder-delay-ms", type=float, default=10.0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--name", default="RELAY", help="relay name in statistics channels")
    ap.add_argument("--stats-period", type=float, default=1.0, help="seconds")
    ap.add_argument("--duration", type=float, default=0.0, help="stop after seconds (0: never)")
    ap.add_argument(
        "--inside-netns", action="store_true", help="allow ttl=1 URLs (only in a network namespace made for the run)"
    )
    args = ap.parse_args(argv)
    for name in ("loss", "duplicate", "reorder"):
        if not 0.0 <= getattr(args, name) <= 1.0:
            ap.error(f"--{name} must be a probability in [0, 1]")
    for name in ("delay_ms", "jitter_ms", "reorder_delay_ms"):
        if getattr(args, name) < 0:
            ap.error(f"--{name.replace('_', '-')} must be >= 0")
    if args.stats_period <= 0:
        ap.error("--stats-period must be > 0")
    if not re.fullmatch(r"[A-Z][A-Z0-9_]{0,30}", args.name):
        ap.error("--name: upper-case letters, digits and _, starting with a letter")
    try:
        re.compile(args.channel)
    except re.error as exc:
        ap.error(f"--channel {args.channel!r}: {exc}")
    if args.url_in == args.url_out:
        ap.error("--in and --out are the same URL: the relay would feed itself")
    try:
        for url in (args.url_in, args.url_out):
            check_local(url, inside_netns=args.inside_netns)
    except ValueError as exc:
        ap.error(str(exc))
    return args


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    return Relay(args).run(args.stats_period, args.duration)


if __name__ == "__main__":
    sys.exit(main())
