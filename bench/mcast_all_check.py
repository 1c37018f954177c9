"""Which sockets on one port receive a datagram sent to a second multicast group
(docs/performance.md, "The next factor: groups by channel prefix").

Three sockets bound to one port, all joined to the base group 239.255.76.67:
A keeps Linux's default IP_MULTICAST_ALL = 1 (as liblcm's socket does), B sets
it to 0 and also joins 239.255.76.68, C sets it to 0. One datagram goes to each
group (ttl=0). Prints what each socket received; asserts nothing.
Run: tests/isolated_net.sh .venv/bin/python bench/mcast_all_check.py
"""

from __future__ import annotations

import socket
import struct
import time

IP_MULTICAST_ALL = 49  # linux/in.h
PORT = 7999
BASE, OTHER = "239.255.76.67", "239.255.76.68"


def receiver(groups: list[str], mc_all: int) -> socket.socket:
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    s.setsockopt(socket.IPPROTO_IP, IP_MULTICAST_ALL, mc_all)
    s.bind(("", PORT))
    for g in groups:
        mreq = struct.pack("4s4s", socket.inet_aton(g), socket.inet_aton("0.0.0.0"))
        s.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, mreq)
    s.setblocking(False)
    return s


def main() -> None:
    socks = {
        "A: IP_MULTICAST_ALL=1, base": receiver([BASE], 1),
        "B: IP_MULTICAST_ALL=0, base + other": receiver([BASE, OTHER], 0),
        "C: IP_MULTICAST_ALL=0, base": receiver([BASE], 0),
    }
    tx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    tx.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
    tx.sendto(b"to-other", (OTHER, PORT))
    tx.sendto(b"to-base", (BASE, PORT))
    time.sleep(0.1)
    for name, s in socks.items():
        got = []
        while True:
            try:
                got.append(s.recv(64).decode())
            except BlockingIOError:
                break
        print(f"{name:40s} received {', '.join(got) or 'nothing'}")


if __name__ == "__main__":
    main()
