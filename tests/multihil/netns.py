"""Hosts as network namespaces on a bridge, for multi-host tests.

`ip netns add` needs to mount /run/netns, which a user namespace (where
`make test` runs: tests/isolated_net.sh) may not do. So each host is a
holder process in a fresh network namespace (`unshare -n`), joined to a
bridge in the test's own namespace by a veth pair moved by the holder's pid,
and commands run in it through `nsenter -t PID -n`. Each host gets 10.77.X.N/24
on eth0 and a multicast route there: LCM with ttl=1 reaches the other hosts
over the bridge and nothing else (the test's namespace has no way out).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import time

import pytest

from auvlcm.url import NETNS_ENV


def _run(*cmd: str) -> None:
    subprocess.run(cmd, check=True, capture_output=True, text=True)


def unavailable() -> str:
    """Why hosts cannot be built here, or '' if they can."""
    for tool in ("ip", "unshare", "nsenter"):
        if shutil.which(tool) is None:
            return f"{tool} is not installed"
    probe = subprocess.run(["unshare", "-n", "true"], capture_output=True, text=True)
    if probe.returncode != 0:
        return (
            "cannot create network namespaces here (run the test through "
            f"tests/isolated_net.sh): {probe.stderr.strip()}"
        )
    name = f"mhprobe{os.getpid() % 10000}"
    probe = subprocess.run(["ip", "link", "add", name, "type", "bridge"], capture_output=True, text=True)
    if probe.returncode != 0:
        return f"cannot create a bridge here: {probe.stderr.strip()}"
    subprocess.run(["ip", "link", "del", name], capture_output=True)
    return ""


def hosts_or_skip(count: int, subnet: int, what: str) -> Hosts:
    """count hosts, or the test skips saying why (outside tests/isolated_net.sh, or no tools)."""
    why = (
        unavailable()
        if os.environ.get("AUV_IN_ISOLATED_NET") == "1"
        else (
            "run it through tests/isolated_net.sh, so that its hosts and bridge live in a "
            "private namespace and never on the machine's own network"
        )
    )
    if why:
        pytest.skip(f"{what} needs network namespaces: {why}")
    return Hosts(count, subnet)


class Hosts:
    def __init__(self, count: int, subnet: int = 77) -> None:
        tag = os.getpid() % 1000
        self.tag, self.subnet = tag, subnet
        self.bridge = f"mhbr{tag}"
        self.holders: list[subprocess.Popen] = []
        self.veths: list[str] = []
        _run("ip", "link", "add", self.bridge, "type", "bridge", "mcast_snooping", "0")
        _run("ip", "link", "set", self.bridge, "up")
        try:
            for i in range(1, count + 1):
                self._add_host(i, tag, subnet)
        except Exception:
            self.close()
            raise

    def _add_host(self, i: int, tag: int, subnet: int) -> None:
        holder = subprocess.Popen(["unshare", "-n", "sleep", "infinity"])
        self.holders.append(holder)
        pid = str(holder.pid)
        outer, inner = f"mh{tag}h{i}", f"mh{tag}p{i}"
        _run("ip", "link", "add", outer, "type", "veth", "peer", "name", inner)
        self.veths.append(outer)
        deadline = time.monotonic() + 5.0
        # unshare must have made the namespace before the move: moving a link to
        # a pid still in our namespace "succeeds" and leaves the link here (seen
        # on a loaded machine: the host then has no such link to rename)
        ours = os.readlink("/proc/self/ns/net")
        while os.readlink(f"/proc/{pid}/ns/net") == ours:
            if time.monotonic() > deadline:
                raise RuntimeError(f"unshare -n (pid {pid}) made no network namespace within 5 s")
            time.sleep(0.02)
        while True:
            try:
                _run("ip", "link", "set", inner, "netns", pid)
                break
            except subprocess.CalledProcessError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.05)
        _run("ip", "link", "set", outer, "master", self.bridge, "up")
        for cmd in (
            ["ip", "link", "set", "lo", "up"],
            ["ip", "link", "set", inner, "name", "eth0"],
            ["ip", "addr", "add", f"10.{subnet}.{tag % 250}.{i}/24", "dev", "eth0"],
            ["ip", "link", "set", "eth0", "up", "multicast", "on"],
            ["ip", "route", "add", "224.0.0.0/4", "dev", "eth0"],
        ):
            _run("nsenter", "-t", pid, "-n", *cmd)

    def address(self, host: int) -> str:
        """Host 1..N's address on the bridge."""
        return f"10.{self.subnet}.{self.tag % 250}.{host}"

    def prefix(self, host: int) -> list[str]:
        """Command prefix that runs a program on host 1..N."""
        return ["nsenter", "-t", str(self.holders[host - 1].pid), "-n"]

    @staticmethod
    def env(base: dict) -> dict:
        """Child environment: ttl=1 is allowed there (it cannot leave the bridge)."""
        return {**base, NETNS_ENV: "1"}

    def close(self) -> None:
        for h in self.holders:
            h.kill()
            h.wait()
        for v in self.veths:
            subprocess.run(["ip", "link", "del", v], capture_output=True)
        subprocess.run(["ip", "link", "del", self.bridge], capture_output=True)
