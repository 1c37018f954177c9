#!/usr/bin/env python3
"""Launcher side of the host agents: send a scenario, stop it, show the
process tables (docs/hosts.md). No ssh: everything goes over LCM.

    auv-agentctl start SCENARIO [--host H]... [--run NAME] [--restart RULE]... [--deadman S]
    auv-agentctl stop  (SCENARIO | --host H...) [--run NAME]
    auv-agentctl status --host H... [--json]

Commands are signed with --key-file (default $AUV_KEY_FILE, else the
scenario's key_file; docs/security.md); without one they are not authenticated.

start sends the whole scenario to the agent of each of its hosts (or the
--host ones) and waits for every acknowledgement; agents then run their
parts on their own: this command may end, or die, and the runs go on (until
a stop, or the dead-man time of --deadman without a command for the run).

RULE: PATTERN=never or PATTERN=on-failure[:LIMIT[:BACKOFF_S[:MAX_S]]], first
match wins, e.g. '*.sim=on-failure:3:0.5' '*=never' (default: never restart).

Exit status: 0 every agent answered ok; 2 usage or a bad scenario (checked
here first); 3 an agent refused or failed (its message is printed);
4 an agent did not answer in time.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import socket
import sys
import time
from pathlib import Path

import lcm

from auv import agent_ack_t, agent_command_t, agent_restart_t, agent_table_t
from auvlcm import auth, programs
from auvlcm.rx import Receiver
from auvlcm.url import check_local, default_url
from confcheck import ConfigError
from tools.hosts.agent import channels
from tools.hosts.agent_procs import STATE_NAMES, rule_errors
from tools.scenario.scenario_file import load_scenario

C = agent_command_t
RULE = re.compile(r"(?P<pat>[^=]+)=(?P<pol>never|on-failure)(?::(?P<lim>\d+))?(?::(?P<b>[0-9.]+))?(?::(?P<m>[0-9.]+))?")


def parse_rule(text: str) -> agent_restart_t:
    m = RULE.fullmatch(text)
    if not m:
        raise ValueError(
            f"--restart {text!r}: expected PATTERN=never or PATTERN=on-failure[:LIMIT[:BACKOFF_S[:MAX_S]]]"
        )
    r = agent_restart_t()
    r.process, r.policy = m["pat"], int(m["pol"] == "on-failure")
    r.max_restarts = int(m["lim"] or 3)
    try:
        r.backoff_s, r.backoff_max_s = float(m["b"] or 1.0), float(m["m"] or 30.0)
    except ValueError:
        raise ValueError(f"--restart {text!r}: back-off must be a number of seconds") from None
    errs = rule_errors(r.process, r.policy, r.max_restarts, r.backoff_s, r.backoff_max_s)
    if errs:
        raise ValueError(f"--restart {text!r}: {'; '.join(errs)}")
    return r


class Control:
    """Sends commands to agents and collects their acks and tables."""

    def __init__(self, url: str, ring: auth.KeyRing | None = None) -> None:
        self.lc = lcm.LCM(url)
        self.rx = Receiver(self.lc)
        self.ring = ring
        self.sender = f"agentctl@{socket.gethostname()}:{os.getpid()}"
        self.seq = int(time.time()) % 100000 * 1000
        self.acks: dict[tuple[str, int], agent_ack_t] = {}
        self.tables: dict[str, agent_table_t] = {}
        self._subscribed: set[str] = set()

    def watch(self, host: str) -> None:
        if host in self._subscribed:
            return
        self._subscribed.add(host)
        _, ack_ch, table_ch = channels(host)
        self.rx.subscribe(
            ack_ch,
            agent_ack_t,
            lambda _c, a: self.acks.__setitem__((a.host, a.seq), a) if a.sender == self.sender else None,
            queue_capacity=200,
        )
        self.rx.subscribe(table_ch, agent_table_t, lambda _c, t: self.tables.__setitem__(t.host, t))

    def command(self, host: str, kind: int, **fields) -> agent_command_t:
        self.watch(host)
        self.seq += 1
        cmd = agent_command_t()
        cmd.utime, cmd.host, cmd.sender, cmd.seq, cmd.command = (
            int(time.time() * 1e6),
            host,
            self.sender,
            self.seq,
            kind,
        )
        cmd.run, cmd.scenario_path, cmd.scenario_text = (
            fields.get("run", ""),
            fields.get("path", ""),
            fields.get("text", ""),
        )
        cmd.deadman_s = fields.get("deadman_s", 0.0)
        cmd.restart = fields.get("restart", [])
        cmd.n_restart = len(cmd.restart)
        return cmd

    def signed(self, cmd: agent_command_t) -> bytes:
        """cmd encoded, signed afresh (a resend gets a new counter: the agent
        answers it from its table of acks instead of refusing a replay)."""
        if self.ring:
            auth.sign(cmd, self.ring, self.sender)
        return cmd.encode()

    def send_all(self, cmds: list[agent_command_t], timeout: float) -> dict[str, agent_ack_t | None]:
        """Publish each command, resend every second (agents answer a resend
        without acting twice) until every host has answered or the time is up."""
        deadline, resend = time.monotonic() + timeout, 0.0
        while time.monotonic() < deadline:
            pending = [c for c in cmds if (c.host, c.seq) not in self.acks]
            if not pending:
                break
            if time.monotonic() >= resend:
                for c in pending:
                    self.lc.publish(channels(c.host)[0], self.signed(c))
                resend = time.monotonic() + 1.0
            self.lc.handle_timeout(50)
        return {c.host: self.acks.get((c.host, c.seq)) for c in cmds}

    def wait_tables(self, hosts: list[str], timeout: float) -> None:
        for h in hosts:
            self.watch(h)
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline and not all(h in self.tables for h in hosts):
            self.lc.handle_timeout(50)


def report(answers: dict) -> int:
    worst = 0
    for host, ack in answers.items():
        if ack is None:
            print(f"{host}: no answer (is its agent running on this LCM URL?)", file=sys.stderr)
            worst = max(worst, 4)
            continue
        word = ["ok", "refused", "failed"][ack.result] if 0 <= ack.result <= 2 else str(ack.result)
        lines = ack.message.splitlines() or [""]
        out = sys.stdout if ack.result == agent_ack_t.RESULT_OK else sys.stderr
        print(f"{host}: {word}: {lines[0]}", file=out)
        for ln in lines[1:]:
            print(f"  {ln}", file=out)
        if ack.result != agent_ack_t.RESULT_OK:
            worst = max(worst, 3)
    return worst


def table_text(t: agent_table_t) -> str:
    rows = [f"{t.host}: run '{t.run or '-'}' {t.status} (agent pid {t.agent_pid})"]
    for p in t.procs:
        rows.append(
            f"  {p.name:<24} {STATE_NAMES[p.state] if 0 <= p.state < 5 else p.state:<8} pid {p.pid:>7} "
            f"cpu {100 * p.cpu_load:5.1f}%  rss {p.rss_bytes / 2**20:7.1f} MiB  "
            f"restarts {p.restarts}  exit {p.exit_code}  up {p.uptime_s:7.1f} s"
        )
    return "\n".join(rows)


def table_dict(t: agent_table_t) -> dict:
    return {
        "host": t.host,
        "run": t.run,
        "status": t.status,
        "agent_pid": t.agent_pid,
        "procs": [
            {
                "name": p.name,
                "pid": p.pid,
                "state": STATE_NAMES[p.state] if 0 <= p.state < 5 else p.state,
                "exit_code": p.exit_code,
                "restarts": p.restarts,
                "cpu_load": p.cpu_load,
                "rss_bytes": p.rss_bytes,
                "uptime_s": p.uptime_s,
            }
            for p in t.procs
        ],
    }


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=("start", "stop", "status"))
    ap.add_argument("scenario", type=Path, nargs="?")
    ap.add_argument("--host", action="append", default=[], help="an agent's host (repeat); default: the scenario's")
    ap.add_argument("--run", default="", help="run name (default: the scenario's name)")
    ap.add_argument("--restart", action="append", default=[], metavar="RULE")
    ap.add_argument(
        "--deadman",
        type=float,
        default=0.0,
        help="agents stop the run after this many seconds without a command for it (0: never)",
    )
    programs.add_lcm_url_argument(ap, "LCM URL (default $LCM_DEFAULT_URL or the project's)")
    ap.add_argument("--netns", action="store_true", help="allow ttl=1 (a network namespace made for this run)")
    ap.add_argument("--timeout", type=float, default=30.0, help="seconds to wait for every answer")
    ap.add_argument("--json", action="store_true", help="status: the tables as JSON")
    auth.add_key_file_argument(ap)
    args = ap.parse_args(argv)
    try:
        rules = [parse_rule(r) for r in args.restart]
        if not (0 <= args.deadman < float("inf")):
            raise ValueError(f"--deadman {args.deadman}: expected seconds >= 0")
        url = check_local(args.url or default_url(), inside_netns=args.netns or None)
        sc = load_scenario(args.scenario) if args.scenario else None
        key_file = args.key_file or (sc.key_file if sc else None)
        ring = auth.ring_for(key_file, "agentctl") if args.action != "status" else None
    except ConfigError as exc:  # a ValueError too: first
        print("\n".join(exc.errors), file=sys.stderr)
        print(f"agentctl: {args.scenario}: {len(exc.errors)} error(s)", file=sys.stderr)
        return 2
    except ValueError as exc:
        print(f"agentctl: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"agentctl: {exc}", file=sys.stderr)
        return 2
    hosts = args.host or (sc.hosts if sc else [])
    if not hosts or (args.action == "start" and sc is None):
        print(
            f"agentctl: {args.action}: "
            + ("needs a SCENARIO" if args.action == "start" else "needs a SCENARIO or --host"),
            file=sys.stderr,
        )
        return 2
    if sc and (unknown := [h for h in hosts if h not in sc.hosts]):
        print(
            f"agentctl: --host {', '.join(unknown)}: not among the scenario's hosts: {', '.join(sc.hosts)}",
            file=sys.stderr,
        )
        return 2
    ctl = Control(url, ring)
    if args.action == "status":
        ctl.wait_tables(hosts, args.timeout)
        missing = [h for h in hosts if h not in ctl.tables]
        found = [ctl.tables[h] for h in hosts if h in ctl.tables]
        print(
            json.dumps([table_dict(t) for t in found], indent=2)
            if args.json
            else "\n".join(table_text(t) for t in found)
        )
        for h in missing:
            print(f"{h}: no process table (is its agent running on this LCM URL?)", file=sys.stderr)
        return 4 if missing else 0
    if args.action == "start":
        cmds = [
            ctl.command(
                h, C.CMD_START, run=args.run, path=str(sc.path), text=sc.text, deadman_s=args.deadman, restart=rules
            )
            for h in hosts
        ]
    else:
        cmds = [ctl.command(h, C.CMD_STOP, run=args.run) for h in hosts]
    return report(ctl.send_all(cmds, args.timeout))


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        sys.exit(130)
