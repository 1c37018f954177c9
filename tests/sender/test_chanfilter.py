"""The kernel-side channel filter (c/common/lcm_chanfilter.c, auvlcm/chanfilter.py).

The program is checked in the kernel itself: compiled through the library,
attached to a plain UDP socket joined to the test's group, and fed crafted LCM
datagrams; what arrives is what the filter let through. Then the same through
real LCM instances: a subscription made through the filter is delivered, one
made around it is dropped by the kernel (the proof that it filters), and an
instance that cannot tell its socket from another's filters nothing.
Run inside tests/isolated_net.sh.
"""

from __future__ import annotations

import ctypes
import random
import re
import socket
import struct
import time

import lcm
import pytest

from auvlcm import chanfilter
from auvlcm.chanfilter import ChannelFilter, FilteredLcm
from auvlcm.own_socket import Rule
from auvlcm.sender import ThreadedLcm

SO_ATTACH_FILTER = 26


def compile_rules(rules: list[tuple]) -> tuple[int, ctypes.Array]:
    lib = chanfilter._load()
    assert lib is not None, "libauvlcm_sender.so is not built"
    arr = (Rule * max(1, len(rules)))()
    for i, r in enumerate(rules):
        payload = r[1] if len(r) > 1 else None
        arr[i] = Rule(r[0].encode(), payload, r[2] if len(r) > 2 else 0, len(payload) if payload else 0)
    out = ctypes.create_string_buffer(8 * 4096)
    n = lib.auv_chanfilter_compile(arr, len(rules), out, 4096)
    return n, out


def group_port(url: str) -> tuple[str, int]:
    m = re.match(r"udpm://([\d.]+):(\d+)", url)
    return m.group(1), int(m.group(2))


def short(channel: str, payload: bytes = b"") -> bytes:
    """An unfragmented LCM datagram: magic LC02, sequence number, channel, payload."""
    return b"LC02" + struct.pack(">I", 7) + channel.encode() + b"\0" + payload


def fragment(channel: str) -> bytes:
    """The first fragment of a fragmented message (LC03)."""
    return b"LC03" + struct.pack(">IIIHH", 7, 100000, 0, 0, 2) + channel.encode() + b"\0" + b"x" * 40


def passed(url: str, rules: list[tuple], datagrams: list[bytes]) -> list[bytes]:
    """The datagrams a socket with the rules' program receives, in order."""
    group, port = group_port(url)
    n, prog = compile_rules(rules)
    rx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    rx.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    rx.bind(("", port))
    rx.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, socket.inet_aton(group) + socket.inet_aton("0.0.0.0"))
    if n > 0:
        rx.setsockopt(socket.SOL_SOCKET, SO_ATTACH_FILTER, struct.pack("HL", n, ctypes.addressof(prog)))
    tx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    tx.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
    marker = b"END-OF-TEST"  # not LCM: always let through
    for d in [*datagrams, marker]:
        tx.sendto(d, (group, port))
    rx.settimeout(5.0)
    got = []
    while (d := rx.recv(70000)) != marker:
        got.append(d)
    rx.close()
    tx.close()
    return got


def participant(name: str) -> bytes:
    """lockstep_t's participant field: length with the NUL (big-endian), characters, NUL."""
    return struct.pack(">I", len(name) + 1) + name.encode() + b"\0"


def lockstep(name: str) -> bytes:
    return short("SIM.LOCKSTEP", b"F" * 8 + b"U" * 8 + participant(name) + b"\x01" + b"S" * 8)


RULES = [
    ("A_CHANNEL_NAME_LONGER_THAN_EVERY_DATAGRAM_BELOW",),  # a load past a short datagram's end must not drop it
    ("AUV1.NAV",),
    ("SIM\\.CL..K",),
    ("^AUV2\\..*$",),
    ("SIM.LOCKSTEP", participant("AUV1.sim"), 16),
    ("X",),
]
KEEP = [
    short("X"),
    short("AUV1.NAV", b"abc"),
    short("AUV1xNAV"),  # `.` is any character, as in the regex
    short("SIM.CLOCK", b"\0" * 50),
    short("SIM.CLxxK"),
    short("AUV2.NAV"),
    short("AUV2.", b"q"),
    lockstep("AUV1.sim"),
    fragment("AUV9.SONAR"),  # a fragment: liblcm decides
    b"hello",  # not LCM
    b"LC0",  # too short to judge
]
DROP = [
    short("AUV1.NAVX"),
    short("AUV1.NA"),
    short("AUV3.NAV", b"x" * 300),
    short("SIM.CLOCKS"),
    short("AUV2"),
    short("XY"),
    short("AUV1.NAV\1"),
    lockstep("AUV2.sim"),
    lockstep("AUV1.simX"),
    short("SIM.LOCKSTEP", b"F" * 8 + b"U" * 8 + participant("AUV1.sim")[:6]),  # cut short
]


def test_the_kernel_lets_through_exactly_what_the_rules_match(lcm_url):
    datagrams = KEEP + DROP
    random.Random(3).shuffle(datagrams)
    got = passed(lcm_url, RULES, datagrams)
    assert sorted(got) == sorted(KEEP)
    assert passed(lcm_url, [], datagrams) == [d for d in datagrams if d in KEEP[-3:]], "no rule: only non-LC02 passes"


