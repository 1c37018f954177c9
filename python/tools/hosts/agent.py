#!/usr/bin/env python3
"""Host agent: one per host, started once; runs that host's part of whatever
scenario a launcher sends over LCM (docs/hosts.md).

    auv-agent --host NAME [--lcm-url URL] [--out DIR] [--build DIR] [--netns] [--key-file FILE]

Listens on AGENT.<HOST>.CMD (agent_command_t), answers every command on
AGENT.<HOST>.ACK (agent_ack_t) and publishes its process table, with each
process's state, CPU and memory, on AGENT.<HOST>.PROCS (agent_table_t) at
1 Hz and after every change. A command for another host, a second START
while a run is active, a bad scenario or a bad restart rule is refused with
the reason in the ack and changes nothing.

With --key-file (default $AUV_KEY_FILE) every command must be signed with one
of its keys (docs/security.md): an unsigned, forged, replayed or stale one is
refused with the reason in the ack and counted in the table (auth_*).

A launcher that dies leaves the run going until a STOP, unless the START
set a dead-man time (deadman_s): then the run is stopped after that long
without any command for it (agentctl keepalives count). An agent that dies
takes its processes with it (PR_SET_PDEATHSIG): nothing is orphaned.
SIGINT/SIGTERM stop the run and end the agent (exit 0).
"""

from __future__ import annotations

import argparse
import os
import re
import signal
import sys
import time
from pathlib import Path

import lcm

from auv import agent_ack_t, agent_command_t, agent_process_t, agent_table_t
from auvlcm import auth, programs
from auvlcm.paths import ROOT, build_dir
from auvlcm.rx import Receiver
from auvlcm.url import check_local, default_url
from tools.hosts.agent_part import PartError, host_part
from tools.hosts.agent_procs import BACKOFF, RUNNING, Supervised, policy_for, rule_errors
from tools.launch.procs import stop_together
from tools.scenario.scenario_file import HOST_NAME

C = agent_command_t
TABLE_PERIOD_S = 1.0
MAX_MESSAGE = 8000  # characters of errors in one ack
MAX_CHANNEL = 63  # an LCM limit
RESULT_WORDS = ("ok", "refused", "failed")


def channels(host: str) -> tuple[str, str, str]:
    return f"AGENT.{host}.CMD", f"AGENT.{host}.ACK", f"AGENT.{host}.PROCS"


