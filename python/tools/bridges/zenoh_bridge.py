#!/usr/bin/env python3
"""LCM <-> Zenoh bridge: one per site, joins sites whose multicast stops at
their edge (a ship and a lab, cloud runs). docs/zenoh.md.

    auv-zenoh-bridge --site SITE [--realm REALM] [--lcm-url LCM_URL]
                    [--listen EP]... [--connect EP]... [--mode peer|client]
                    [--allow REGEX]... [--deny REGEX]... [--stats-period S]
                    [--connect-timeout S]
    auv-zenoh-bridge router --listen EP...        (a Zenoh router, nothing else)

Every LCM message of the site whose channel matches an --allow regex (whole
name; default: all) and no --deny regex is put on Zenoh under the key
`<realm>/<site>/lcm/<CHANNEL>`, its payload the LCM message bytes unchanged.
The bridge subscribes to `<realm>/*/lcm/**` and publishes what other sites
put onto its own LCM (the same allow/deny rules apply on the way in).

No loops: a key's site segment says where a message came from; the bridge
ignores its own site's keys, and it never sends back to Zenoh what it has
itself published on LCM (LCM loops multicast back to the publisher: those
are remembered by channel and payload hash for a few seconds, as the link
relay does). One bridge per site: two bridges on one site would echo each
other's traffic. Channels a Zenoh key cannot carry (`*`, `$`, `?`, `#`, `/`)
are counted and dropped.

Counters (sent, received, denied out/in, echoes suppressed, unbridgeable)
are printed every --stats-period seconds and at exit, and published as
link_stats_t on SIM.LINK_STATS.ZENOH_<SITE> (forwarded = sent + received,
dropped = denied + unbridgeable). Exit 0 on SIGINT/SIGTERM, 2 on usage errors.
"""

from __future__ import annotations

import argparse
import queue
import re
import select
import signal
import sys
import time

import lcm

from auvlcm import programs
from auvlcm.url import check_local, default_url
from tools.bridges.lcm_relay import Echoes

SITE = re.compile(r"[A-Za-z0-9_-]{1,40}")
BAD_KEY_CHARS = re.compile(r"[*$?#/]")
INBOX_CAPACITY = 100_000


def zenoh_config(mode: str, listen: list[str], connect: list[str]):
    import json

    import zenoh

    c = zenoh.Config()
    c.insert_json5("mode", json.dumps(mode))
    c.insert_json5("scouting/multicast/enabled", "false")  # peers only where told: never beyond the site's links
    if listen:
        c.insert_json5("listen/endpoints", json.dumps(listen))
    if connect:
        c.insert_json5("connect/endpoints", json.dumps(connect))
    return c


def open_session(config, timeout_s: float):
    """zenoh.open, retried while the endpoints it must connect to are not up
    yet (a router that starts after the bridge), for up to timeout_s."""
    import zenoh

    deadline, said = time.monotonic() + timeout_s, False
    while True:
        try:
            return zenoh.open(config)
        except Exception as exc:  # zenoh.ZError: no endpoint answered
            if time.monotonic() >= deadline:
                raise
            if not said:
                print(f"zenoh_bridge: waiting for the Zenoh endpoints ({exc})", flush=True)
                said = True
            time.sleep(0.5)


class Rules:
    def __init__(self, allow: list[str], deny: list[str]) -> None:
        self.allow = [re.compile(r) for r in allow or [".*"]]
        self.deny = [re.compile(r) for r in deny] + [re.compile(r"LCM_SELF_TEST")]  # liblcm's own probe

    def passes(self, channel: str) -> bool:
        return any(r.fullmatch(channel) for r in self.allow) and not any(r.fullmatch(channel) for r in self.deny)