@pytest.mark.parametrize("pattern", [".*", "AUV[12]\\.NAV", "A|B", "AUV\\d", "(AUV1)\\.NAV", "AUV1+", "A?"])
def test_a_pattern_that_is_not_a_name_lets_everything_through(lcm_url, pattern):
    n, _ = compile_rules([("AUV1.NAV",), (pattern,)])
    assert n == 0
    n, _ = compile_rules([("AUV1.NAV",)])
    assert n > 0


def test_never_drops_what_lcm_would_deliver_and_drops_the_rest_of_plain_names(lcm_url):
    """Random names and patterns over a small alphabet: the kernel passes every
    channel the anchored regex matches, and for patterns of literal characters
    nothing else."""
    rng = random.Random(11)
    pieces = ["A", "B", ".", "\\.", "1"]
    for _ in range(25):
        pattern = "".join(rng.choice(pieces) for _ in range(rng.randint(1, 5)))
        if rng.random() < 0.3:
            pattern += ".*"
        channels = sorted({"".join(rng.choice("AB.1") for _ in range(rng.randint(1, 7))) for _ in range(40)})
        got = {d[8:].split(b"\0")[0].decode() for d in passed(lcm_url, [(pattern,)], [short(c) for c in channels])}
        wanted = {c for c in channels if re.fullmatch(pattern, c)}
        assert wanted <= got, (pattern, wanted - got)
        if "." not in pattern.replace("\\.", ""):
            assert got == wanted, (pattern, got - wanted)


def drain(lc, seconds: float = 0.4) -> None:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        lc.handle_timeout(50)


def unfiltered(lc) -> lcm.LCM:
    """The lcm.LCM inside a FilteredLcm, or inside a ThreadedLcm's FilteredLcm."""
    while not isinstance(lc, lcm.LCM):
        lc = lc.lc
    return lc


@pytest.mark.parametrize("kind", [FilteredLcm, ThreadedLcm])
def test_a_subscription_around_the_filter_is_dropped_by_the_kernel(lcm_url, kind, monkeypatch):
    """liblcm receiving (AUV_LCM_READER=0), its socket filtered."""
    monkeypatch.setenv("AUV_LCM_READER", "0")
    got: list[str] = []
    lc = kind(lcm_url)
    lc.subscribe("AUV1.NAV", lambda c, d: got.append(c))
    unfiltered(lc).subscribe("AUV2.NAV", lambda c, d: got.append(c))  # not through the filter
    tx = lcm.LCM(lcm_url)
    for _ in range(3):
        tx.publish("AUV1.NAV", b"1")
        tx.publish("AUV2.NAV", b"2")
    drain(lc)
    assert got == ["AUV1.NAV"] * 3
    # the same with the filter off: liblcm delivers both
    monkeypatch.setenv("AUV_LCM_CHANFILTER", "0")
    got.clear()
    off = kind(lcm_url)
    off.subscribe("AUV1.NAV", lambda c, d: got.append(c))
    unfiltered(off).subscribe("AUV2.NAV", lambda c, d: got.append(c))
    for _ in range(3):
        tx.publish("AUV1.NAV", b"1")
        tx.publish("AUV2.NAV", b"2")
    drain(off)
    assert sorted(got) == ["AUV1.NAV"] * 3 + ["AUV2.NAV"] * 3
    if kind is ThreadedLcm:
        lc.close()
        off.close()


def test_later_subscriptions_widen_the_filter_and_instances_keep_their_own(lcm_url):
    a, b = FilteredLcm(lcm_url), FilteredLcm(lcm_url)
    got_a: list[str] = []
    got_b: list[str] = []
    a.subscribe("A1", lambda c, d: got_a.append(c))
    b.subscribe("B1", lambda c, d: got_b.append(c))
    a.subscribe("A2", lambda c, d: got_a.append(c))  # after the socket is known
    tx = lcm.LCM(lcm_url)
    for ch in ("A1", "A2", "B1", "C"):
        tx.publish(ch, b"")
    drain(a, 0.3)
    drain(b, 0.3)
    assert got_a == ["A1", "A2"] and got_b == ["B1"]
    assert a.filtering and b.filtering


def test_an_instance_that_cannot_tell_its_socket_filters_nothing(lcm_url):
    """Another instance makes its socket between this one's creation and its
    first subscribe: two new sockets on the port. Filtering either would risk
    the other's channels, so neither is touched."""
    mine = lcm.LCM(lcm_url)
    f = ChannelFilter(lcm_url)
    other = lcm.LCM(lcm_url)
    seen: list[str] = []
    other.subscribe(".*", lambda c, d: c != "LCM_SELF_TEST" and seen.append(c))
    f.subscribe(mine, "MINE", lambda c, d: None)
    assert not f.filtering
    tx = lcm.LCM(lcm_url)
    tx.publish("ANYTHING", b"")
    drain(other, 0.3)
    assert seen == ["ANYTHING"]