class Agent:
    def __init__(
        self, host: str, url: str, out: Path, build: Path, inside_netns: bool, key_file: Path | None = None
    ) -> None:
        self.host, self.url, self.out, self.build, self.netns = host, url, out, build, inside_netns
        self.key_file = key_file.resolve() if key_file else None  # its managers get it too
        self.verifier = auth.Verifier(auth.ring_for(key_file, f"agent {host}"))
        self.cmd_ch, self.ack_ch, self.table_ch = channels(host)
        self.lc = lcm.LCM(url)
        self.rx = Receiver(self.lc)
        self.rx.subscribe(self.cmd_ch, C, self.on_command, queue_capacity=200)
        self.run = ""
        self.status = "idle"
        self.procs: list[Supervised] = []
        self.deadman_s = 0.0
        self.last_heard = time.monotonic()
        self.acks: dict[tuple[str, int], agent_ack_t] = {}  # (sender, seq) -> answer: resends are answered again
        self.next_table = 0.0

    def log(self, text: str) -> None:
        print(f"agent {self.host}: {text}", flush=True)

    # ------------------------------------------------------------ commands
    def on_command(self, _channel: str, cmd) -> None:
        verdict = self.verifier.verify(cmd)
        if verdict != auth.OK:  # nothing of it is acted on, nor remembered
            self.answer(cmd, agent_ack_t.RESULT_REJECTED, f"refused: {auth.RESULT_TEXT[verdict]}")
            self.log(f"command from {cmd.sender!r} seq {cmd.seq} refused: {auth.RESULT_TEXT[verdict]}")
            self.publish_table()
            return
        key = (cmd.sender, cmd.seq)
        if key in self.acks and cmd.command != C.CMD_KEEPALIVE:
            self.lc.publish(self.ack_ch, self.acks[key].encode())
            return
        try:
            result, message = self.execute(cmd)
        except Exception as exc:  # an agent never dies of a command: the sender hears why
            result, message = agent_ack_t.RESULT_FAILED, f"internal error: {type(exc).__name__}: {exc}"
        ack = self.answer(cmd, result, message)
        if cmd.command != C.CMD_KEEPALIVE:
            self.acks[key] = ack
            if len(self.acks) > 1000:
                self.acks.pop(next(iter(self.acks)))
            kind = {C.CMD_START: "START", C.CMD_STOP: "STOP"}.get(cmd.command, f"command {cmd.command}")
            self.log(f"{kind} from {cmd.sender} seq {cmd.seq}: {RESULT_WORDS[result]}: {message}")
        self.publish_table()

    def answer(self, cmd, result: int, message: str) -> agent_ack_t:
        ack = agent_ack_t()
        ack.utime, ack.host, ack.sender, ack.seq = int(time.time() * 1e6), self.host, cmd.sender, cmd.seq
        ack.result, ack.message = result, message[:MAX_MESSAGE]
        self.lc.publish(self.ack_ch, ack.encode())
        return ack

    def execute(self, cmd) -> tuple[int, str]:
        if cmd.host != self.host:
            return agent_ack_t.RESULT_REJECTED, (
                f"command for host '{cmd.host}' reached the agent of host '{self.host}' on {self.cmd_ch}: refused"
            )
        if cmd.command == C.CMD_START:
            return self.start(cmd)
        if cmd.command == C.CMD_STOP:
            if cmd.run and self.run and cmd.run != self.run:
                return agent_ack_t.RESULT_REJECTED, f"no run '{cmd.run}' here (this host runs '{self.run}')"
            n = self.stop_run(f"stopped by {cmd.sender}")
            return agent_ack_t.RESULT_OK, f"stopped {n} process(es)" if n else "nothing was running"
        if cmd.command == C.CMD_KEEPALIVE:
            if cmd.run and cmd.run != self.run:
                return agent_ack_t.RESULT_REJECTED, f"no run '{cmd.run}' here ('{self.run or 'idle'}')"
            self.last_heard = time.monotonic()
            return agent_ack_t.RESULT_OK, "alive"
        return agent_ack_t.RESULT_REJECTED, f"unknown command {cmd.command}"

    def start(self, cmd) -> tuple[int, str]:
        if self.active():
            return agent_ack_t.RESULT_REJECTED, (
                f"already running '{self.run}' ({len(self.active())} process(es)); stop it first"
            )
        errors = [
            e
            for r in cmd.restart
            for e in rule_errors(r.process, r.policy, r.max_restarts, r.backoff_s, r.backoff_max_s)
        ]
        if not (cmd.deadman_s >= 0 and cmd.deadman_s < float("inf")):
            errors.append(f"deadman_s {cmd.deadman_s} is not a finite number >= 0")
        if errors:
            return agent_ack_t.RESULT_REJECTED, "\n".join(errors)
        folder = re.sub(r"[^A-Za-z0-9_.-]+", "_", cmd.run or Path(cmd.scenario_path or "scenario").stem)
        try:
            sc, specs = host_part(
                cmd.scenario_text,
                cmd.scenario_path,
                self.host,
                self.out / (folder[:63] or "run"),
                self.url,
                self.build,
                self.netns,
                self.key_file,
            )
        except PartError as exc:
            return agent_ack_t.RESULT_REJECTED, "\n".join(exc.errors)
        run = cmd.run or sc.name
        self.run, self.deadman_s, self.last_heard, self.status = run, cmd.deadman_s, time.monotonic(), "running"
        self.procs = [
            Supervised(s.name, s.cmd, s.out, policy_for(s.name, cmd.restart), self.log, s.tier) for s in specs
        ]
        started = []
        for p in self.procs:
            try:
                p.start()
            except OSError as exc:
                self.stop_run(f"{p.name} did not start: {exc}")
                return agent_ack_t.RESULT_FAILED, f"{p.name} did not start ({exc}); stopped: {', '.join(started)}"
            started.append(p.name)
        if not started:
            return agent_ack_t.RESULT_OK, f"nothing of '{run}' runs on host {self.host}"
        return agent_ack_t.RESULT_OK, f"started {len(started)} process(es) of '{run}': {', '.join(started)}"

    # ------------------------------------------------------------ supervise
    def active(self) -> list[Supervised]:
        return [p for p in self.procs if p.state in (RUNNING, BACKOFF)]

    def stop_run(self, why: str) -> int:
        n = len(self.active())
        stop_together(self.procs, timeout=5.0)  # managers first, the logger last
        if self.run:
            self.status = f"stopped: {why}"
            self.log(f"run '{self.run}' {self.status}")
        return n

    def tick(self) -> None:
        now = time.monotonic()
        changed = any([p.tick(now) for p in self.procs])
        if self.deadman_s > 0 and self.active() and now - self.last_heard > self.deadman_s:
            self.stop_run(f"dead-man: no command for {self.deadman_s:g} s")
            changed = True
        if changed or now >= self.next_table:
            self.publish_table()

    def publish_table(self) -> None:
        now = time.monotonic()
        self.next_table = now + TABLE_PERIOD_S
        t = agent_table_t()
        t.utime, t.host, t.agent_pid = int(time.time() * 1e6), self.host, os.getpid()
        t.run, t.status = self.run, self.status
        t.launcher_silent_s = now - self.last_heard if self.run else 0.0
        for p in self.procs:
            p.sample(now)
            row = agent_process_t()
            row.name, row.pid, row.state, row.exit_code, row.restarts = p.name, p.pid, p.state, p.exit_code, p.restarts
            row.cpu_load, row.rss_bytes, row.uptime_s = p.cpu_load, p.rss, p.uptime(now)
            t.procs.append(row)
        t.n_procs = len(t.procs)
        n = self.verifier.counts
        t.auth_unsigned, t.auth_unknown_key, t.auth_bad_mac = n["unsigned"], n["unknown_key"], n["bad_mac"]
        t.auth_replay, t.auth_stale = n["replay"], n["stale"]
        self.lc.publish(self.table_ch, t.encode())

    def loop(self, stop) -> None:
        self.log(f"listening on {self.cmd_ch} over {self.url}")
        self.publish_table()
        while not stop():
            try:
                self.lc.handle_timeout(100)
            except OSError:  # a signal interrupted the wait: the loop checks stop()
                pass
            self.tick()
        self.stop_run("agent ending")
        self.publish_table()


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--host", required=True, help="this host's name, as scenarios name it (hosts:)")
    programs.add_lcm_url_argument(ap, "LCM URL (default $LCM_DEFAULT_URL or the project's)")
    ap.add_argument("--out", type=Path, help="runs folder (default build/agents/<host>)")
    ap.add_argument("--build", type=Path, default=build_dir())
    ap.add_argument(
        "--netns", action="store_true", help="running in a network namespace made for this run: allows ttl=1 URLs"
    )
    auth.add_key_file_argument(ap)
    args = ap.parse_args(argv)
    if not re.fullmatch(HOST_NAME, args.host) or len(channels(args.host)[2]) > MAX_CHANNEL:
        print(
            f"agent: --host '{args.host}': letters, digits, _.- and at most "
            f"{MAX_CHANNEL - len('AGENT..PROCS')} characters",
            file=sys.stderr,
        )
        return 2
    try:
        url = check_local(args.url or default_url(), inside_netns=args.netns or None)
        if args.key_file:
            auth.load_keys(args.key_file)  # refused here, before anything listens
    except ValueError as exc:  # KeyFileError too
        print(f"agent: {exc}", file=sys.stderr)
        return 2
    out = (args.out or ROOT / "build" / "agents" / args.host).resolve()
    out.mkdir(parents=True, exist_ok=True)
    flag = {"stop": False}
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, lambda *_: flag.update(stop=True))
    Agent(args.host, url, out, args.build, args.netns or None, args.key_file).loop(lambda: flag["stop"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