class Bridge:
    def __init__(self, args) -> None:
        self.site, self.realm, self.rules = args.site, args.realm, Rules(args.allow, args.deny)
        self.stats_channel = f"SIM.LINK_STATS.ZENOH_{self.site.upper().replace('-', '_')}"
        self.n = dict(sent=0, received=0, denied_out=0, denied_in=0, echoes=0, unbridgeable=0, inbox_full=0)
        self.echoes = Echoes()
        self.inbox: queue.Queue = queue.Queue(INBOX_CAPACITY)
        self.lc = lcm.LCM(args.url)
        self.lc.subscribe(".*", self.on_lcm).set_queue_capacity(10_000)
        self.z = open_session(zenoh_config(args.mode, args.listen, args.connect), args.connect_timeout)
        self.sub = self.z.declare_subscriber(f"{self.realm}/*/lcm/**", self.on_zenoh)
        self.publishers: dict[str, object] = {}

    # Zenoh thread: hand over to the LCM thread, nothing else
    def on_zenoh(self, sample) -> None:
        parts = str(sample.key_expr).split("/", 3)
        if len(parts) != 4 or parts[2] != "lcm" or parts[1] == self.site:
            return  # our own puts come back to our own subscriber
        try:
            self.inbox.put_nowait((parts[3], sample.payload.to_bytes()))
        except queue.Full:
            self.n["inbox_full"] += 1

    # LCM thread
    def on_lcm(self, channel: str, data: bytes) -> None:
        if self.echoes.is_echo(channel, data, time.monotonic()):
            self.n["echoes"] += 1  # what we published from Zenoh: never back
            return
        if channel == self.stats_channel:
            return
        if not self.rules.passes(channel):
            self.n["denied_out"] += 1
            return
        if BAD_KEY_CHARS.search(channel) or not channel:
            self.n["unbridgeable"] += 1
            return
        pub = self.publishers.get(channel)
        if pub is None:
            pub = self.publishers[channel] = self.z.declare_publisher(f"{self.realm}/{self.site}/lcm/{channel}")
        pub.put(data)
        self.n["sent"] += 1

    def deliver(self) -> None:
        while True:
            try:
                channel, data = self.inbox.get_nowait()
            except queue.Empty:
                return
            if not self.rules.passes(channel):
                self.n["denied_in"] += 1
                continue
            self.echoes.published(channel, data, time.monotonic())
            self.lc.publish(channel, data)
            self.n["received"] += 1

    def stats(self) -> None:
        from auv import link_stats_t

        print(f"zenoh_bridge {self.site}: " + ", ".join(f"{k} {v}" for k, v in self.n.items()), flush=True)
        m = link_stats_t()
        m.utime, m.relay = int(time.time() * 1e6), f"zenoh-{self.site}"
        m.forwarded = self.n["sent"] + self.n["received"]
        m.dropped = self.n["denied_out"] + self.n["denied_in"] + self.n["unbridgeable"] + self.n["inbox_full"]
        m.duplicated, m.reordered, m.mean_delay_ms = 0, 0, 0.0
        self.lc.publish(self.stats_channel, m.encode())

    def loop(self, stop, period: float) -> None:
        print(f"zenoh_bridge {self.site}: {self.realm}/{self.site}/lcm/<CHANNEL> <-> LCM", flush=True)
        fd, next_stats = self.lc.fileno(), time.monotonic() + period
        while not stop():
            if select.select([fd], [], [], 0.005)[0]:
                self.lc.handle()
            self.deliver()
            if time.monotonic() >= next_stats:
                next_stats = time.monotonic() + period
                self.stats()
        self.stats()
        self.z.close()


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    router = bool(argv) and argv[0] == "router"
    if not router:
        ap.add_argument("--site", required=True)
        ap.add_argument("--realm", default="auv")
        programs.add_lcm_url_argument(ap, "the site's LCM URL (default $LCM_DEFAULT_URL or the project's)")
        ap.add_argument("--mode", choices=("peer", "client"), default="peer")
        ap.add_argument("--allow", action="append", default=[], help="channel regex to bridge (whole name)")
        ap.add_argument("--deny", action="append", default=[], help="channel regex never to bridge")
        ap.add_argument("--stats-period", type=float, default=5.0)
        ap.add_argument("--netns", action="store_true", help="allow ttl=1 (a network namespace made for this run)")
        ap.add_argument("--connect", action="append", default=[], help="Zenoh endpoint, e.g. tcp/10.0.0.1:7447")
        ap.add_argument(
            "--connect-timeout",
            type=float,
            default=30.0,
            help="seconds to keep trying the --connect endpoints at start (default 30)",
        )
    ap.add_argument("--listen", action="append", default=[], help="Zenoh endpoint to listen on")
    args = ap.parse_args(argv[1:] if router else argv)
    flag = {"stop": False}
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: flag.update(stop=True))
    try:
        import zenoh
    except ImportError:
        print("zenoh_bridge: the eclipse-zenoh package is not installed (requirements.txt)", file=sys.stderr)
        return 2
    if router:
        if not args.listen:
            print("zenoh_bridge: router needs --listen", file=sys.stderr)
            return 2
        z = zenoh.open(zenoh_config("router", args.listen, []))
        print(f"zenoh_bridge: router on {', '.join(args.listen)}", flush=True)
        while not flag["stop"]:
            time.sleep(0.1)
        z.close()
        return 0
    try:
        if not SITE.fullmatch(args.site) or not SITE.fullmatch(args.realm):
            raise ValueError(f"--site {args.site!r} / --realm {args.realm!r}: letters, digits, _ and - only")
        for r in args.allow + args.deny:
            try:
                re.compile(r)
            except re.error as exc:
                raise ValueError(f"bad channel regex {r!r}: {exc}") from None
        if not args.stats_period > 0:
            raise ValueError("--stats-period must be > 0")
        url = check_local(args.url or default_url(), inside_netns=args.netns or None)
    except ValueError as exc:
        print(f"zenoh_bridge: {exc}", file=sys.stderr)
        return 2
    args.url = url
    try:
        bridge = Bridge(args)
    except Exception as exc:  # zenoh: a bad endpoint, a port in use
        print(f"zenoh_bridge: cannot open the Zenoh session: {exc}", file=sys.stderr)
        return 2
    bridge.loop(lambda: flag["stop"], args.stats_period)
    return 0


if __name__ == "__main__":
    sys.exit(main())
